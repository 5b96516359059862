// Three simulated hours at 2 kHz (21.6 M ticks) through three wraps of the
// 32-bit microsecond clock (stress_long_run.hpp): no drift (at the end of
// every rest the filtered position equals the sensor's within 0.1 px), no
// growing error (every cycle tracks as well as the first, same input), no
// counter trouble. FF_STRESS_LONG_RUN_SECONDS sets the length (3 h native,
// 10 min under ASan).
#include "stress_long_run.hpp"

#include <gtest/gtest.h>

#include <cstdio>

#include "stress_random.hpp"
#include "support/models/trace_classes.hpp"

#ifndef FF_STRESS_LONG_RUN_SECONDS
#define FF_STRESS_LONG_RUN_SECONDS 10800
#endif

namespace ff::stress {
namespace {

void check_long_run(const TrackerConfig& tracker, const char* label) {
  const LongRunResult r = long_run(tracker, FF_STRESS_LONG_RUN_SECONDS, base_seed());
  std::printf("[long run] %s: %llu s simulated, %llu ticks, %.2f s wall (%.0f ns/tick)\n", label,
              static_cast<unsigned long long>(r.seconds), static_cast<unsigned long long>(r.ticks), r.wall_seconds,
              r.wall_seconds * 1e9 / static_cast<double>(r.ticks));
  for (size_t c = 0; c < r.cycles; c += 30) {
    std::printf("[long run]   minute %3zu: stroke error max %.4f px, rest offset %.2e px\n", c, r.max_error_per_cycle[c],
                r.rest_offset_per_cycle[c]);
  }
  std::printf("[long run]   worst rest offset %.2e px; stroke error max %.4f (first minute %.4f), mean %.4f (first %.4f) px\n",
              r.worst_rest_offset, r.worst_max_error, r.first_max_error, r.worst_mean_error, r.first_mean_error);
  EXPECT_EQ(r.bad_ticks, 0u);
  EXPECT_LE(r.worst_rest_offset, 0.1) << "drift: the filter does not settle on a resting finger";
  // No growing error: no cycle tracks worse than the first (same input), to 1e-3 px.
  EXPECT_LE(r.worst_max_error, r.first_max_error + 1e-3);
  EXPECT_LE(r.worst_mean_error, r.first_mean_error + 1e-3);
  EXPECT_EQ(r.pipeline_ticks, static_cast<uint32_t>(r.ticks));
  EXPECT_EQ(r.faults[Fault::NonIncreasingTime], 0u);
  EXPECT_EQ(r.faults[Fault::BadTickTime], 0u);
  EXPECT_EQ(r.faults[Fault::LiftOff], r.lifts);
  EXPECT_EQ(r.faults[Fault::TouchDown], r.lifts + 1);
  EXPECT_EQ(r.faults[Fault::SensorTimeout], 0u);
}

// Shorter than one cycle: rounded up to one minute (ff-stress-report
// --long-run-seconds 30 read the first minute's figures from an empty list).
TEST(LongRun, ARunShorterThanAMinuteIsOneWholeMinute) {
  const LongRunResult r = long_run(TrackerConfig::recommended(), 1, base_seed());
  EXPECT_EQ(r.cycles, 1u);
  EXPECT_EQ(r.seconds, 60u);
  EXPECT_EQ(r.ticks, 120000u);  // 60 s at 2 kHz
  EXPECT_EQ(r.bad_ticks, 0u);
  EXPECT_EQ(r.max_error_per_cycle.size(), 1u);
}

TEST(LongRun, ThreeHoursRecommendedTracker) { check_long_run(TrackerConfig::recommended(), "recommended"); }
// The direction filter at its largest: the wander and the tremor as states.
TEST(LongRun, ThreeHoursRecommendedTrackerForASensorWithWanderAndTremor) {
  const SensorProfile sensor = tracegen::class_profile("realistic-200hz");
  check_long_run(TrackerConfig::recommended(sensor), "recommended(wander and tremor)");
}
TEST(LongRun, ThreeHoursThesisTracker) { check_long_run(TrackerConfig::thesis(), "thesis (ticks + 1-euro)"); }

}  // namespace
}  // namespace ff::stress
