// ff-bench's double-precision reference: its gradients are the derivatives of
// its heights, its max|G| and amplitudes match hand-derived values, and the
// float core's closed forms agree with it to within the 1 LSB goal.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

#include "accuracy.hpp"
#include "bench_cases.hpp"
#include "reference_scene.hpp"

namespace ff::bench {
namespace {

using reference::Scene;
using reference::Term;
using reference::TermKind;
using reference::Vec2d;

constexpr double kPi = 3.14159265358979323846;

bool near_kink(const Term& t, Vec2d p) {
  if (t.kind == TermKind::Cone) return std::hypot(p.x - t.centre.x, p.y - t.centre.y) < 1.0;
  if (t.kind == TermKind::Tunnel) {  // the width's slope jumps at both ends
    return std::fabs(p.x - t.tunnel_x0) < 1.0 || std::fabs(p.x - t.tunnel_x0 - t.tunnel_length) < 1.0;
  }
  return false;
}

TEST(BenchReference, GradientIsTheDerivativeOfTheHeight) {
  constexpr double h = 1e-4;
  int checked = 0;
  for (int s = 0; s < kSceneCount; ++s) {
    const Scene scene = reference::scene_for(static_cast<SceneId>(s));
    for (const Term& t : scene.terms) {
      if (t.kind == TermKind::Vortex) continue;  // a field without a height
      for (double y = 3.7; y < 479.0; y += 31.3) {
        for (double x = 2.9; x < 799.0; x += 37.1) {
          const Vec2d p{x, y};
          if (near_kink(t, p)) continue;
          const Vec2d g = reference::gradient(t, p);
          const double dx = (reference::height(t, {x + h, y}) - reference::height(t, {x - h, y})) / (2 * h);
          const double dy = (reference::height(t, {x, y + h}) - reference::height(t, {x, y - h})) / (2 * h);
          ASSERT_NEAR(g.x, dx, 1e-6 * (1.0 + std::fabs(dx))) << scene_name(static_cast<SceneId>(s)) << " at " << x << ", " << y;
          ASSERT_NEAR(g.y, dy, 1e-6 * (1.0 + std::fabs(dy))) << scene_name(static_cast<SceneId>(s)) << " at " << x << ", " << y;
          ++checked;
        }
      }
    }
  }
  EXPECT_GT(checked, 5000);
}

TEST(BenchReference, VortexFieldIsTheRotatedOffset) {
  const Scene vortex = reference::scene_for(SceneId::Vortex);
  const Vec2d g = reference::field(vortex, {410.0, 250.0});
  EXPECT_DOUBLE_EQ(g.x, -10.0);
  EXPECT_DOUBLE_EQ(g.y, 10.0);
}

TEST(BenchReference, MaxGradientMatchesHandDerivedValues) {
  // Vortex around (400, 240): the farthest screen point is the corner (0, 0).
  EXPECT_NEAR(reference::max_gradient(reference::scene_for(SceneId::Vortex)), std::hypot(400.0, 240.0), 1e-9);
  // Bumps h sin(kx) sin(ky): |G| = h k at most, h = 20, k = 2 pi / 160.
  EXPECT_NEAR(reference::max_gradient(reference::scene_for(SceneId::BumpMap)), 20.0 * 2.0 * kPi / 160.0, 1e-9);
  // Heightmap middle: valley and cone gradients align at (700, 0): u = -240,
  // a u = -48, |dZ_path/du| = 48^2 / (1 + 48^2) = 2304 / 2305, |G_cone| = 1.
  EXPECT_NEAR(reference::max_gradient(reference::scene_for(SceneId::HeightmapMiddle)),
              0.5 * (1.0 + 2304.0 / 2305.0), 1e-9);
}

TEST(BenchReference, HeightmapAmplitudeOnTheFlatStart) {
  // At (50, 240) the middle path is flat and the finger is on it (u = 0):
  // G = 1/2 (0, 0) + 1/2 (-1, 0). Moving right, towards the target, is downhill.
  const Scene scene = reference::scene_for(SceneId::HeightmapMiddle);
  const double m = 0.5 * (1.0 + 2304.0 / 2305.0);
  EXPECT_NEAR(reference::amplitude(scene, m, {50.0, 240.0}, {1.0, 0.0}), 0.5 + 0.25 / m, 1e-12);
  EXPECT_NEAR(reference::amplitude(scene, m, {50.0, 240.0}, {-1.0, 0.0}), 0.5 - 0.25 / m, 1e-12);
  EXPECT_NEAR(reference::amplitude(scene, m, {50.0, 240.0}, {0.0, 1.0}), 0.5, 1e-12);
}

TEST(BenchReference, FrictionmapProfileIsTheQuinticBand) {
  // Left of x = 100 the top path is flat at y = 240: A = S5((30 - |u|) / 20).
  const Scene scene = reference::scene_for(SceneId::FrictionmapTop);
  EXPECT_DOUBLE_EQ(reference::profile(scene, {50.0, 240.0}), 1.0);
  EXPECT_DOUBLE_EQ(reference::profile(scene, {50.0, 250.0}), 1.0);
  EXPECT_NEAR(reference::profile(scene, {50.0, 260.0}), 0.5, 1e-12);
  EXPECT_NEAR(reference::profile(scene, {50.0, 215.0}), 6.0 / 1024 - 15.0 / 256 + 10.0 / 64, 1e-12);
  EXPECT_DOUBLE_EQ(reference::profile(scene, {50.0, 270.0}), 0.0);
}

TEST(BenchReference, CubicPathJoinsFlatAndEndsAtTheTarget) {
  reference::Curve c;
  c.rise = -200.0;
  EXPECT_DOUBLE_EQ(c.y(100.0), 240.0);
  EXPECT_DOUBLE_EQ(c.y(700.0), 40.0);
  EXPECT_DOUBLE_EQ(c.y(50.0), 240.0);
  EXPECT_DOUBLE_EQ(c.y(750.0), 40.0);
  EXPECT_NEAR(c.slope(400.0), 1.5 * -200.0 / 600.0, 1e-12);  // 3T / (2L) at the middle
  EXPECT_NEAR(c.slope(100.0), 0.0, 1e-12);
  EXPECT_NEAR(c.slope(700.0), 0.0, 1e-12);
}

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

TEST(BenchReference, CoreClosedFormsAgreeWithinOneLsb) {
  // The reference and the core describe the same scenes: their closed forms
  // agree on a coarse grid to the goal (ff-bench measures the fine grid).
  for (int s = 0; s < kSceneCount; ++s) {
    const SceneId id = static_cast<SceneId>(s);
    const ReferenceGrid grid(reference::scene_for(id), 23.0);
    ScenePlan plan;
    ASSERT_EQ(plan.prepare(scene_definition(id), nullptr, 0), PrepareStatus::Ok) << scene_name(id);
    const Accuracy acc = grid.measure(plan);
    EXPECT_LT(acc.max_lsb, 1.0) << scene_name(id);
    EXPECT_GT(acc.samples, 0) << scene_name(id);
  }
}

}  // namespace
}  // namespace ff::bench
