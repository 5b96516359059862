// The minimum-jerk fit against strokes built from the profile's formula
// (10 tau^3 - 15 tau^4 + 6 tau^5, written out here), and the predictor's
// claims: it ends a stroke where the finger stops, not before, and never on
// a resting finger's noise.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "stroke_end_predictor.hpp"
#include "support/random.hpp"
#include "support/models/min_jerk_stroke.hpp"

namespace ff::bench {
namespace {

using Stroke = testing::MinJerkStroke;

// Reports every 5 ms over [t0, t1), with white noise of sigma px per axis.
std::vector<TimedReport> reports_of(const Stroke& s, double t0, double t1, double sigma_px, uint64_t seed) {
  support::Random rng(seed);
  std::vector<TimedReport> out;
  for (double t = t0; t < t1; t += 0.005)
    out.push_back({t, s.x(t) + sigma_px * rng.gaussian(), s.y(t) + sigma_px * rng.gaussian()});
  return out;
}

const Stroke kStroke{0.1, 0.5, 100.0, 50.0, 240.0, -70.0};

TEST(StrokeEndPredictor, AtTheTrueTimingTheFitIsTheStroke) {
  const std::vector<TimedReport> r = reports_of(kStroke, 0.0, 0.7, 0.0, 1);
  const MinJerkFit f = fit_min_jerk_at(r, kStroke.start_s, kStroke.duration_s);
  ASSERT_TRUE(f.valid());
  EXPECT_NEAR(f.from_x, 100.0, 1e-6);
  EXPECT_NEAR(f.from_y, 50.0, 1e-6);
  EXPECT_NEAR(f.travel_x, 240.0, 1e-6);
  EXPECT_NEAR(f.travel_y, -70.0, 1e-6);
  EXPECT_NEAR(f.distance_px(), std::hypot(240.0, -70.0), 1e-6);
  EXPECT_NEAR(f.cost, 0.0, 1e-6);
  EXPECT_DOUBLE_EQ(f.end_s(), 0.6);
  // Any other timing leaves residuals.
  EXPECT_GT(fit_min_jerk_at(r, 0.11, 0.5).cost, 1.0);
  EXPECT_GT(fit_min_jerk_at(r, 0.1, 0.52).cost, 1.0);
}

TEST(StrokeEndPredictor, ReportsThatCannotTellTheStrokeGiveNoFit) {
  const std::vector<TimedReport> before = reports_of(kStroke, 0.0, 0.09, 0.0, 2);  // all before it starts
  EXPECT_FALSE(fit_min_jerk_at(before, kStroke.start_s, kStroke.duration_s).valid());
  EXPECT_FALSE(fit_min_jerk_at({}, 0.0, 1.0).valid());
}

TEST(StrokeEndPredictor, SeenPastItsPeakTheStrokesEndIsFound) {
  // Reports up to 70 % of the stroke, nothing guessed: the grid and the search find its timing.
  const std::vector<TimedReport> r = reports_of(kStroke, 0.0, 0.1 + 0.7 * 0.5, 0.0, 3);
  const MinJerkFit f = fit_min_jerk(r, MinJerkFit{}, 0.15);
  ASSERT_TRUE(f.valid());
  EXPECT_NEAR(f.start_s, 0.1, 1e-3);
  EXPECT_NEAR(f.end_s(), 0.6, 2e-3);
  EXPECT_NEAR(f.travel_x, 240.0, 1.0);
}

TEST(StrokeEndPredictor, EndsEachStrokeWhereItStopsAndNeverOnNoise) {
  // A stroke, a 60 ms dwell, a reversal back, then a rest, with 1 px noise.
  const Stroke back{0.66, 0.4, 340.0, -20.0, -200.0, 60.0};
  support::Random rng(7);
  StrokeEndPredictor predictor;
  std::vector<double> ends;
  for (double t = 0.0; t < 2.5; t += 0.005) {
    const Stroke& s = t < 0.63 ? kStroke : back;
    if (predictor.report(t, s.x(t) + rng.gaussian(), s.y(t) + rng.gaussian())) ends.push_back(t);
  }
  ASSERT_EQ(ends.size(), 2u);
  EXPECT_NEAR(ends[0], 0.6, 0.02);
  EXPECT_NEAR(ends[1], 1.06, 0.02);
  // A finger that rests for 5 s (1 px noise, no drift) never ends a stroke.
  predictor.restart();
  for (double t = 0.0; t < 5.0; t += 0.005) EXPECT_FALSE(predictor.report(t, 200.0 + rng.gaussian(), 100.0 + rng.gaussian())) << t;
}

TEST(StrokeEndPredictor, AStrokeShorterThanTheMinimumIsNotEnded) {
  // Clean reports (0.1 px of noise): the fit is sure of both, only the length differs.
  auto ends = [](double length_px) {
    const Stroke s{0.1, 0.3, 50.0, 50.0, length_px * 0.6, length_px * 0.8};
    support::Random rng(11);
    StrokeEndPredictor predictor;  // 10 px at least
    int n = 0;
    for (double t = 0.0; t < 1.0; t += 0.005) n += predictor.report(t, s.x(t) + 0.1 * rng.gaussian(), s.y(t) + 0.1 * rng.gaussian());
    return n;
  };
  EXPECT_EQ(ends(8.0), 0);
  EXPECT_EQ(ends(14.0), 1);
}

}  // namespace
}  // namespace ff::bench
