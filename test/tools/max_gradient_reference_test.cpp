// The core's max|G| search against the double reference's dense scan (every
// pixel, then a compass search to 1e-9 px) for every benchmarked scene at its
// closed form: the normalisation of every directional scene's amplitude.
// 1e-5 relative (the float evaluation alone is off by up to 2.5e-6: tunnel A).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "bench_cases.hpp"
#include "frictionfield/core/scene_plan.hpp"
#include "accuracy.hpp"

namespace ff::bench {
namespace {

TEST(MaxGradientSearch, WithinTenMillionthsOfTheDenseScanForEveryScene) {
  std::vector<unsigned char> table(kTableSlotBytes);
  for (int i = 0; i < kSceneCount; ++i) {
    const auto id = static_cast<SceneId>(i);
    const reference::ReferenceScene ref = reference_scene_for(id);
    if (ref.rendering() != Rendering::Directional) continue;
    SceneDefinition def = scene_definition(id);
    def.evaluation = Evaluation::ClosedForm;
    ScenePlan plan;
    ASSERT_EQ(plan.prepare(def, table.data(), table.size()), PrepareStatus::Ok) << scene_name(id);
    const double dense = ref.max_gradient();
    const double core = plan.stats().max_gradient;
    EXPECT_LE(std::fabs(core - dense), 1e-5 * dense) << scene_name(id) << ": core " << core << ", dense " << dense;
  }
}

}  // namespace
}  // namespace ff::bench
