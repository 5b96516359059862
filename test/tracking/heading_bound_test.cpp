// The heading bound's filter against a batch regression written out
// independently, its claims (a misread speed rescales the heading, not its
// direction; a standstill forgets it), and the bound on generated traces.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "class_report.hpp"
#include "heading_bound.hpp"
#include "lookahead_bound.hpp"
#include "stroke_end_predictor.hpp"
#include "support/models/trace_classes.hpp"
#include "support/random.hpp"

namespace ff::bench {
namespace {

ReportNoise white(float sigma_px) {
  ReportNoise n;
  n.white_variance = sigma_px * sigma_px;
  return n;
}

// white-200hz's 4 s traces, and the noise the bounds are told on them.
std::vector<PreparedCase> white_200hz_cases() {
  const tracegen::TraceClass* white_class = tracegen::find_trace_class("white-200hz");
  EXPECT_NE(white_class, nullptr);
  return white_class != nullptr ? prepare_cases(class_cases(*white_class, 4.0)) : std::vector<PreparedCase>{};
}
ReportNoise told_noise(const std::vector<PreparedCase>& cases) {
  return ReportNoise::of(tracegen::nominal_profile(cases.front().spec.options));
}

struct StrokeReport {
  float travelled_px;  // since the previous report
  Vec2 z;
};

// A straight stroke from (200, 150) along `angle`, its speed rising and
// falling, reported every 5 ms with white noise.
std::vector<StrokeReport> straight_stroke(double angle, double sigma_px, uint64_t seed) {
  support::Random rng(seed);
  std::vector<StrokeReport> out;
  double s = 0.0;
  for (int k = 0; k < 40; ++k) {
    const double step = k == 0 ? 0.0 : 0.2 + 3.0 * std::sin(M_PI * k / 40.0);
    s += step;
    out.push_back({static_cast<float>(step),
                   {static_cast<float>(200.0 + s * std::cos(angle) + sigma_px * rng.gaussian()),
                    static_cast<float>(150.0 + s * std::sin(angle) + sigma_px * rng.gaussian())}});
  }
  return out;
}

// Without turning, the heading is a regression of each axis on the distance
// travelled: z_k = p0 + s_k u + noise, p0 and u unknown, the prior on u
// N(0, kUnknownSigma^2) and none on p0. Per axis the information is
// A = sum [1 s_k]^T [1 s_k] / sigma^2 + diag(0, 1 / kUnknownSigma^2) and
// A [p0 u]^T = sum [1 s_k]^T z_k / sigma^2; u's variance is (A^-1)_11.
TEST(HeadingBound, WithoutTurningTheFilterIsTheBatchRegression) {
  const float sigma = 1.0f;
  const std::vector<StrokeReport> reports = straight_stroke(0.7, static_cast<double>(sigma), 3);
  StrokeHeading heading(white(sigma), 0.0f);
  const double unknown = static_cast<double>(StrokeHeading::kUnknownSigma);
  double a00 = 0, a01 = 0, a11 = 1.0 / (unknown * unknown);
  double bx0 = 0, bx1 = 0, by0 = 0, by1 = 0, s = 0;
  for (size_t k = 0; k < reports.size(); ++k) {
    const StrokeReport& r = reports[k];
    if (k == 0) heading.touch_down(r.z);
    else heading.update(r.z, r.travelled_px, 0.005f);
    s += static_cast<double>(r.travelled_px);
    const double w = 1.0 / static_cast<double>(sigma * sigma);
    a00 += w;
    a01 += w * s;
    a11 += w * s * s;
    bx0 += w * static_cast<double>(r.z.x);
    bx1 += w * s * static_cast<double>(r.z.x);
    by0 += w * static_cast<double>(r.z.y);
    by1 += w * s * static_cast<double>(r.z.y);
    if (k < 2) continue;
    const double det = a00 * a11 - a01 * a01;
    const double ux = (a00 * bx1 - a01 * bx0) / det, uy = (a00 * by1 - a01 * by0) / det;
    const double var_u = a00 / det;
    const FingerKalman& f = heading.filter();
    EXPECT_NEAR(static_cast<double>(f.P11), var_u, 2e-3 * var_u) << k;
    EXPECT_NEAR(static_cast<double>(f.v.x), ux, 2e-3 * std::hypot(ux, uy) + 1e-4) << k;
    EXPECT_NEAR(static_cast<double>(f.v.y), uy, 2e-3 * std::hypot(ux, uy) + 1e-4) << k;
    EXPECT_NEAR(heading.kappa(), std::hypot(ux, uy) / var_u, 5e-3 * std::hypot(ux, uy) / var_u) << k;
  }
  EXPECT_NEAR(heading.mu(), 0.7, 0.02);
}

TEST(HeadingBound, ASpeedReadTooLowRescalesTheHeadingNotItsDirection) {
  const std::vector<StrokeReport> reports = straight_stroke(-2.2, 0.0, 4);  // noise-free
  StrokeHeading exact(white(1.0f), 1e-4f), halved(white(1.0f), 1e-4f);
  exact.touch_down(reports[0].z);
  halved.touch_down(reports[0].z);
  for (size_t k = 1; k < reports.size(); ++k) {
    exact.update(reports[k].z, reports[k].travelled_px, 0.005f);
    halved.update(reports[k].z, 0.5f * reports[k].travelled_px, 0.005f);
  }
  EXPECT_NEAR(exact.mu(), -2.2, 1e-3);
  EXPECT_NEAR(halved.mu(), -2.2, 1e-3);
  const Vec2 u = exact.filter().v, v = halved.filter().v;
  EXPECT_NEAR(static_cast<double>(length(u)), 1.0, 0.01);
  EXPECT_NEAR(static_cast<double>(length(v)), 2.0, 0.02);
}

TEST(HeadingBound, AStandstillForgetsTheHeadingAndTheNextStrokeIsLearnt) {
  StrokeHeading heading(white(1.0f), 1e-4f);
  const std::vector<StrokeReport> first = straight_stroke(0.0, 0.5, 5);
  heading.touch_down(first[0].z);
  for (size_t k = 1; k < first.size(); ++k) heading.update(first[k].z, first[k].travelled_px, 0.005f);
  EXPECT_GT(heading.kappa(), 100.0);
  heading.new_stroke();
  EXPECT_EQ(heading.kappa(), 0.0);
  // Forgotten: the heading as unknown as at touch-down, and no longer tied to the position.
  EXPECT_EQ(heading.filter().P11, StrokeHeading::kUnknownSigma * StrokeHeading::kUnknownSigma);
  EXPECT_EQ(heading.filter().P01, 0.0f);
  // The second stroke leaves from where the first ended, at a right angle,
  // and is learnt as fast as the first: from a few px of it.
  const Vec2 end = heading.filter().p;
  const std::vector<StrokeReport> second = straight_stroke(M_PI / 2, 0.5, 6);
  for (size_t k = 0; k < second.size(); ++k) {
    const StrokeReport& r = second[k];
    heading.update({end.x + r.z.x - 200.0f, end.y + r.z.y - 150.0f}, r.travelled_px, 0.005f);
    if (k == 5) {  // 4.5 px into it
      EXPECT_NEAR(heading.mu(), M_PI / 2, 0.3);
      EXPECT_GT(heading.kappa(), 10.0);
      EXPECT_NEAR(static_cast<double>(length(heading.filter().v)), 1.0, 0.3);  // not shrunk by the old certainty
    }
  }
  EXPECT_GT(heading.kappa(), 100.0);
  EXPECT_NEAR(heading.mu(), M_PI / 2, 0.05);
}

// A new stroke's heading is unknown and tied to nothing: with a wander, not
// to the wander either.
TEST(HeadingBound, ANewStrokeForgetsTheHeadingsTieToTheWander) {
  ReportNoise noise = white(0.5f);
  noise.wander_variance = 2.0f;
  noise.inverse_tau_s = 1.0f / 0.03f;
  StrokeHeading heading(noise, 1e-4f);
  const std::vector<StrokeReport> stroke = straight_stroke(1.0, 0.5, 10);
  heading.touch_down(stroke[0].z);
  for (size_t k = 1; k < stroke.size(); ++k) heading.update(stroke[k].z, stroke[k].travelled_px, 0.005f);
  ASSERT_NE(heading.filter().P12, 0.0f);
  heading.new_stroke();
  EXPECT_EQ(heading.filter().P12, 0.0f);
  EXPECT_EQ(heading.filter().P01, 0.0f);
}

// The matching of predicted ends to standstills, on times written out: an
// end counts for a standstill from 40 ms before its first report to 40 ms
// after its last, the nearest to its first report; the delay is to its first.
TEST(HeadingBound, EndsAreMatchedToTheNearestStandstillWithinTheTolerance) {
  StrokeEndLog a;
  a.standstills = {{1.0, 1.5}, {2.0, 2.01}, {3.0, 3.02}};
  a.ends = {1.45,    // inside the first standstill, 450 ms after its first report
            1.98,    // 20 ms before the second
            2.049,   // 49 ms after the second's first report, 39 ms after its last
            2.8,     // near none
            3.061};  // 61 ms after the third's first report, 41 ms after its last: near none
  StrokeEndLog b;
  b.standstills = {{0.5, 0.6}};
  b.ends = {0.47, 0.52};  // the nearer of two
  const StrokeEndStats stats = stroke_end_stats({a, b});
  EXPECT_EQ(stats.standstills, 4u);
  EXPECT_EQ(stats.found, 3u);       // the third has no end within its window
  EXPECT_EQ(stats.other_ends, 2u);  // 2.8 and 3.061
  EXPECT_NEAR(stats.median_delay_ms, 20.0, 1e-9);  // of 450, -20 and 20 ms
  EXPECT_TRUE(std::isnan(stroke_end_stats({}).median_delay_ms));
}

// What the observer logs: the truth's standstills and the ends of a
// minimum-jerk fit fed every report of each touch, both found here again by
// a replay of the case's reports written out on its own.
TEST(HeadingBound, TheLoggedEndsAreThePredictorsOnEveryReport) {
  const std::vector<PreparedCase> cases = white_200hz_cases();
  const ReportNoise noise = told_noise(cases);
  HeadingBoundOptions predicted;
  predicted.boundaries = StrokeBoundaries::PredictedEnds;
  const HeadingBoundResult r = heading_bound(cases, kClassMovingSpeedPxS, noise, predicted);
  ASSERT_EQ(r.end_logs.size(), cases.size());
  size_t standstills = 0, ends = 0;
  for (size_t i = 0; i < cases.size(); ++i) {
    const PreparedCase& c = cases[i];
    StrokeEndLog expected;
    StrokeEndPredictor predictor;
    bool touching = false, was_still = false, began_still = false;
    for (const tracegen::TraceSample& s : c.trace.samples) {
      const double scan_us = static_cast<double>(s.t_us) - s.latency_us;
      if (scan_us > static_cast<double>(c.ticks.back().t_us)) break;  // the replay ends with the ticks
      if (!s.touch || !std::isfinite(s.x) || !std::isfinite(s.y)) {
        touching = touching && s.touch;
        continue;
      }
      const double scan_s = scan_us * 1e-6;
      const bool still = standing_still(c.trace.truth_at(static_cast<uint64_t>(std::llround(scan_us))));
      if (!touching) {
        predictor.restart();
        predictor.report(scan_s, s.x, s.y);
        began_still = still;
      } else if (predictor.report(scan_s, s.x, s.y)) {
        expected.ends.push_back(scan_s);
      }
      if (still && !began_still) {
        if (was_still && touching) expected.standstills.back().second = scan_s;
        else expected.standstills.push_back({scan_s, scan_s});
      }
      if (!still) began_still = false;
      was_still = still;
      touching = true;
    }
    EXPECT_EQ(r.end_logs[i].ends, expected.ends) << "case " << i;
    EXPECT_EQ(r.end_logs[i].standstills, expected.standstills) << "case " << i;
    standstills += expected.standstills.size();
    ends += expected.ends.size();
  }
  EXPECT_GT(standstills, 10u);
  EXPECT_GT(ends, 10u);
  // Some standstills last longer than a report: their last report is logged.
  size_t lasting = 0;
  for (const StrokeEndLog& log : r.end_logs)
    for (const auto& [first, last] : log.standstills) lasting += last > first ? 1 : 0;
  EXPECT_GT(lasting, 0u);
}

TEST(HeadingBound, OnTracesItLiesBetweenTheFloorAndTheTrackers) {
  const tracegen::TraceClass* realistic = tracegen::find_trace_class("realistic-200hz");
  ASSERT_NE(realistic, nullptr);
  const std::vector<PreparedCase> cases = prepare_cases(class_cases(*realistic, 4.0));
  const SensorProfile sensor = tracegen::nominal_profile(cases.front().spec.options);
  const double bound = heading_bound_heightmap_rms(cases, kClassMovingSpeedPxS, ReportNoise::of(sensor));
  EvalOptions options;
  options.moving_speed_px_s = kClassMovingSpeedPxS;
  options.lag = false;
  options.cost = false;
  const double shipping = evaluate(TrackerConfig::recommended(sensor), cases, options).heightmap_rms;
  EXPECT_GT(bound, 0.0);
  EXPECT_LT(bound, 0.8 * shipping);
  // Told nothing of the standstills it would keep each heading across
  // reversals and new strokes: the starts are what it is told.
  HeadingBoundOptions never_still;
  never_still.boundaries = StrokeBoundaries::None;
  EXPECT_GT(heading_bound_heightmap_rms(cases, kClassMovingSpeedPxS, ReportNoise::of(sensor), never_still), 1.2 * bound);
}

// Told nothing, its strokes ended where a minimum-jerk fit predicts: on the
// generator's strokes (exactly minimum-jerk) it finds almost every end, on
// time, and stays near the bound told the standstills.
TEST(HeadingBound, StrokesEndedWherePredictedComeCloseToTheStandstillsTold) {
  const std::vector<PreparedCase> cases = white_200hz_cases();
  const ReportNoise noise = told_noise(cases);
  const double told = heading_bound_heightmap_rms(cases, kClassMovingSpeedPxS, noise);
  HeadingBoundOptions predicted;
  predicted.boundaries = StrokeBoundaries::PredictedEnds;
  const HeadingBoundResult r = heading_bound(cases, kClassMovingSpeedPxS, noise, predicted);
  EXPECT_LT(r.heightmap_rms, 1.15 * told);
  ASSERT_GT(r.ends.standstills, 10u);
  EXPECT_GE(r.ends.found, r.ends.standstills * 9 / 10);
  EXPECT_LE(std::fabs(r.ends.median_delay_ms), 10.0);
  EXPECT_LE(r.ends.other_ends, r.ends.standstills / 5);
  // It never decides the finger rests: at rest it renders a heading learnt from the noise,
  // where the bound told the standstills renders 0.5.
  EXPECT_LT(heading_bound(cases, kClassMovingSpeedPxS, noise).rest_rms, 1e-6);
  EXPECT_GT(r.rest_rms, 0.05);
}

// The tracker's own predictor (float, 32 points, one search step per
// refinement) against the standstills and beside the double-precision full
// search: on white-200hz it finds as many, as soon, and as few elsewhere.
TEST(HeadingBound, TheTrackersPredictorFindsTheEndsTheFullSearchFinds) {
  const std::vector<PreparedCase> cases = white_200hz_cases();
  const ReportNoise noise = told_noise(cases);
  HeadingBoundOptions full, tracker;
  full.boundaries = StrokeBoundaries::PredictedEnds;
  tracker.boundaries = StrokeBoundaries::TrackerEnds;
  const StrokeEndStats f = heading_bound(cases, kClassMovingSpeedPxS, noise, full).ends;
  const StrokeEndStats t = heading_bound(cases, kClassMovingSpeedPxS, noise, tracker).ends;
  ASSERT_GT(t.standstills, 10u);
  EXPECT_EQ(t.standstills, f.standstills);
  EXPECT_GE(t.found + t.standstills / 20, f.found);  // within 5 % of the full search
  EXPECT_GE(t.found, t.standstills * 9 / 10);
  EXPECT_LE(std::fabs(t.median_delay_ms), 10.0);
  EXPECT_LE(t.other_ends, t.standstills / 10);
}

// A stroke too short or slow for the fit ends nowhere: forgetting the
// heading while the speed reads low keeps it from outlasting the stop.
TEST(HeadingBound, PredictedEndsForgetTheHeadingWhileTheFingerIsSlow) {
  StrokeHeading heading(white(1.0f), 1e-4f);
  const std::vector<StrokeReport> stroke = straight_stroke(0.3, 0.5, 8);
  heading.touch_down(stroke[0].z);
  for (size_t k = 1; k < stroke.size(); ++k) heading.update(stroke[k].z, stroke[k].travelled_px, 0.005f);
  const double kappa = heading.kappa(), variance = static_cast<double>(heading.filter().P11);
  heading.forget(10.0f);  // 1 s at the default rate
  EXPECT_NEAR(heading.kappa(), kappa * variance / (variance + 10.0), 1e-6 * kappa);

  // In the observer: a heading forgotten while the finger is slow renders
  // closer to 0.5 where it rests.
  const std::vector<PreparedCase> cases = white_200hz_cases();
  const ReportNoise noise = told_noise(cases);
  HeadingBoundOptions predicted;
  predicted.boundaries = StrokeBoundaries::PredictedEnds;
  HeadingBoundOptions never_forgets = predicted;
  never_forgets.forget_variance_per_s = 0.0f;
  EXPECT_LT(heading_bound(cases, kClassMovingSpeedPxS, noise, predicted).rest_rms,
            0.9 * heading_bound(cases, kClassMovingSpeedPxS, noise, never_forgets).rest_rms);
}

}  // namespace
}  // namespace ff::bench
