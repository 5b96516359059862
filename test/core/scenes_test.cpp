// Hand-derived values of every built-in scene at named points (docs/spec.md#scenes).
#include "frictionfield/core/scenes.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "frictionfield/core/scene_plan.hpp"
#include "support/reference/reference_scene.hpp"
#include "support/reference/spec_scenes.hpp"

namespace ff {
namespace {

// The spec's scenes in double (test/support/reference), max|G| from every pixel refined.
reference::ReferenceScene reference_heightmap(Target t) {
  return reference::ReferenceScene(reference::spec::heightmap(target_rise(t)), reference::kEveryPixel);
}
double reference_frictionmap(double x, double y, Target t) {
  return reference::ReferenceScene(reference::spec::frictionmap(target_rise(t))).profile(x, y);
}

ScenePlan prepared(const SceneDefinition& s) {
  ScenePlan plan;
  EXPECT_EQ(plan.prepare(s, nullptr, 0), PrepareStatus::Ok);
  return plan;
}

double amp(const ScenePlan& p, float x, float y, float dx = 0.0f, float dy = 0.0f) {
  return static_cast<double>(p.amplitude({x, y}, {dx, dy}));
}

TEST(Frictionmap, SlipperyPathFeatherAndStickyBeyond) {
  const ScenePlan middle = prepared(scenes::frictionmap(Target::Middle));
  EXPECT_EQ(middle.needs(), Needs::Position);
  EXPECT_DOUBLE_EQ(amp(middle, 400, 240), 1.0);   // path centre
  EXPECT_DOUBLE_EQ(amp(middle, 400, 250), 1.0);   // |u| = 10: edge of the 20 px path
  EXPECT_NEAR(amp(middle, 400, 260), 0.5, 1e-6);  // feather midpoint: S5(1/2) = 1/2
  EXPECT_NEAR(amp(middle, 400, 220), 0.5, 1e-6);
  EXPECT_NEAR(amp(middle, 400, 265), reference::smootherstep(0.25), 1e-6);
  EXPECT_DOUBLE_EQ(amp(middle, 400, 270), 0.0);   // |u| = 30: high friction
  EXPECT_DOUBLE_EQ(amp(middle, 400, 400), 0.0);
  // Top path: y_path(400) = 140; direction of motion is ignored.
  const ScenePlan top = prepared(scenes::frictionmap(Target::Top));
  EXPECT_DOUBLE_EQ(amp(top, 400, 140, 1, 0), 1.0);
  EXPECT_NEAR(amp(top, 400, 160, 0, -1), 0.5, 1e-6);
}

TEST(Frictionmap, MatchesDoubleReferenceOnTheWholeScreen) {
  for (Target t : {Target::Top, Target::Middle, Target::Bottom}) {
    const ScenePlan p = prepared(scenes::frictionmap(t));
    double worst = 0;
    for (int y = 0; y < 480; y += 2)
      for (int x = 0; x < 800; x += 2)
        worst = std::fmax(worst, std::fabs(amp(p, x, y) - reference_frictionmap(x, y, t)));
    EXPECT_LT(worst, 0.5 / 4095) << "more than half an LSB";
  }
}

TEST(Neutral, HalfEverywhereAndNeedsNothing) {
  const ScenePlan p = prepared(scenes::neutral());
  EXPECT_EQ(p.needs(), Needs::Nothing);
  EXPECT_DOUBLE_EQ(amp(p, 0, 0), 0.5);
  EXPECT_DOUBLE_EQ(amp(p, 400, 240, 1, 0), 0.5);
}

class HeightmapTest : public ::testing::Test {
 protected:
  static double max_g(Target t) { return reference_heightmap(t).max_gradient(); }
};

TEST_F(HeightmapTest, MaxGradientMatchesTheReferenceSearch) {
  for (Target t : {Target::Top, Target::Middle, Target::Bottom}) {
    const ScenePlan p = prepared(scenes::heightmap(t));
    const double reference = max_g(t);  // every pixel, refined to 1e-9 px
    EXPECT_NEAR(static_cast<double>(p.stats().max_gradient), reference, 1e-5 * reference);
  }
}

TEST_F(HeightmapTest, OnTheValleyTowardsTheTargetIsSlippery) {
  // Middle target, at (400, 240): u = 0, so G = 1/2 cone gradient = (-1/2, 0).
  const ScenePlan p = prepared(scenes::heightmap(Target::Middle));
  EXPECT_EQ(p.needs(), Needs::PositionAndDirection);
  const double m = static_cast<double>(p.stats().max_gradient);
  EXPECT_NEAR(amp(p, 400, 240, 1, 0), 0.5 + 0.25 / m, 1e-6);   // downhill: A > 0.5
  EXPECT_NEAR(amp(p, 400, 240, -1, 0), 0.5 - 0.25 / m, 1e-6);  // uphill: A < 0.5
  EXPECT_NEAR(amp(p, 400, 240, 0, 1), 0.5, 1e-7);              // perpendicular: neutral
  EXPECT_NEAR(amp(p, 400, 240, 0, 0), 0.5, 1e-7);              // at rest: neutral
  EXPECT_GT(amp(p, 400, 240, 1, 0), 0.5);
}

TEST_F(HeightmapTest, OffTheValleyMovingBackIsAssisted) {
  // (400, 300): u = 60, dZ_path/du = a^2 u^2 / (1 + a^2 u^2) = 144/145, path flat (middle).
  const ScenePlan p = prepared(scenes::heightmap(Target::Middle));
  const double m = static_cast<double>(p.stats().max_gradient);
  const double r = std::hypot(300.0, 60.0);
  const double gx = 0.5 * (-300.0 / r), gy = 0.5 * (144.0 / 145.0) + 0.5 * (60.0 / r);
  EXPECT_NEAR(amp(p, 400, 300, 0, -1), 0.5 + gy / (2 * m), 1e-6);  // back up towards the valley
  EXPECT_NEAR(amp(p, 400, 300, 0, 1), 0.5 - gy / (2 * m), 1e-6);   // further away: sticky
  EXPECT_NEAR(amp(p, 400, 300, 1, 0), 0.5 - gx / (2 * m), 1e-6);
  EXPECT_LT(amp(p, 400, 300, 0, 1), 0.5);
}

TEST_F(HeightmapTest, AgreesWithDoubleReferenceEverywhere) {
  for (Target t : {Target::Top, Target::Bottom}) {
    const ScenePlan p = prepared(scenes::heightmap(t));
    const double m = max_g(t);
    const reference::ReferenceScene ref = reference_heightmap(t);
    double worst = 0;
    for (int y = 1; y < 480; y += 7) {
      for (int x = 1; x < 800; x += 7) {
        const reference::DVec g = ref.field(x, y);
        for (int k = 0; k < 16; ++k) {
          const double a = 2 * M_PI * k / 16;
          const double ref = 0.5 - (std::cos(a) * g.x + std::sin(a) * g.y) / (2 * m);
          const double got = amp(p, x, y, static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a)));
          worst = std::fmax(worst, std::fabs(got - ref));
        }
      }
    }
    EXPECT_LT(worst * 4095, 0.5) << "max error in DAC LSB";
  }
}

