#pragma once
// What knowing when each stroke starts would buy (issue 14): the heightmap
// error of an observer told only when the finger stands still (by the
// truth, at each report's scan time), which learns where each stroke goes
// from the reports alone. Its finger model has a heading that turns with
// the distance travelled, not with time: the finger moves `travelled` px
// along the heading u between reports and u turns by white noise per px,
// the distance from a constant-velocity filter's speed on the same reports
// (the core's FingerKalman). A speed read too low or too high only rescales
// u, not its direction. At each standstill the heading is unknown again
// (the position and the wander's estimate are kept, and no distance is
// travelled there, so a rest averages its reports into the next stroke's
// anchor). As the floor (direction_bound.hpp), it renders the amplitude's
// posterior mean over a von Mises heading (kappa = |u| / its variance) at
// the true position. Not a tracker: it is told the standstills, which a
// tracker must find in the reports.
#include <vector>

#include "frictionfield/core/finger_kalman.hpp"
#include "frictionfield/core/report_noise.hpp"
#include "tracking_evaluation.hpp"

namespace ff::bench {

struct HeadingBoundOptions {
  float turn_variance_per_px = 1e-4f;    // of each component of the unit heading: 0.1 rad over 100 px
  float speed_accel_noise_px_s2 = 150.0f;  // sqrt q of the filter that reads the speed
  bool told_standstills = true;  // false: never told, each heading carried into the next stroke
};

// One stroke's heading: the core's Kalman filter (position, heading,
// wander) advanced by the distance travelled instead of time.
class StrokeHeading {
 public:
  static constexpr float kUnknownSigma = 10.0f;  // per component, around 0, for a vector of length 1

  StrokeHeading(const ReportNoise& noise, float turn_variance_per_px) : noise_(noise), turn_(turn_variance_per_px) {}
  void touch_down(Vec2 z);
  void new_stroke();  // the heading unknown again
  void update(Vec2 z, float travelled_px, float dt_s);
  double kappa() const;
  double mu() const;  // radians
  const FingerKalman& filter() const { return k_; }

 private:
  ReportNoise noise_;
  float turn_;
  FingerKalman k_;
};

double heading_bound_heightmap_rms(const std::vector<PreparedCase>& cases, double moving_speed_px_s,
                                   const ReportNoise& noise, const HeadingBoundOptions& options = {});

}  // namespace ff::bench
