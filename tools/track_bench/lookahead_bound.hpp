#pragma once
// What knowing the future would buy (issue 14): the heightmap error of a
// constant-velocity Kalman smoother that, at each tick, has seen every report
// up to `lookahead` after it -- a fixed-lag smoother: no lookahead is the
// causal filter, an unbounded one the Rauch-Tung-Striebel smoother of the
// whole stroke (reference_path.hpp). Its direction is rendered at full length
// whenever the finger moves (a perfect motion oracle) and its acceleration
// noise is the best of a grid for each class and lookahead. Not a tracker: a
// bound that shows how much of a causal tracker's error is the future it
// cannot see (starts, stops, reversals) rather than the reports' noise.
#include <cmath>
#include <cstdint>
#include <iosfwd>
#include <iterator>
#include <string>
#include <vector>

#include "heading_bound.hpp"
#include "reference_path.hpp"
#include "tracking_evaluation.hpp"

namespace ff::bench {

struct AxisState {
  double p = 0.0, v = 0.0;
};

// One axis of the fixed-lag smoother over one run of reports, the pass's
// times those of the scans, each report stamped (seen) latency_s later.
class FixedLagAxis {
 public:
  // lookahead_s = INFINITY: the whole run (the RTS smoother).
  FixedLagAxis(AxisPass pass, double lookahead_s, double latency_s = 0.0);
  // The finger at scan time t_s (not before the run's first report), from
  // every report stamped by t_s + lookahead: smoothed at the last of them
  // scanned at or before t_s, then predicted to t_s at constant velocity.
  // Calls in increasing t_s reuse the last step.
  AxisState at(double t_s);

 private:
  AxisPass pass_;
  double lookahead_s_, latency_s_;
  std::vector<double> smoothed_p_, smoothed_v_;  // unbounded lookahead only
  size_t cached_k_ = SIZE_MAX, cached_m_ = SIZE_MAX;
  AxisState cached_;
};

// RMS of |A - A_ideal| over the moving ticks a tracker would have tracked
// (inside a run of reports, as Metrics::heightmap_rms counts them), the
// reports dated latency_s before their stamps. Anchored (causal only): the
// filter is also told when the finger stands still (filter_axis'
// `standstill`, from the truth at each report's dated scan time): what a
// tracker with a resting mode and a perfect start detector could do.
enum class BoundModel : uint8_t { ConstantVelocity, AnchoredAtRest };
double lookahead_heightmap_rms(const std::vector<PreparedCase>& cases, double moving_speed_px_s,
                               const SmootherOptions& smoother, double latency_s, double lookahead_s,
                               BoundModel model = BoundModel::ConstantVelocity);

constexpr double kLookaheadsMs[] = {0.0, 10.0, 30.0, 100.0, INFINITY};
// The grid of white-acceleration densities (px^2/s^3) the bound picks from.
constexpr double kLookaheadAccelNoise[] = {3e1, 1e2, 3e2, 1e3, 3e3, 1e4, 3e4, 1e5, 3e5, 1e6};

struct LookaheadRow {
  std::string trace_class;
  double thesis_heightmap_rms = 0.0;
  double tracker_heightmap_rms = 0.0;
  double best_rms[std::size(kLookaheadsMs)] = {};
  double best_accel_noise[std::size(kLookaheadsMs)] = {};
  double anchored_rms = 0.0;  // BoundModel::AnchoredAtRest, causal, at its best acceleration noise
  double anchored_accel_noise = 0.0;
  double heading_bound_rms = NAN;    // heading_bound.hpp: told when each stroke starts; NaN: not measured
  double direction_bound_rms = NAN;  // direction_bound.hpp: told all but where each stroke goes; NaN: not measured
  HeadingBoundResult predicted_ends{NAN, NAN, {}, {}};  // heading_bound.hpp, StrokeBoundaries::PredictedEnds
  HeadingBoundResult tracker_ends{NAN, NAN, {}, {}};    // StrokeBoundaries::TrackerEnds
};
// Every lookahead, and the anchored causal bound, at its best acceleration noise; the measurement noise is
// the profile's white and correlated noise together.
LookaheadRow lookahead_row(const std::string& trace_class, const std::vector<PreparedCase>& cases,
                           double moving_speed_px_s, double white_noise_px, double correlated_noise_px,
                           double latency_s);
void write_lookahead_report(std::ostream& out, const std::vector<LookaheadRow>& rows);
// The heading model told nothing, its strokes ended where a minimum-jerk fit predicts (issue 14).
void write_predicted_ends_report(std::ostream& out, const std::vector<LookaheadRow>& rows);

}  // namespace ff::bench
