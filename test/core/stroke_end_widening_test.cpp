// The tracker at a predicted stroke end (TrackerConfig::stroke_end_widening):
// a minimum-jerk stroke (the formula written out here) that stops is
// rendered at rest sooner than without the prediction and quiet at the stop
// itself; the prediction costs nothing when off, and a burst of reports
// refines once per tick.
#include <gtest/gtest.h>

#include <cmath>

#include "frictionfield/core/tracker.hpp"
#include "support/random.hpp"

namespace ff {
namespace {

constexpr uint32_t kReportPeriodUs = 5000;  // 200 Hz
constexpr uint32_t kStartUs = 1000000;
constexpr double kStrokeStartS = 0.2, kStrokeS = 0.5;  // stops at 0.7 s

double profile(double tau) {
  if (tau <= 0.0) return 0.0;
  if (tau >= 1.0) return 1.0;
  return tau * tau * tau * (10.0 - 15.0 * tau + 6.0 * tau * tau);
}

SensorSample report(uint32_t k, support::Random& rng) {
  const double t = k * (kReportPeriodUs * 1e-6);
  const double s = profile((t - kStrokeStartS) / kStrokeS);
  return {kStartUs + k * kReportPeriodUs, static_cast<float>(150.0 + 300.0 * s + rng.gaussian()),
          static_cast<float>(240.0 - 100.0 * s + rng.gaussian()), true};
}

struct AfterTheStop {
  double direction_squares = 0.0;  // sum of |direction|^2 over the 100 ms after the stop, per tick
  double at_the_stop = 0.0;        // the same over its first 10 ms
  uint32_t ends = 0, refinements = 0;
};

// The stroke and 0.5 s of rest, 1 px noise, a tick every 500 us; the
// reports reach the tracker `burst` at a time.
AfterTheStop run(const TrackerConfig& c, uint64_t seed, uint32_t burst = 1) {
  Tracker tracker(c);
  support::Random rng(seed);
  AfterTheStop r;
  uint32_t k = 0;
  const uint32_t stop_us = kStartUs + static_cast<uint32_t>((kStrokeStartS + kStrokeS) * 1e6);
  for (uint32_t now = kStartUs; now < kStartUs + 1200000; now += kTickPeriodUs) {
    uint32_t due = 0;  // reports scanned by now
    while (kStartUs + (k + due) * kReportPeriodUs <= now) ++due;
    if (due >= burst)
      while (due-- > 0) tracker.on_sample(report(k++, rng));
    const TrackState& s = tracker.on_tick(now);
    const double squares = static_cast<double>(dot(s.direction, s.direction));
    if (now >= stop_us && now < stop_us + 100000) r.direction_squares += squares;
    if (now >= stop_us && now < stop_us + 10000) r.at_the_stop += squares;
  }
  r.ends = tracker.stroke_ends();
  r.refinements = tracker.stroke_end_predictor().refinements();
  return r;
}

TrackerConfig without_ends() {
  TrackerConfig c = TrackerConfig::recommended();
  c.stroke_end_widening = 1.0f;
  return c;
}

TEST(StrokeEndWidening, AStoppedStrokeIsRenderedAtRestSooner) {
  // Measured (sum of |direction|^2 over the 100 ms after the stop, seeds
  // 1-5): 0 / 0.04 / 0.007 / 0 / 0.22 with the prediction, 24 / 6.6 / 0.45 /
  // 28 / 13 without: never worse, 5x less in all (before the direction was
  // quieted over the stop: 0 / 5.2 / 0.007 / 0 / 7.9).
  double with_all = 0.0, without_all = 0.0;
  for (uint64_t seed = 1; seed <= 5; ++seed) {
    const AfterTheStop with = run(TrackerConfig::recommended(), seed);
    const AfterTheStop without = run(without_ends(), seed);
    EXPECT_EQ(with.ends, 1u) << seed;
    EXPECT_LE(with.direction_squares, without.direction_squares) << seed;
    with_all += with.direction_squares;
    without_all += without.direction_squares;
  }
  EXPECT_LT(with_all, 0.3 * without_all);
}

TEST(StrokeEndWidening, TheDirectionIsQuietAtTheStopItself) {
  // The direction faded out over the fitted stop (StrokeEndConfig::
  // quiet_speed_px_s) instead of at the first refinement after it. Measured
  // (sum of |direction|^2 over the first 10 ms of the rest, seeds 1-5):
  // 0 / 0.0005 / 0 / 0 / 0.22 quieted, 0 / 5.2 / 0 / 0 / 7.9 not.
  double quiet_all = 0.0, without_all = 0.0;
  TrackerConfig loud = TrackerConfig::recommended();
  loud.stroke_end.quiet_speed_px_s = 0.0f;
  for (uint64_t seed = 1; seed <= 5; ++seed) {
    const AfterTheStop quiet = run(TrackerConfig::recommended(), seed);
    const AfterTheStop without = run(loud, seed);
    EXPECT_LE(quiet.at_the_stop, without.at_the_stop) << seed;
    quiet_all += quiet.at_the_stop;
    without_all += without.at_the_stop;
  }
  EXPECT_LT(quiet_all, 0.05 * without_all);
}

TEST(StrokeEndWidening, ItIsWhatCatchesTheStopWithoutTheManeuverDetector) {
  TrackerConfig ends_only = TrackerConfig::recommended();
  ends_only.maneuver_threshold = 0.0f;
  TrackerConfig neither = without_ends();
  neither.maneuver_threshold = 0.0f;
  const AfterTheStop with = run(ends_only, 3);
  const AfterTheStop without = run(neither, 3);
  EXPECT_EQ(with.ends, 1u);
  EXPECT_LT(with.direction_squares, 0.5 * without.direction_squares);
}

// The stroke above, then straight back at once: a reversal. The sum over
// the 150 ms after the turn of the direction's component along the way back
// (a tick fully right adds 1, fully wrong -1), and the predicted ends.
struct AfterTheTurn {
  double along_the_way_back = 0.0;
  uint32_t ends = 0;
};

AfterTheTurn run_reversal(const TrackerConfig& c, uint64_t seed) {
  Tracker tracker(c);
  support::Random rng(seed);
  const double turn_s = kStrokeStartS + kStrokeS;
  const auto at = [&](double t) { return profile((t - kStrokeStartS) / kStrokeS) - profile((t - turn_s) / kStrokeS); };
  const Vec2 back = (1.0f / std::sqrt(300.0f * 300.0f + 100.0f * 100.0f)) * Vec2{-300.0f, 100.0f};
  AfterTheTurn r;
  uint32_t k = 0;
  const uint32_t turn_us = kStartUs + static_cast<uint32_t>(turn_s * 1e6);
  for (uint32_t now = kStartUs; now < kStartUs + 1400000; now += kTickPeriodUs) {
    while (kStartUs + k * kReportPeriodUs <= now) {
      const double s = at(k * (kReportPeriodUs * 1e-6));
      tracker.on_sample({kStartUs + k * kReportPeriodUs, static_cast<float>(150.0 + 300.0 * s + rng.gaussian()),
                         static_cast<float>(240.0 - 100.0 * s + rng.gaussian()), true});
      ++k;
    }
    const TrackState& state = tracker.on_tick(now);
    if (now >= turn_us && now < turn_us + 150000) r.along_the_way_back += static_cast<double>(dot(state.direction, back));
  }
  r.ends = tracker.stroke_ends();
  return r;
}

TEST(StrokeEndWidening, AtAReversalTheDirectionTakesOverThePositionFiltersEstimate) {
  // At the turn the position filter has seen the finger slow down while the
  // direction filter still lags the stroke: taking over its estimate turns
  // the direction sooner. Measured (150 ms after the turn, 300 ticks, seeds
  // 1-5): 189 / 167 / 182 / 198 / 190 taken over, 176 / 167 / 176 / 183 / 181
  // widened (seed 2: the position filter read the finger faster, so the
  // direction filter was widened as before).
  double taken_all = 0.0, widened_all = 0.0;
  TrackerConfig widened = TrackerConfig::recommended();
  widened.stroke_end_takes_position = false;
  for (uint64_t seed = 1; seed <= 5; ++seed) {
    const AfterTheTurn taken = run_reversal(TrackerConfig::recommended(), seed);
    const AfterTheTurn without = run_reversal(widened, seed);
    EXPECT_GE(taken.ends, 1u) << seed;
    EXPECT_EQ(taken.ends, without.ends) << seed;
    EXPECT_GE(taken.along_the_way_back, without.along_the_way_back) << seed;
    taken_all += taken.along_the_way_back;
    widened_all += without.along_the_way_back;
  }
  EXPECT_GT(taken_all, widened_all + 30.0);  // measured: 43.5 more
}

TEST(StrokeEndWidening, OffItCostsNothing) {
  const AfterTheStop off = run(without_ends(), 4);
  EXPECT_EQ(off.ends, 0u);
  EXPECT_EQ(off.refinements, 0u);
  EXPECT_GT(run(TrackerConfig::recommended(), 4).refinements, 0u);
}

TEST(StrokeEndWidening, ABurstOfReportsRefinesOncePerTick) {
  // Eight reports at once (a stalled main loop) every 40 ms: at most one
  // refinement per burst, as its reports come within one tick.
  const AfterTheStop burst = run(TrackerConfig::recommended(), 5, 8);
  const uint32_t bursts = 1200000 / (8 * kReportPeriodUs) + 1;
  EXPECT_GT(burst.refinements, 0u);
  EXPECT_LE(burst.refinements, bursts);
}

TEST(StrokeEndWidening, TheCountsStartAgainWithEachConfiguration) {
  // maneuvers(), stroke_ends() and the fit's refinements count since
  // configure(): a new condition starts them at 0, whatever came before.
  Tracker tracker(TrackerConfig::recommended());
  support::Random rng(6);
  auto feed = [&](uint32_t k, SensorSample s) {  // a report and the ticks up to the next one
    tracker.on_sample(s);
    for (uint32_t t = 0; t < kReportPeriodUs; t += kTickPeriodUs) tracker.on_tick(kStartUs + k * kReportPeriodUs + t);
  };
  uint32_t k = 0;
  for (; k < 240; ++k) feed(k, report(k, rng));  // the stroke and its stop
  for (int i = 0; i < 80; ++i, ++k) {            // then a sharp back-and-forth: 400 px/s, turned at once
    const float x = 450.0f - 2.0f * static_cast<float>(i < 40 ? i : 80 - i);
    feed(k, {kStartUs + k * kReportPeriodUs, x, 140.0f, true});
  }
  ASSERT_GT(tracker.maneuvers(), 0u);
  ASSERT_GT(tracker.stroke_ends(), 0u);
  ASSERT_GT(tracker.stroke_end_predictor().refinements(), 0u);
  tracker.configure(TrackerConfig::recommended());
  EXPECT_EQ(tracker.maneuvers(), 0u);
  EXPECT_EQ(tracker.stroke_ends(), 0u);
  EXPECT_EQ(tracker.stroke_end_predictor().refinements(), 0u);
}

}  // namespace
}  // namespace ff
