// ff-bench's cases and its accuracy grid: the float core's closed forms agree
// with the double reference of the spec's scenes (test/support/reference,
// tested there) to within the 1 LSB goal.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

#include "accuracy.hpp"
#include "bench_cases.hpp"
#include "support/models/trace_classes.hpp"

namespace ff::bench {
namespace {

TEST(BenchCases, IdsAreUniqueAndEveryKindIsPresent) {
  std::set<std::string> ids;
  int defaults = 0;
  for (int i = 0; i < case_count(); ++i) {
    char id[96];
    case_id(case_at(i), id, sizeof(id));
    EXPECT_TRUE(ids.insert(id).second) << id;
    defaults += is_default(case_at(i)) ? 1 : 0;
  }
  EXPECT_EQ(defaults, kSceneCount);  // one default per scene
  for (const char* expected : {"neutral/closed-form", "heightmap-top/table-1px-float-gradient",
                               "heightmap-top/table-16px-int16-height-cd", "frictionmap-top/table-4px-int16-profile",
                               "vortex/table-8px-float-gradient", "general-6/closed-form"}) {
    EXPECT_EQ(ids.count(expected), 1u) << expected;
  }
  EXPECT_EQ(ids.count("vortex/table-8px-float-height-cd"), 0u);  // a vortex has no height
}

// The benchmark's realistic tracker is configured for the realistic-200hz
// class's sensor, as the trace generator models it.
TEST(BenchCases, TheRealisticProfileIsTheRealisticClasssNominalProfile) {
  const SensorProfile bench = realistic_sensor_profile();
  const SensorProfile generated = tracegen::class_profile("realistic-200hz");
  EXPECT_FLOAT_EQ(bench.white_noise_px, generated.white_noise_px);
  EXPECT_FLOAT_EQ(bench.jitter_us, generated.jitter_us);
  SensorProfile rest = bench;  // every other field exactly
  rest.white_noise_px = generated.white_noise_px;
  rest.jitter_us = generated.jitter_us;
  EXPECT_TRUE(rest == generated);
  EXPECT_TRUE(is_valid(bench));
  EXPECT_DEATH(tracegen::class_profile("realistic-2khz"), "no trace class");  // never the default sensor
}

TEST(BenchReference, CoreClosedFormsAgreeWithinOneLsb) {
  // The reference and the core describe the same scenes: their closed forms
  // agree on a coarse grid to the goal (ff-bench measures the fine grid).
  for (int s = 0; s < kSceneCount; ++s) {
    const SceneId id = static_cast<SceneId>(s);
    const ReferenceGrid grid(reference_scene_for(id), 23.0);
    ScenePlan plan;
    ASSERT_EQ(plan.prepare(scene_definition(id), nullptr, 0), PrepareStatus::Ok) << scene_name(id);
    const Accuracy acc = grid.measure(plan);
    EXPECT_LT(acc.max_lsb, 1.0) << scene_name(id);
    EXPECT_GT(acc.samples, 0) << scene_name(id);
  }
}

}  // namespace
}  // namespace ff::bench
