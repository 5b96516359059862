// Issue 14's goals, per trace class, on what ships: recommended(profile) with
// the profile a calibration of each trace's sensor and finger would give (its
// generator parameters and its tremor's frequency: nominal_profile). The goals the tracker meets are checked as
// stated (chatter at rest <= 0.01 now on every class); the one it does not
// yet meet everywhere (heightmap <= 0.45x the thesis pipeline's, 0.35x on
// white-200hz) is checked against today's measured values plus a small margin, so that a change that
// loses ground fails, and docs/tracking.md says how far each is from the goal.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>

#include "class_report.hpp"
#include "direction_bound.hpp"
#include "heading_bound.hpp"
#include "support/models/trace_classes.hpp"
#include "tracking_evaluation.hpp"

namespace ff::bench {
namespace {

constexpr double kDurationS = 10.0;  // 6 traces per class: ~1 min of finger per class

struct ClassResult {
  Metrics thesis, shipping, uncalibrated;
  double floor = 0.0;    // told all but where each stroke goes (direction_bound.hpp)
  double heading = 0.0;  // told when each stroke starts (heading_bound.hpp)
};

const ClassResult& result(const std::string& name) {
  static std::map<std::string, ClassResult> cache;
  auto it = cache.find(name);
  if (it != cache.end()) return it->second;
  const tracegen::TraceClass* trace_class = tracegen::find_trace_class(name);
  EXPECT_NE(trace_class, nullptr) << name;
  const std::vector<PreparedCase> cases = prepare_cases(class_cases(*trace_class, kDurationS));
  EvalOptions options;
  options.cost = false;
  options.moving_speed_px_s = kClassMovingSpeedPxS;
  const SensorProfile sensor = tracegen::nominal_profile(cases.front().spec.options);
  ClassResult r{evaluate(TrackerConfig::thesis(), cases, options),
                evaluate([](const PreparedCase& c) { return TrackerConfig::recommended(nominal_profile(c)); }, cases,
                         options),
                evaluate(TrackerConfig::recommended(), cases, options),
                class_direction_bound(*trace_class, cases, kDurationS, kClassMovingSpeedPxS),
                heading_bound_heightmap_rms(cases, kClassMovingSpeedPxS, ReportNoise::of(sensor))};
  return cache.emplace(name, r).first->second;
}

struct Bounds {
  const char* trace_class;
  double heightmap_ratio;  // the goal (0.45) where met, else measured on 10 s traces + 0.05
  double rest_rms;         // the goal (0.01) where met, else measured + 0.01
};

class ClassGoals : public ::testing::TestWithParam<Bounds> {};

TEST_P(ClassGoals, ShippingTrackerPerClass) {
  const Bounds b = GetParam();
  const ClassResult& r = result(b.trace_class);
  ASSERT_GT(r.shipping.moving_ticks, 10000u);
  ASSERT_GT(r.shipping.rest_ticks, 500u);
  // Met on every class: the goals as the issue states them.
  EXPECT_LE(std::fabs(r.shipping.lag_ms), kClassMaxLagMs);
  EXPECT_LE(r.shipping.frictionmap_rms, kClassMaxFrictionmapRatio * r.thesis.frictionmap_rms);
  // Not yet met everywhere: no worse than today.
  EXPECT_LE(r.shipping.heightmap_rms, b.heightmap_ratio * r.thesis.heightmap_rms);
  EXPECT_LE(r.shipping.heightmap_rest_rms, b.rest_rms);
}

// The goals stay within what the reports carry: an observer told all but
// where each stroke goes (direction_bound.hpp) errs less than the heightmap
// goal allows on every class, so a missed goal is the tracker's, not the
// class's. Fails if the generated classes grow harder than the goals.
TEST_P(ClassGoals, TheHeightmapGoalIsWithinWhatTheReportsCarry) {
  const ClassResult& r = result(GetParam().trace_class);
  EXPECT_LT(r.floor, class_heightmap_goal(GetParam().trace_class) * r.thesis.heightmap_rms)
      << "floor " << r.floor / r.thesis.heightmap_rms << "x of the thesis pipeline";
}

// And within reach of a finger model: a heading that turns per px travelled,
// told only when each stroke starts (heading_bound.hpp), meets the goal on
// every class (10 s: 0.33-0.43x against 0.35 / 0.45x), so what the tracker
// lacks is a detector of starts and stops.
TEST_P(ClassGoals, AHeadingModelToldTheStartsMeetsTheHeightmapGoal) {
  const ClassResult& r = result(GetParam().trace_class);
  EXPECT_LT(r.heading, class_heightmap_goal(GetParam().trace_class) * r.thesis.heightmap_rms)
      << "heading bound " << r.heading / r.thesis.heightmap_rms << "x of the thesis pipeline";
}

INSTANTIATE_TEST_SUITE_P(Classes, ClassGoals,
                         // Measured (10 s traces, stroke ends predicted, quiet at each stop, the position
                         // filter's estimate taken over there when slower, the tremor a state of every
                         // filter at its measured frequency, the position and the calm filters' speeds as
                         // evidence of motion): heightmap 0.456 / 0.405 / 0.449 / 0.467 / 0.551 / 0.502 /
                         // 0.569 / 0.622x, chatter 0.0061 / 0.0091 / 0.0010 / 0.0061 / 0.0013 / 0.0069 /
                         // 0.0071 / 0.0095 (30 s: all 8 within 0.01 too, docs/tracking.md).
                         ::testing::Values(Bounds{"white-200hz", 0.51, kClassRestBound},
                                           Bounds{"slow-fingers", kClassMaxHeightmapRatio, kClassRestBound},
                                           Bounds{"tremor", 0.50, kClassRestBound},
                                           Bounds{"latency", 0.52, kClassRestBound},
                                           Bounds{"correlated-noise", 0.60, kClassRestBound},
                                           Bounds{"realistic-100hz", 0.55, kClassRestBound},
                                           Bounds{"realistic-200hz", 0.62, kClassRestBound},
                                           Bounds{"realistic-1khz", 0.67, kClassRestBound}),
                         [](const ::testing::TestParamInfo<Bounds>& info) {
                           std::string n = info.param.trace_class;
                           for (char& c : n)
                             if (c == '-') c = '_';
                           return n;
                         });

// What calibration buys: where the sensor differs from the default profile,
// recommended(profile) beats recommended() where it matters.
TEST(ClassGoals, TheProfileRemovesTheLatencyAndTheWandersChatter) {
  const ClassResult& latency = result("latency");
  EXPECT_GT(latency.uncalibrated.lag_ms, 1.5);  // 1-3 ms late stamps pass through
  EXPECT_LT(latency.shipping.lag_ms, 0.5);
  const ClassResult& wander = result("correlated-noise");
  EXPECT_LT(wander.shipping.heightmap_rest_rms, 0.5 * wander.uncalibrated.heightmap_rest_rms);
  const ClassResult& fast = result("realistic-1khz");
  EXPECT_LT(fast.shipping.heightmap_rest_rms, 0.5 * fast.uncalibrated.heightmap_rest_rms);
  EXPECT_LT(fast.shipping.lag_ms, 0.5 * fast.uncalibrated.lag_ms);
}

}  // namespace
}  // namespace ff::bench
