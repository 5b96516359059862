// The fixed-lag smoother behind ff-track-bench's lookahead bound: closed
// forms on noiseless constant-velocity paths (the model's own, so every
// innovation is zero), a stop seen only once it is inside the lookahead, the
// unbounded lookahead equal to the whole-run smoother, the filter told when
// the finger stands still (a running mean there, a start from it), and on a
// generated class what more lookahead, the latency's dating and the anchor buy.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "class_report.hpp"
#include "lookahead_bound.hpp"
#include "support/models/trace_classes.hpp"
#include "support/text_lines.hpp"

namespace ff::bench {
namespace {

// x = 20 + 100 t until t_stop, then at rest; reports every 5 ms, noiseless.
AxisPass stopping_finger(double t_stop, double duration_s) {
  std::vector<double> t, z;
  for (int k = 0; 0.005 * k <= duration_s + 1e-9; ++k) {
    t.push_back(0.005 * k);
    z.push_back(20.0 + 100.0 * std::min(t.back(), t_stop));
  }
  return filter_axis(t, z, SmootherOptions{});
}

TEST(FixedLagSmoother, CausalFollowsAConstantVelocityExactlyAndPredictsBetweenReports) {
  FixedLagAxis axis(stopping_finger(10.0, 1.0), 0.0);
  for (double t : {0.3, 0.3025, 0.6013, 0.9999}) {
    const AxisState s = axis.at(t);
    EXPECT_NEAR(s.v, 100.0, 1e-3) << t;
    EXPECT_NEAR(s.p, 20.0 + 100.0 * t, 1e-4) << t;  // predicted from the last report at 100 px/s
  }
}

TEST(FixedLagSmoother, SeesAStopOnlyOnceItIsInsideTheLookahead) {
  // Stop at 0.5 s. At 0.45 s a 30 ms lookahead reaches 0.48 s: still moving,
  // the estimate exact. At 0.49 s it reaches 0.52 s: the stop pulls the
  // velocity down; the causal filter still reads 100 px/s.
  const AxisPass pass = stopping_finger(0.5, 1.0);
  FixedLagAxis causal(pass, 0.0), ahead(pass, 0.030);
  EXPECT_NEAR(ahead.at(0.45).v, 100.0, 1e-3);
  EXPECT_NEAR(causal.at(0.49).v, 100.0, 1e-3);
  EXPECT_LT(ahead.at(0.49).v, 95.0);
  // Long after the stop both agree that the finger rests where it stopped.
  EXPECT_NEAR(causal.at(0.99).p, 70.0, 0.05);
  EXPECT_NEAR(ahead.at(0.99).v, 0.0, 0.5);
}

TEST(FixedLagSmoother, AReportIsSeenWhenStampedNotWhenScanned) {
  // The same stop at 0.5 s (scan time), each report stamped 10 ms late. At
  // 0.475 s a 30 ms lookahead has seen stamps up to 0.505 s: scans up to
  // 0.495 s, all before the stop, so the estimate is still exact (dated by
  // the scan, the reports up to 0.505 s would already show the stop). At
  // 0.49 s no lookahead has seen the scan of 0.485 s yet: predicted from 0.48 s.
  const AxisPass pass = stopping_finger(0.5, 1.0);
  FixedLagAxis late(pass, 0.030, 0.010), causal(pass, 0.0, 0.010);
  EXPECT_NEAR(late.at(0.475).v, 100.0, 1e-3);
  EXPECT_LT(FixedLagAxis(pass, 0.030).at(0.475).v, 99.0);  // stamped as scanned: sees 0.505 s
  EXPECT_LT(late.at(0.485).v, 99.0);  // sees stamps up to 0.515 s: the scans after the stop
  const AxisState s = causal.at(0.49);
  EXPECT_NEAR(s.v, 100.0, 1e-3);
  EXPECT_NEAR(s.p, 20.0 + 100.0 * 0.49, 1e-4);
}

TEST(FixedLagSmoother, ALookaheadPastTheRunIsTheWholeRunSmoother) {
  // The finite lookahead walks back from the run's last report at every
  // call; the unbounded one is the smoother of reference_path.hpp.
  std::vector<double> t, z;
  for (int k = 0; k < 120; ++k) {
    t.push_back(0.005 * k + 0.0007 * (k % 4));
    z.push_back(50.0 + 30.0 * std::sin(7.0 * t.back()) + ((k * 37) % 11 - 5) * 0.3);  // curved, with noise
  }
  std::vector<double> p, v;
  smooth_axis(t, z, SmootherOptions{}, p, v);
  FixedLagAxis far(filter_axis(t, z, SmootherOptions{}), 10.0), whole(filter_axis(t, z, SmootherOptions{}), INFINITY);
  for (size_t k = 0; k < t.size(); k += 7) {
    EXPECT_NEAR(far.at(t[k]).p, p[k], 1e-6) << k;
    EXPECT_NEAR(far.at(t[k]).v, v[k], 1e-5) << k;
    EXPECT_NEAR(whole.at(t[k]).v, v[k], 1e-9) << k;
  }
}

TEST(AnchoredFilter, AveragesAtAStandstillAndStartsFromTheMean) {
  // 40 reports at rest around 10 px, then a start at 100 px/s, every 5 ms.
  std::vector<double> t, z;
  std::vector<bool> still;
  for (int k = 0; k < 60; ++k) {
    t.push_back(0.005 * k);
    z.push_back(k < 40 ? 10.0 + 0.6 * (k % 3 - 1) + 0.05 * (k % 7) : 10.0 + 100.0 * 0.005 * (k - 39));
    still.push_back(k < 40);
  }
  SmootherOptions options;
  options.measurement_noise_px = 1.0;
  options.accel_noise_px2_s3 = 3e3;
  const AxisPass pass = filter_axis(t, z, options, &still);
  // At rest: the velocity exactly 0, the position the mean of the reports so
  // far.
  double sum = 0.0;
  for (int k = 0; k < 40; ++k) {
    sum += z[k];
    EXPECT_EQ(pass.filtered_v[k], 0.0) << k;
    EXPECT_NEAR(pass.filtered_p[k], sum / (k + 1), 1e-9) << k;
    EXPECT_NEAR(pass.filtered_cov[k].pp, 1.0 / (k + 1), 1e-9) << k;
  }
  // The first moving report: the velocity unknown (kStartSpeedSigmaPxS),
  // so it is nearly the step from the anchor over one interval. By hand:
  // P = [pp + dt^2 s^2 + q dt^3 / 3, dt s^2 + q dt^2 / 2; ...], v = P01 (z - anchor) / (P00 + r).
  const double anchor = sum / 40.0, pp = 1.0 / 40.0, dt = 0.005, s2 = kStartSpeedSigmaPxS * kStartSpeedSigmaPxS;
  const double q = options.accel_noise_px2_s3;
  const double expected_v =
      (dt * s2 + q * dt * dt / 2.0) * (z[40] - anchor) / (pp + dt * dt * s2 + q * dt * dt * dt / 3.0 + 1.0);
  EXPECT_NEAR(pass.filtered_v[40], expected_v, 1e-9 * std::fabs(expected_v));
  // Without the oracle the same filter has not learned that the finger rests.
  const AxisPass plain = filter_axis(t, z, options);
  EXPECT_NE(plain.filtered_v[20], 0.0);
}

// A stop told by the oracle: from the first still report the velocity is
// exactly 0, however fast the finger was moving before it.
TEST(AnchoredFilter, AStopHoldsTheVelocityAtZero) {
  std::vector<double> t, z;
  std::vector<bool> still;
  for (int k = 0; k < 40; ++k) {
    t.push_back(0.005 * k);
    z.push_back(k < 20 ? 2.0 * k : 40.0 + 0.3 * (k % 2));
    still.push_back(k >= 20);
  }
  SmootherOptions options;
  options.measurement_noise_px = 1.0;
  options.accel_noise_px2_s3 = 3e3;
  const AxisPass pass = filter_axis(t, z, options, &still);
  EXPECT_GT(pass.filtered_v[19], 300.0);  // 400 px/s
  for (int k = 20; k < 40; ++k) EXPECT_EQ(pass.filtered_v[k], 0.0) << k;
}

std::vector<PreparedCase> class_traces(const char* name, double duration_s) {
  std::vector<PreparedCase> cases;
  for (const TrackCase& c : class_cases(*tracegen::find_trace_class(name), duration_s)) cases.push_back(prepare_case(c));
  return cases;
}

TEST(LookaheadBound, MoreOfTheFutureLessError) {
  // Each step sees the stroke's changes (starts, stops, reversals) sooner.
  const std::vector<PreparedCase> cases = class_traces("latency", 4.0);
  const SensorProfile sensor = tracegen::nominal_profile(cases.front().spec.options);
  ASSERT_GT(sensor.latency_us, 1000u);
  SmootherOptions smoother;
  smoother.accel_noise_px2_s3 = 3e3;
  smoother.measurement_noise_px = 1.0;
  double previous = 1.0;
  for (double ms : {0.0, 10.0, 30.0, 100.0}) {
    const double rms = lookahead_heightmap_rms(cases, kClassMovingSpeedPxS, smoother, sensor.latency_us * 1e-6, ms * 1e-3);
    EXPECT_GT(rms, 0.0) << ms;
    EXPECT_LT(rms, 0.95 * previous) << ms;
    previous = rms;
  }
}

// Told the latency, the bound dates each report when it was scanned and
// uses it once it is stamped: reports stamped 20 ms late are the on-time
// reports seen 20 ms later (a lookahead 20 ms shorter), but for the ticks
// of each touch's first 20 ms, before its first report is stamped.
TEST(LookaheadBound, ReportsAreDatedWhenScannedAndSeenWhenStamped) {
  const std::vector<PreparedCase> cases = class_traces("white-200hz", 4.0);
  std::vector<PreparedCase> late = class_traces("white-200hz", 4.0);
  for (PreparedCase& c : late)
    for (tracegen::TraceSample& s : c.trace.samples) s.t_us += 20000;
  SmootherOptions smoother;
  smoother.accel_noise_px2_s3 = 3e3;
  smoother.measurement_noise_px = 1.0;
  for (double lookahead_s : {0.0, 0.03}) {
    const double seen_later = lookahead_heightmap_rms(cases, kClassMovingSpeedPxS, smoother, 0.0, lookahead_s - 0.02);
    EXPECT_NEAR(lookahead_heightmap_rms(late, kClassMovingSpeedPxS, smoother, 0.02, lookahead_s), seen_later,
                0.02 * seen_later)
        << lookahead_s;
  }
}

// Ticks after the last report (a trace that ends while the truth goes on)
// are not judged: the same as a case whose ticks end there too.
TEST(LookaheadBound, TicksAfterTheLastReportAreNotJudged) {
  // Both lose the second half of their reports; `trimmed` also its ticks
  // after the last report (and its allowed gap).
  std::vector<PreparedCase> cut = class_traces("white-200hz", 4.0), trimmed = class_traces("white-200hz", 4.0);
  SmootherOptions smoother;
  smoother.accel_noise_px2_s3 = 3e3;
  smoother.measurement_noise_px = 1.0;
  for (std::vector<PreparedCase>* cases : {&cut, &trimmed})
    for (PreparedCase& c : *cases) c.trace.samples.resize(c.trace.samples.size() / 2);
  for (PreparedCase& c : trimmed) {
    const uint64_t end_us = c.trace.samples.back().t_us + static_cast<uint64_t>(smoother.max_gap_s * 1e6);
    while (!c.ticks.empty() && c.ticks.back().t_us > end_us) c.ticks.pop_back();
  }
  const double rms = lookahead_heightmap_rms(cut, kClassMovingSpeedPxS, smoother, 0.0, 0.0);
  EXPECT_GT(rms, 0.0);
  EXPECT_DOUBLE_EQ(rms, lookahead_heightmap_rms(trimmed, kClassMovingSpeedPxS, smoother, 0.0, 0.0));
}

TEST(LookaheadBound, TheTablePicksTheBestAccelerationNoisePerLookahead) {
  const std::vector<PreparedCase> cases = class_traces("white-200hz", 3.0);
  LookaheadRow row = lookahead_row("white-200hz", cases, kClassMovingSpeedPxS, 1.0, 0.0, 0.0);
  SmootherOptions smoother;
  smoother.measurement_noise_px = 1.0;
  // The least of the grid, and where it is.
  const auto expect_best = [&](double lookahead_s, BoundModel model, double rms, double accel_noise) {
    double least = INFINITY, at = NAN;
    for (double q : kLookaheadAccelNoise) {
      smoother.accel_noise_px2_s3 = q;
      const double r = lookahead_heightmap_rms(cases, kClassMovingSpeedPxS, smoother, 0.0, lookahead_s, model);
      if (r < least) {
        least = r;
        at = q;
      }
    }
    EXPECT_GT(least, 0.0);
    EXPECT_EQ(rms, least) << lookahead_s;
    EXPECT_EQ(accel_noise, at) << lookahead_s;
  };
  for (size_t i = 0; i < std::size(kLookaheadsMs); ++i)
    expect_best(kLookaheadsMs[i] * 1e-3, BoundModel::ConstantVelocity, row.best_rms[i], row.best_accel_noise[i]);
  expect_best(0.0, BoundModel::AnchoredAtRest, row.anchored_rms, row.anchored_accel_noise);
  row.thesis_heightmap_rms = 0.2;
  row.tracker_heightmap_rms = 0.09;
  std::ostringstream out;
  write_lookahead_report(out, {row});
  EXPECT_NE(out.str().find("| white-200hz | 0.200 | 0.090 (0.45×) |"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("whole stroke (RTS)"), std::string::npos);
  EXPECT_NE(out.str().find("causal, anchored at rest |"), std::string::npos);
}

// The two tables on rows written by hand: every cell, each row as wide as
// its header; a bound not measured is a dash.
TEST(LookaheadBound, TheTablesShowEveryFigureOfARow) {
  LookaheadRow row;
  row.trace_class = "slow";
  row.thesis_heightmap_rms = 0.25;
  row.tracker_heightmap_rms = 0.1;
  const double best[] = {0.125, 0.1, 0.075, 0.05, 0.025};
  const double q[] = {3e3, 1e3, 3e2, 1e2, 3e1};
  for (size_t i = 0; i < std::size(kLookaheadsMs); ++i) {
    row.best_rms[i] = best[i];
    row.best_accel_noise[i] = q[i];
  }
  row.anchored_rms = 0.0875;
  row.anchored_accel_noise = 1e4;
  row.heading_bound_rms = 0.0625;
  std::ostringstream table;
  write_lookahead_report(table, {row});
  const std::vector<std::string> lines = support::lines_of(table.str());
  ASSERT_GE(lines.size(), 5u);
  EXPECT_EQ(lines[0],
            "| class | thesis HM amp RMS | recommended(profile) | causal, 0 ms ahead | 10 ms ahead | 30 ms ahead | "
            "100 ms ahead | whole stroke (RTS) | causal, anchored at rest | told when each stroke starts | "
            "told all but each stroke's direction |");
  EXPECT_EQ(lines[1], "|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|");
  EXPECT_EQ(lines[2],
            "| slow | 0.250 | 0.100 (0.40×) | 0.125 (0.50×, q 3e+03) | 0.100 (0.40×, q 1e+03) | "
            "0.075 (0.30×, q 3e+02) | 0.050 (0.20×, q 1e+02) | 0.025 (0.10×, q 3e+01) | 0.087 (0.35×, q 1e+04) | "
            "0.062 (0.25×) | - |");
  EXPECT_EQ(lines[3], "");
  EXPECT_NE(lines[4].find("every report up to 0, 10, 30 or 100 ms after it"), std::string::npos);

  row.predicted_ends.heightmap_rms = 0.075;
  row.predicted_ends.rest_rms = 0.2;
  row.predicted_ends.ends = {40, 36, 3, 5.0};
  row.tracker_ends.ends = {40, 35, 2, 7.0};
  std::ostringstream ends;
  write_predicted_ends_report(ends, {row});
  const std::vector<std::string> end_lines = support::lines_of(ends.str());
  ASSERT_GE(end_lines.size(), 5u);
  EXPECT_EQ(end_lines[0],
            "| class | thesis HM amp RMS | recommended(profile) | heading model, told the standstills | told nothing, "
            "strokes ended where predicted | its HM at rest RMS | standstills | predicted within 40 ms | median delay "
            "ms | other predicted ends | the tracker's predictor: within 40 ms | median delay ms | other ends |");
  EXPECT_EQ(end_lines[1], "|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|");
  EXPECT_EQ(end_lines[2],
            "| slow | 0.250 | 0.100 (0.40×) | 0.062 (0.25×) | 0.075 (0.30×) | 0.200 | 40 | 36 | 5 | 3 | 35 | 7 | 2 |");
  for (const std::vector<std::string>* t : {&lines, &end_lines})
    EXPECT_EQ(std::count((*t)[2].begin(), (*t)[2].end(), '|'), std::count((*t)[0].begin(), (*t)[0].end(), '|'));
  EXPECT_NE(end_lines[4].find("at most 32 decimated reports"), std::string::npos) << end_lines[4];
  EXPECT_NE(end_lines[4].find("per 4 ms of reports"), std::string::npos) << end_lines[4];
}

TEST(LookaheadBound, AnAnchorAtRestHelpsAtStartsAndIsCausalOnly) {
  // The same filter, told when the finger stands still, starts each stroke
  // from a settled position instead of a wandering velocity.
  const std::vector<PreparedCase> cases = class_traces("white-200hz", 8.0);
  SmootherOptions smoother;
  smoother.accel_noise_px2_s3 = 1e3;
  smoother.measurement_noise_px = 1.0;
  const double plain = lookahead_heightmap_rms(cases, kClassMovingSpeedPxS, smoother, 0.0, 0.0);
  const double anchored =
      lookahead_heightmap_rms(cases, kClassMovingSpeedPxS, smoother, 0.0, 0.0, BoundModel::AnchoredAtRest);
  EXPECT_GT(anchored, 0.0);
  EXPECT_LT(anchored, 0.8 * plain);  // 0.054 against 0.093 when written
  EXPECT_TRUE(std::isnan(
      lookahead_heightmap_rms(cases, kClassMovingSpeedPxS, smoother, 0.0, 0.010, BoundModel::AnchoredAtRest)));
}

}  // namespace
}  // namespace ff::bench