TEST_F(HeightmapTest, TopAndBottomAreMirrorImages) {
  const ScenePlan top = prepared(scenes::heightmap(Target::Top));
  const ScenePlan bottom = prepared(scenes::heightmap(Target::Bottom));
  for (int y = 20; y <= 460; y += 20) {
    for (int x = 0; x < 800; x += 25) {
      const float yf = static_cast<float>(y), xf = static_cast<float>(x);
      EXPECT_NEAR(amp(top, xf, yf, 0.6f, 0.8f), amp(bottom, xf, 480.0f - yf, 0.6f, -0.8f), 1e-4) << x << "," << y;
    }
  }
}

TEST(PilotScenes, TunnelConvergingAndDivergingAreOpposite) {
  TunnelParams t;  // W 60 -> 20 over 400 px from x = 100, s = 1
  const ScenePlan conv = prepared(scenes::steering_tunnel(t, scenes::TunnelMode::Converging));
  const ScenePlan div = prepared(scenes::steering_tunnel(t, scenes::TunnelMode::Diverging));
  const ScenePlan neu = prepared(scenes::steering_tunnel(t, scenes::TunnelMode::Neutral));
  // Below the centre line moving back up (towards it): converging assists, diverging impedes.
  EXPECT_GT(amp(conv, 300, 300, 0, -1), 0.5);
  EXPECT_LT(amp(div, 300, 300, 0, -1), 0.5);
  EXPECT_NEAR(amp(conv, 300, 300, 0, -1) - 0.5, 0.5 - amp(div, 300, 300, 0, -1), 1e-6);
  EXPECT_DOUBLE_EQ(amp(neu, 300, 300, 0, -1), 0.5);
  // On the centre line the valley is flat: 0.5 whatever the direction.
  EXPECT_NEAR(amp(conv, 300, 240, 0, 1), 0.5, 1e-7);
}

