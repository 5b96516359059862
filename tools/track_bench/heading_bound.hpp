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
// tracker must find in the reports. Told nothing instead, it can start each
// stroke where a minimum-jerk fit predicts the last one ends: what finding
// the ends from the reports leaves (StrokeBoundaries::PredictedEnds).
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "frictionfield/core/finger_kalman.hpp"
#include "frictionfield/core/report_noise.hpp"
#include "tracking_evaluation.hpp"

namespace ff::bench {

// Where each stroke starts afresh.
enum class StrokeBoundaries : uint8_t {
  ToldStandstills,  // by the truth: wherever the finger stands still
  PredictedEnds,    // told nothing: where a minimum-jerk fit says the stroke ends (stroke_end_predictor.hpp)
  TrackerEnds,      // the same, by the tracker's own predictor (core/stroke_end_predictor.hpp)
  None,             // never: each heading carried into the next stroke
};

struct HeadingBoundOptions {
  float turn_variance_per_px = 1e-4f;    // of each component of the unit heading: 0.1 rad over 100 px
  float speed_accel_noise_px_s2 = 150.0f;  // sqrt q of the filter that reads the speed
  StrokeBoundaries boundaries = StrokeBoundaries::ToldStandstills;
  // PredictedEnds: a stroke too short or too slow for the fit can still end;
  // while the speed reads below this, the heading is forgotten at this rate
  // (variance per component per second), so that it does not outlast a stop.
  float forget_below_px_s = 10.0f;
  float forget_variance_per_s = 10.0f;
};

// One stroke's heading: the core's Kalman filter (position, heading,
// wander) advanced by the distance travelled instead of time.
class StrokeHeading {
 public:
  static constexpr float kUnknownSigma = 10.0f;  // per component, around 0, for a vector of length 1

  StrokeHeading(const ReportNoise& noise, float turn_variance_per_px) : noise_(noise), turn_(turn_variance_per_px) {}
  void touch_down(Vec2 z);
  void new_stroke();  // the heading unknown again
  void forget(float variance);  // the heading less certain by this much (per component)
  void update(Vec2 z, float travelled_px, float dt_s);
  double kappa() const;
  double mu() const;  // radians
  const FingerKalman& filter() const { return k_; }

 private:
  ReportNoise noise_;
  float turn_;
  FingerKalman k_;
};

// How well the stroke ends were predicted (PredictedEnds): the standstills
// of the truth (runs of reports below kStandstillPxS), those with a predicted
// end within kPredictedEndToleranceMs of them (the replayed observer's tolerance,
// docs/tracking-research.md), the median delay from a standstill's first
// report to that end, and the predicted ends near no standstill.
constexpr double kPredictedEndToleranceMs = 40.0;
struct StrokeEndStats {
  size_t standstills = 0, found = 0, other_ends = 0;
  double median_delay_ms = NAN;
};

// One case's standstills of the truth (first and last report's scan time, s;
// not those a touch begins with, which end no stroke) and its predicted ends.
struct StrokeEndLog {
  std::vector<std::pair<double, double>> standstills;
  std::vector<double> ends;
};
StrokeEndStats stroke_end_stats(const std::vector<StrokeEndLog>& logs);

struct HeadingBoundResult {
  double heightmap_rms = 0.0, rest_rms = 0.0;  // ObserverErrors
  StrokeEndStats ends;                         // PredictedEnds and TrackerEnds only
  std::vector<StrokeEndLog> end_logs;          // per case
};

HeadingBoundResult heading_bound(const std::vector<PreparedCase>& cases, double moving_speed_px_s,
                                 const ReportNoise& noise, const HeadingBoundOptions& options = {});
inline double heading_bound_heightmap_rms(const std::vector<PreparedCase>& cases, double moving_speed_px_s,
                                          const ReportNoise& noise, const HeadingBoundOptions& options = {}) {
  return heading_bound(cases, moving_speed_px_s, noise, options).heightmap_rms;
}

}  // namespace ff::bench
