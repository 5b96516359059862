// Every stress class (stress_classes.cpp) over seeded cases: invariants at
// every tick, bit-for-bit repeatability, bounded recovery, and each class's
// own check. FF_STRESS_SEED / FF_STRESS_CASES reproduce a failure.
#include "stress_classes.hpp"

#include <gtest/gtest.h>

#include <cstdio>

#include "stress_random.hpp"

#ifndef FF_STRESS_TEST_CASES
#define FF_STRESS_TEST_CASES 12
#endif

namespace ff::stress {
namespace {

int cases_for(const char* name) {
  // Minutes-long rests cost ~1 M ticks a case.
  const int n = std::string(name) == "long_rest_then_move" ? (FF_STRESS_TEST_CASES + 5) / 6 : FF_STRESS_TEST_CASES;
  return cases_or(n);
}

void expect_clean(const char* name) {
  const StressClass* c = find_class(name);
  ASSERT_NE(c, nullptr) << name;
  const ClassResult r = c->run(base_seed(), cases_for(name));
  std::printf("[stress] %-34s cases %3d ticks %9llu failures %d worst float/double %.3g recovery %lld %s\n", name,
              r.cases, static_cast<unsigned long long>(r.ticks), r.failures, r.worst_rendering,
              static_cast<long long>(r.worst_recovery), r.note.c_str());
  EXPECT_EQ(r.failures, 0) << r.first_failure;
  EXPECT_LE(r.worst_rendering, kRenderingBound);
  EXPECT_LE(r.worst_recovery, kRecoveryBoundTicks);
}

#define FF_STRESS_CLASS_TEST(name) \
  TEST(StressClass, name) { expect_clean(#name); }

FF_STRESS_CLASS_TEST(random_scenes_and_traces)
FF_STRESS_CLASS_TEST(nonfinite_coordinates)
FF_STRESS_CLASS_TEST(subnormal_coordinates)
FF_STRESS_CLASS_TEST(huge_coordinates)
FF_STRESS_CLASS_TEST(bad_time_steps)
FF_STRESS_CLASS_TEST(clock_wrap)
FF_STRESS_CLASS_TEST(mailbox_overflow)
FF_STRESS_CLASS_TEST(sensor_silence)
FF_STRESS_CLASS_TEST(long_rest_then_move)
FF_STRESS_CLASS_TEST(bad_strength_and_settings)
FF_STRESS_CLASS_TEST(flat_fields)
FF_STRESS_CLASS_TEST(singular_points)
FF_STRESS_CLASS_TEST(extreme_weights_safety)
FF_STRESS_CLASS_TEST(general_scenes)
FF_STRESS_CLASS_TEST(tick_stalls_and_skips)
FF_STRESS_CLASS_TEST(second_finger_and_flapping)

// Found failing, fixed in the core (7706717, c7ddc3a): regression classes now.
FF_STRESS_CLASS_TEST(stamps_far_ahead)
FF_STRESS_CLASS_TEST(tick_time_glitch_ahead)
FF_STRESS_CLASS_TEST(clock_set_back)
FF_STRESS_CLASS_TEST(extreme_weights_scale_invariance)
FF_STRESS_CLASS_TEST(direction_unit_length)
FF_STRESS_CLASS_TEST(max_gradient_search)

TEST(StressClass, EveryClassIsTested) {
  int known = 0;
  for (const StressClass& c : stress_classes()) known += c.known_bug ? 1 : 0;
  EXPECT_EQ(stress_classes().size(), 22u);
  EXPECT_EQ(known, 0);  // docs/stress.md "Findings": every bug found so far is fixed
}

}  // namespace
}  // namespace ff::stress
