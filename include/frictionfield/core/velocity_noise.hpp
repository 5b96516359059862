#pragma once
// How fast a resting finger seems to move: the velocity the tracker's
// direction filter (finger_kalman.hpp), settled, reads from the sensor's
// noise and the finger's tremor alone. The direction confidence measures
// speeds in units of it (docs/tracking.md#direction-confidence). Computed
// once per configuration, not per tick.
#include "frictionfield/core/finger_kalman.hpp"
#include "frictionfield/core/report_noise.hpp"
#include "frictionfield/core/sensor_profile.hpp"

namespace ff {

struct SteadyStateFilter {
  FingerKalman::Gains gains;       // per report
  float velocity_variance = 0.0f;  // P11 after an update, px^2/s^2
  float interval_s = 0.0f;         // the reports' mean interval
  float wander_correlation = 0.0f; // the filter's phi over that interval
  bool tremor = false;             // with the tremor's states (ReportNoise::with_tremor)
  TremorModel::Step tremor_step{}; // their step over that interval
};

// The filter (white acceleration of density accel_q, px^2/s^3, reports
// weighed by `noise`) after many reports at the profile's mean interval.
SteadyStateFilter steady_state_filter(float accel_q, const ReportNoise& noise, const SensorProfile& sensor);

// Per axis, px^2/s^2: the variance of that filter's velocity for a finger at
// rest: the white noise and the wander (exact: the stationary covariance of
// filter and wander together) plus the tremor (its sinusoid through the
// filter's frequency response, at the worst frequency of its TremorBand), whether
// or not the filter carries the tremor as a state.
float resting_velocity_variance(const SteadyStateFilter& filter, const SensorProfile& sensor);

}  // namespace ff