TEST(PilotScenes, TunnelGradientMatchesNumericalDerivative) {
  TunnelParams t;
  t.scale = 10.0f;
  const FieldElement e = FieldElement::tunnel_valley(t);
  for (float x : {150.0f, 300.0f, 450.0f}) {
    for (float y : {200.0f, 236.0f, 243.0f, 300.0f}) {
      const float h = 0.01f;
      const double nx = (static_cast<double>(element_height(e, {x + h, y})) - static_cast<double>(element_height(e, {x - h, y}))) / (2.0 * static_cast<double>(h));
      const double ny = (static_cast<double>(element_height(e, {x, y + h})) - static_cast<double>(element_height(e, {x, y - h}))) / (2.0 * static_cast<double>(h));
      const Vec2 g = element_gradient(e, {x, y});
      EXPECT_NEAR(static_cast<double>(g.x), nx, 2e-3) << x << "," << y;
      EXPECT_NEAR(static_cast<double>(g.y), ny, 2e-3) << x << "," << y;
    }
  }
}

TEST(PilotScenes, PilotCValleyIsTwoAtanHalf) {
  // H = |2 atan(u/2) - u| on the middle path: at u = 2, dH/du = (1/4 * 4) / (1 + 1) = 1/2.
  const SceneDefinition s = scenes::pilot_c_valley(Target::Middle);
  EXPECT_EQ(s.rendering, Rendering::Directional);  // a height field, felt by direction
  EXPECT_NEAR(static_cast<double>(element_height(s.elements[0], {400, 242})), std::fabs(2 * std::atan(1.0) - 2), 1e-5);
  EXPECT_NEAR(static_cast<double>(element_gradient(s.elements[0], {400, 242}).y), 0.5, 1e-6);
}

TEST(Texture, PhaseReductionMatchesTheDoubleFormulaEverywhere) {
  // The core reduces the phase to a quarter turn before sinf/cosf; compare
  // with sin/cos of the unreduced phase in double, on the screen, at every
  // quarter-turn boundary, and far off it (|x| up to 1e5, negative too).
  const FieldElement e = FieldElement::sine_texture(160.0f, 120.0f, 20.0f);
  const double kx = 2 * M_PI / 160.0, ky = 2 * M_PI / 120.0;
  const float xs[] = {0.0f, 20.0f, 39.99f, 40.0f, 40.01f, 80.0f, 120.0f, 159.9f, 160.0f, 333.3f, 799.0f,
                      -40.0f, -123.4f, 12345.6f, -99999.5f};
  for (float x : xs) {
    for (float y : {0.0f, 30.0f, 45.5f, 90.0f, 479.0f, -77.7f}) {
      const Vec2 g = element_gradient(e, {x, y});
      const double xd = x, yd = y;
      const double gx = 20.0 * kx * std::cos(kx * xd) * std::sin(ky * yd);
      const double gy = 20.0 * ky * std::sin(kx * xd) * std::cos(ky * yd);
      // float phase of |x| up to 1e5 px: a few ulp of 2 pi x / lambda.
      const double tol = 1e-6 + 2e-7 * (std::fabs(xd) + std::fabs(yd));
      EXPECT_NEAR(static_cast<double>(g.x), gx, tol) << x << ", " << y;
      EXPECT_NEAR(static_cast<double>(g.y), gy, tol) << x << ", " << y;
      const double h = 20.0 * std::sin(kx * xd) * std::sin(ky * yd);
      EXPECT_NEAR(static_cast<double>(element_height(e, {x, y})), h, 20.0 * tol / kx) << x << ", " << y;
    }
  }
}

TEST(Vortex, CirculatesAndPeaksAtTheCorners) {
  const ScenePlan p = prepared(scenes::vortex());
  // |G| = distance from (400, 240): largest at a corner, sqrt(400^2 + 240^2).
  EXPECT_NEAR(static_cast<double>(p.stats().max_gradient), std::hypot(400.0, 240.0), 1e-2);
  // Right of the centre, G = (0, 100): moving down (+y) is "uphill", A < 0.5.
  EXPECT_NEAR(amp(p, 500, 240, 0, 1), 0.5 - 100.0 / (2 * std::hypot(400.0, 240.0)), 1e-5);
  EXPECT_DOUBLE_EQ(amp(p, 400, 240, 1, 0), 0.5);  // the centre
}

TEST(Familiarisation, WindingPathIsSlipperyAndBumpsAlternate) {
  const ScenePlan path = prepared(scenes::familiarisation_path());
  EXPECT_DOUBLE_EQ(amp(path, 100, 360), 1.0);  // on the crest of the sine path
  EXPECT_DOUBLE_EQ(amp(path, 100, 240), 0.0);  // 120 px off it
  const ScenePlan bumps = prepared(scenes::bump_map());
  // Climbing the first bump's slope (x = 0 -> 40 at y = 40) is sticky, descending slippery.
  EXPECT_LT(amp(bumps, 20, 40, 1, 0), 0.5);
  EXPECT_GT(amp(bumps, 20, 40, -1, 0), 0.5);
}

}  // namespace
}  // namespace ff
