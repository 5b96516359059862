#pragma once
// Where the finger was, for judging trackers on a trace file: the file's own
// truth columns (x_true, y_true: ff-tracegen, or a motion-capture reference),
// or, for a recording without them, an offline estimate from the reports
// themselves. The estimate is a Rauch-Tung-Striebel smoother (constant-
// velocity model per axis): it sees every report before and after each
// instant, so it has no lag and far less noise than any causal tracker, but
// it is not ground truth: errors measured against it are relative to the
// best non-causal estimate.
#include <cstdint>
#include <vector>

#include "frictionfield/host/trace_csv.hpp"
#include "support/models/motion.hpp"

namespace ff::bench {

struct PathNode {
  double t_s = 0.0;  // since the trace's first report
  double x = 0.0, y = 0.0, vx = 0.0, vy = 0.0;
};

struct SmootherOptions {
  double accel_noise_px2_s3 = 1.0e5;  // white-acceleration spectral density q
  double measurement_noise_px = 1.5;  // 1 sigma per axis (zForce: ~0.3 mm)
  double max_gap_s = 0.05;            // a longer gap between reports splits the stroke
};

class ReferencePath {
 public:
  // From truth columns: consecutive finite truth points (time strictly
  // increasing) form a segment; velocity by central differences.
  static ReferencePath from_truth(const std::vector<host::TraceRow>& rows, const std::vector<host::TruthPoint>& truth,
                                  uint64_t t0_us);
  // From the reports alone: touch reports on the screen, time strictly
  // increasing, split at lifts and gaps, each segment smoothed.
  static ReferencePath smoothed(const std::vector<host::TraceRow>& rows, uint64_t t0_us, const SmootherOptions& options);

  // The finger at t (s since the first report): touching inside a segment,
  // position and velocity by cubic Hermite interpolation of the nodes;
  // resting when slower than `rest_speed_px_s`. Between segments: not
  // touching, at the nearest segment end (so a time shift near a lift or a
  // gap compares with where the finger was, not with the origin).
  tracegen::TrueState at(double t_s, double rest_speed_px_s) const;
  const std::vector<std::vector<PathNode>>& segments() const { return segments_; }

 private:
  std::vector<std::vector<PathNode>> segments_;  // each sorted by time, >= 2 nodes
};

// The touch reports of a recording as runs: touch reports on the screen
// (finite, inside 0..kScreenMax), time strictly increasing (duplicates and
// out-of-order stamps skipped), split at each lift (touch = 0) and at each gap
// longer than max_gap_s. Times in s since t0_us. `skipped`, if given, counts
// the touch rows left out, so that a refusal can say why.
struct ReportRun {
  std::vector<double> t, x, y;
};
struct SkippedReports {
  size_t off_screen = 0;  // not finite or outside 0..kScreenMax
  size_t not_after = 0;   // stamped at or before the report before it
};
std::vector<ReportRun> touch_runs(const std::vector<host::TraceRow>& rows, uint64_t t0_us, double max_gap_s,
                                  SkippedReports* skipped = nullptr);

// One axis of a constant-velocity RTS smoother (exposed for its test):
// positions z at times t (s, increasing) -> smoothed position and velocity.
void smooth_axis(const std::vector<double>& t, const std::vector<double>& z, const SmootherOptions& options,
                 std::vector<double>& position, std::vector<double>& velocity);

// The smoother in two halves, for a fixed-lag smoother (lookahead_bound.hpp):
// the forward Kalman filter's predicted and filtered state at every report,
// and one step of the backward (Rauch-Tung-Striebel) pass.
//
// With `standstill` (one flag per report, from a motion oracle) the filter
// is told when the finger stands still: there its velocity is exactly 0 and
// its position the mean of the reports since the stop, so that a start
// begins from a settled anchor; at the first report after a standstill the
// velocity is unknown again (1 sigma kStartSpeedSigmaPxS). Forward pass only:
// its covariances at a standstill are singular, so no smooth_step over them.
struct AxisCov {
  double pp = 0.0, pv = 0.0, vv = 0.0;  // 2 x 2 symmetric covariance of (position, velocity)
};
struct AxisPass {
  std::vector<double> t;
  std::vector<double> predicted_p, predicted_v, filtered_p, filtered_v;
  std::vector<AxisCov> predicted_cov, filtered_cov;
};
constexpr double kStartSpeedSigmaPxS = 1000.0;
AxisPass filter_axis(const std::vector<double>& t, const std::vector<double>& z, const SmootherOptions& options,
                     const std::vector<bool>* standstill = nullptr);
// The smoothed state at report k from the smoothed state (p, v) at k + 1 (in place).
void smooth_step(const AxisPass& pass, size_t k, double& p, double& v);
// The whole backward pass: the smoothed state at every report.
void smooth_pass(const AxisPass& pass, std::vector<double>& position, std::vector<double>& velocity);

}  // namespace ff::bench
