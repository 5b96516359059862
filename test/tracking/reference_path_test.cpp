// The reference a trace file is judged against: the smoother on closed forms
// and against the generated truth, the truth columns' differences, and the
// interpolation between nodes.
#include "reference_path.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "support/models/sensor_model.hpp"

namespace ff::bench {
namespace {

TEST(OfflineSmoother, RecoversAStraightLineExactly) {
  // z = 3 + 120 t sampled unevenly without noise: a constant-velocity path is
  // the smoother's own model, so every residual is zero and v = 120 px/s.
  std::vector<double> t, z, p, v;
  for (int k = 0; k < 60; ++k) {
    t.push_back(0.005 * k + 0.0003 * (k % 3));
    z.push_back(3.0 + 120.0 * t.back());
  }
  smooth_axis(t, z, SmootherOptions{}, p, v);
  for (size_t k = 0; k < t.size(); ++k) {
    EXPECT_NEAR(p[k], z[k], 1e-6) << k;
    EXPECT_NEAR(v[k], 120.0, 1e-3) << k;
  }
}

TEST(OfflineSmoother, AveragesNoiseAtRest) {
  // A resting finger seen with alternating +-1 px errors: the smoothed
  // position sits near the mean and moves far less than the reports.
  std::vector<double> t, z, p, v;
  for (int k = 0; k < 200; ++k) {
    t.push_back(0.005 * k);
    z.push_back(50.0 + (k % 2 == 0 ? 1.0 : -1.0));
  }
  smooth_axis(t, z, SmootherOptions{}, p, v);
  for (size_t k = 20; k + 20 < t.size(); ++k) EXPECT_NEAR(p[k], 50.0, 0.2) << k;
}

TEST(OfflineSmoother, NoReportsNothingSmoothed) {
  std::vector<double> p{1.0}, v{1.0};
  smooth_axis({}, {}, SmootherOptions{}, p, v);
  EXPECT_TRUE(p.empty());
  EXPECT_TRUE(v.empty());
  EXPECT_TRUE(filter_axis({}, {}, SmootherOptions{}).filtered_p.empty());
}

TEST(ReferencePath, TruthColumnsGiveCentralDifferences) {
  // x = 100 + 1000 t^2 (central differences are exact for a parabola), y fixed; a lift splits.
  std::vector<host::TraceRow> rows;
  std::vector<host::TruthPoint> truth;
  for (int k = 0; k < 5; ++k) {
    const double t = 0.01 * k;
    rows.push_back({static_cast<uint64_t>(1000000 + 10000 * k), 0.0f, 0.0f, true});
    truth.push_back({100.0 + 1000.0 * t * t, 200.0 - 500.0 * t});
  }
  rows.push_back({1050000, 0.0f, 0.0f, false});
  truth.push_back({});  // lifted: NaN
  for (int k = 6; k < 9; ++k) {  // and down again: a segment of its own
    rows.push_back({static_cast<uint64_t>(1000000 + 10000 * k), 0.0f, 0.0f, true});
    truth.push_back({300.0, 100.0 + k});
  }
  const ReferencePath path = ReferencePath::from_truth(rows, truth, 1000000);
  ASSERT_EQ(path.segments().size(), 2u);
  EXPECT_EQ(path.segments()[0].size(), 5u);
  EXPECT_EQ(path.segments()[1].size(), 3u);
  EXPECT_NEAR(path.segments()[1][0].t_s, 0.06, 1e-12);
  const std::vector<PathNode>& s = path.segments()[0];
  EXPECT_NEAR(s[2].vx, 2000.0 * 0.02, 1e-9);  // dx/dt = 2000 t
  EXPECT_NEAR(s[2].vy, -500.0, 1e-9);
  EXPECT_NEAR(s[0].vy, -500.0, 1e-9);  // one-sided at the ends: exact for a line
  EXPECT_NEAR(s[4].vy, -500.0, 1e-9);
  // At a node the interpolation is the node; past the segment the finger is up.
  const tracegen::TrueState at_node = path.at(0.02, 10.0);
  EXPECT_TRUE(at_node.touching);
  EXPECT_NEAR(at_node.position.x, 100.4, 1e-9);
  EXPECT_NEAR(at_node.velocity.x, 40.0, 1e-9);
  EXPECT_FALSE(path.at(0.045, 10.0).touching);
  // At the first node too, which has no node before it.
  EXPECT_TRUE(path.at(0.0, 10.0).touching);
  EXPECT_NEAR(path.at(0.0, 10.0).position.x, 100.0, 1e-9);
  EXPECT_NEAR(path.at(0.0, 10.0).position.y, 200.0, 1e-9);
  // Halfway between nodes 1 and 2 (t = 0.015): Hermite with exact tangents of a quadratic is exact.
  EXPECT_NEAR(path.at(0.015, 10.0).position.x, 100.0 + 1000.0 * 0.015 * 0.015, 1e-9);
}

// The runs of reports a trace is smoothed in, on rows written by hand: a
// lift and a gap longer than max_gap_s end a run; an off-screen report, a
// repeated stamp and one out of order are skipped inside it.
TEST(ReferencePath, TouchRunsSplitAtLiftsAndGapsAndSkipFaults) {
  const std::vector<host::TraceRow> rows = {
      {1000000, 10.0f, 20.0f, true},   {1005000, 11.0f, 21.0f, true},
      {1005000, 50.0f, 50.0f, true},   // the same stamp again: skipped
      {1004000, 50.0f, 50.0f, true},   // earlier: skipped
      {1010000, -3.0f, 22.0f, true},   // off the screen: skipped
      {1015000, 12.0f, 23.0f, true},   {1020000, 0.0f, 0.0f, false},  // lifted
      {1025000, 30.0f, 40.0f, true},   {1030000, 31.0f, 41.0f, true},
      {1090000, 60.0f, 70.0f, true},   // 60 ms later: a new run
      {1095000, 61.0f, 71.0f, true},
  };
  const std::vector<ReportRun> runs = touch_runs(rows, 1000000, 0.05);
  ASSERT_EQ(runs.size(), 3u);
  EXPECT_EQ(runs[0].t, (std::vector<double>{0.0, 0.005, 0.015}));
  EXPECT_EQ(runs[0].x, (std::vector<double>{10.0, 11.0, 12.0}));
  EXPECT_EQ(runs[0].y, (std::vector<double>{20.0, 21.0, 23.0}));
  EXPECT_EQ(runs[1].x, (std::vector<double>{30.0, 31.0}));
  EXPECT_EQ(runs[2].t.size(), 2u);
  EXPECT_NEAR(runs[2].t[0], 0.09, 1e-12);
  EXPECT_EQ(runs[2].y, (std::vector<double>{70.0, 71.0}));
}

// The truth's nodes skip a repeated or earlier stamp as the reports do.
TEST(ReferencePath, TruthSkipsRepeatedStamps) {
  const std::vector<host::TraceRow> rows = {{1000000, 0.0f, 0.0f, true},
                                            {1010000, 0.0f, 0.0f, true},
                                            {1010000, 0.0f, 0.0f, true},
                                            {1005000, 0.0f, 0.0f, true},
                                            {1020000, 0.0f, 0.0f, true}};
  const std::vector<host::TruthPoint> truth = {{0.0, 0.0}, {1.0, 0.0}, {9.0, 9.0}, {9.0, 9.0}, {2.0, 0.0}};
  const ReferencePath path = ReferencePath::from_truth(rows, truth, 1000000);
  ASSERT_EQ(path.segments().size(), 1u);
  ASSERT_EQ(path.segments()[0].size(), 3u);
  EXPECT_EQ(path.segments()[0][1].x, 1.0);
  EXPECT_EQ(path.segments()[0][2].x, 2.0);
  EXPECT_NEAR(path.segments()[0][1].vx, 100.0, 1e-9);  // (2 - 0) / 0.02 s
}

// Between two touches (and before the first, after the last) the finger is
// where it was seen nearest in time: the end of one segment or the start of
// the next. A touch of one report has no path to smooth.
TEST(ReferencePath, BetweenTouchesTheFingerIsWhereItWasSeenNearest) {
  std::vector<host::TraceRow> rows;
  for (int k = 0; k < 5; ++k) rows.push_back({static_cast<uint64_t>(1000000 + 5000 * k), 10.0f + k, 20.0f, true});
  rows.push_back({1030000, 0.0f, 0.0f, false});
  rows.push_back({1040000, 300.0f, 300.0f, true});  // a touch of one report
  rows.push_back({1045000, 0.0f, 0.0f, false});
  for (int k = 0; k < 5; ++k) rows.push_back({static_cast<uint64_t>(1100000 + 5000 * k), 100.0f + k, 50.0f, true});
  const ReferencePath path = ReferencePath::smoothed(rows, 1000000, SmootherOptions{});
  ASSERT_EQ(path.segments().size(), 2u);
  const auto at = [&](double t_s) { return path.at(t_s, 10.0); };
  EXPECT_FALSE(at(0.03).touching);
  EXPECT_NEAR(at(0.03).position.x, path.segments()[0].back().x, 1e-9);   // 10 ms after the first, 70 before the next
  EXPECT_NEAR(at(0.09).position.x, path.segments()[1].front().x, 1e-9);  // 70 ms after, 10 before
  EXPECT_NEAR(at(-0.5).position.x, path.segments()[0].front().x, 1e-9);
  EXPECT_NEAR(at(2.0).position.x, path.segments()[1].back().x, 1e-9);
  EXPECT_NEAR(path.segments()[0].back().x, 14.0, 0.1);
  EXPECT_NEAR(path.segments()[1].front().x, 100.0, 0.1);
}

TEST(ReferencePath, SmootherStaysCloseToTheGeneratedTruth) {
  // Against the motion model's own truth (independent of the smoother):
  // within half a pixel and a few degrees at low noise, a pixel and ~9 degrees at high.
  for (double noise : {tracegen::kNoiseLowPx, tracegen::kNoiseHighPx}) {
    tracegen::TraceOptions o;
    o.seed = 5;
    o.motion.duration_s = 20.0;
    o.sensor.noise_px = noise;
    o.sensor.quantum_px = tracegen::kZForceQuantumPx;
    const tracegen::GeneratedTrace trace = tracegen::generate_trace(o);
    std::vector<host::TraceRow> rows;
    for (const tracegen::TraceSample& s : trace.samples)
      rows.push_back({s.t_us, static_cast<float>(s.x), static_cast<float>(s.y), s.touch});
    const ReferencePath path = ReferencePath::smoothed(rows, trace.start_us, SmootherOptions{});
    double position_sq = 0.0, angle_sq = 0.0;
    int n = 0;
    for (uint64_t t = trace.start_us; t < trace.end_us(); t += 500) {
      const tracegen::TrueState truth = trace.truth_at(t);
      const double speed = std::hypot(truth.velocity.x, truth.velocity.y);
      const tracegen::TrueState e = path.at(static_cast<double>(t - trace.start_us) * 1e-6, 10.0);
      if (!truth.touching || speed < 50.0 || !e.touching) continue;
      position_sq += std::pow(e.position.x - truth.position.x, 2) + std::pow(e.position.y - truth.position.y, 2);
      const double c = (e.velocity.x * truth.velocity.x + e.velocity.y * truth.velocity.y) /
                       (speed * std::hypot(e.velocity.x, e.velocity.y));
      angle_sq += std::pow(std::acos(std::fmax(-1.0, std::fmin(1.0, c))) * 180.0 / M_PI, 2);
      ++n;
    }
    ASSERT_GT(n, 10000);
    const double position_rms = std::sqrt(position_sq / n), angle_rms = std::sqrt(angle_sq / n);
    std::printf("[smoother] noise %.1f px: position RMS %.3f px, direction RMS %.2f deg over %d ticks\n", noise,
                position_rms, angle_rms, n);
    EXPECT_LT(position_rms, noise < 2.0 ? 0.6 : 1.2);
    EXPECT_LT(angle_rms, noise < 2.0 ? 5.0 : 10.0);
  }
}

}  // namespace
}  // namespace ff::bench
