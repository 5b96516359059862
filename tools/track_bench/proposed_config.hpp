#pragma once
// The tracker constants ff-track-bench tunes (docs/tracking.md): the finger's
// acceleration density for the direction and the position filter and the
// direction confidence's fade and the detection of changes of motion; the sensor's side comes from its SensorProfile.
#include "frictionfield/core/tracker.hpp"

namespace ff::bench {

struct ProposedConstants {
  float direction_accel_px_s2;  // KalmanConfig of the direction filter
  float position_accel_px_s2;   // KalmanConfig of the position filter
  float rest_sigmas;
  float moving_sigmas;
  float maneuver_threshold;
  float maneuver_time_ms;
};

// recommended()'s own constants.
inline ProposedConstants recommended_constants() {
  const TrackerConfig r = TrackerConfig::recommended();
  return {r.kalman.accel_noise_px_s2, r.position_kalman.accel_noise_px_s2, r.rest_sigmas, r.moving_sigmas,
          r.maneuver_threshold, r.maneuver_time_ms};
}

// recommended(sensor) with these constants.
inline TrackerConfig proposed_tracker(const ProposedConstants& c, const SensorProfile& sensor = SensorProfile{}) {
  TrackerConfig t = TrackerConfig::recommended(sensor);
  t.kalman.accel_noise_px_s2 = c.direction_accel_px_s2;
  t.position_kalman.accel_noise_px_s2 = c.position_accel_px_s2;
  t.rest_sigmas = c.rest_sigmas;
  t.moving_sigmas = c.moving_sigmas;
  t.maneuver_threshold = c.maneuver_threshold;
  t.maneuver_time_ms = c.maneuver_time_ms;
  return t;
}

}  // namespace ff::bench
