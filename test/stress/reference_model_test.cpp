// The double reference itself: its closed-form gradients against central
// differences of its own heights, its max|G| against a dense pixel scan, and
// the strength and DAC numbers of docs/spec.md#amplitude.
#include "reference_model.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "frictionfield/core/scenes.hpp"
#include "stress_random.hpp"
#include "stress_scenes.hpp"

namespace ff::stress {
namespace {

TEST(ReferenceModel, GradientsAreTheDerivativesOfTheHeights) {
  Rng rng(base_seed());
  int compared = 0;
  for (int i = 0; i < 300; ++i) {
    const SceneDefinition s = random_general_scene(rng, false);
    for (int e = 0; e < s.element_count; ++e) {
      const FieldElement& el = s.elements[e];
      if (el.kind == ElementKind::Vortex) continue;  // no height
      const double x = rng.uniform(0.0, 799.0), y = rng.uniform(0.0, 479.0);
      const double h = 1e-5;
      const DVec g = ref_gradient(el, x, y);
      const double gx = (ref_height(el, x + h, y) - ref_height(el, x - h, y)) / (2 * h);
      const double gy = (ref_height(el, x, y + h) - ref_height(el, x, y - h)) / (2 * h);
      // Kinks (cone apex, valley centre, tunnel ends, polyline corners) are
      // measure-zero; a random point misses them by far more than h.
      EXPECT_NEAR(g.x, gx, 1e-5 * (1.0 + std::fabs(gx))) << "kind " << static_cast<int>(el.kind) << " at " << x << "," << y;
      EXPECT_NEAR(g.y, gy, 1e-5 * (1.0 + std::fabs(gy))) << "kind " << static_cast<int>(el.kind) << " at " << x << "," << y;
      ++compared;
    }
  }
  EXPECT_GT(compared, 500);
}

double dense_max(const ReferenceScene& r) {
  double best = 0.0;
  for (int y = 0; y < 480; ++y) {
    for (int x = 0; x < 800; ++x) {
      const DVec g = r.field(x, y);
      best = std::fmax(best, std::hypot(g.x, g.y));
    }
  }
  return best;
}

TEST(ReferenceModel, MaxGradientIsAtLeastTheDensePixelScan) {
  const SceneDefinition scenes_to_check[] = {scenes::heightmap(Target::Top), scenes::heightmap(Target::Middle),
                                             scenes::pilot_c_valley(Target::Bottom), scenes::bump_map(), scenes::vortex()};
  for (const SceneDefinition& s : scenes_to_check) {
    const ReferenceScene r(s);
    const double scan = dense_max(r);
    EXPECT_GE(r.max_gradient(), scan * (1.0 - 1e-12));
    EXPECT_LE(r.max_gradient(), scan * (1.0 + 1e-3));  // the pixel grid is within 0.1 % of the true maximum
  }
  // Hand-derived: the vortex around (400, 240) peaks at the far corners, |(-239, 399)| or |(240, -400)|.
  EXPECT_NEAR(ReferenceScene(scenes::vortex()).max_gradient(), std::hypot(400.0, 240.0), 1e-9);
}

TEST(ReferenceModel, StrengthAndDacFollowTheSpec) {
  AmplitudeSettings a;
  a.strength = 0.66f;
  const ReferenceAmplitude r(a, true);
  EXPECT_NEAR(r.scale(0.0), 0.5 - 0.33, 1e-7);  // [17, 83] V of 100 V
  EXPECT_NEAR(r.scale(1.0), 0.5 + 0.33, 1e-7);
  EXPECT_EQ(r.dac(0.5), 2048);   // round(2047.5) half up
  EXPECT_EQ(r.dac(1.0), 4095);
  EXPECT_EQ(r.dac(0.0), 0);
  a.calibration = DacCalibration::inverted();
  EXPECT_EQ(ReferenceAmplitude(a, true).dac(1.0), 0);
  a.strength = std::nanf("");
  EXPECT_EQ(ReferenceAmplitude(a, true).scale(0.9), 0.5);  // NaN strength: no modulation
}

TEST(ReferenceModel, ThesisTrackerExtrapolatesByTicksAndFilters) {
  ReferenceThesisTracker t;
  DVec p, d;
  t.on_sample({0, 100.0f, 200.0f, true});
  t.on_tick(p, d);  // the first sample passes through, no direction
  EXPECT_EQ(p.x, 100.0);
  EXPECT_EQ(d.x, 0.0);
  t.on_sample({5000, 110.0f, 200.0f, true});  // v_raw = 10 px / 5000 us
  t.on_tick(p, d);  // n = 0: p_ext = 110; alpha(fc) with fc = 20 + 0.0004 |dxhat|
  const double fr = 2000.0, pi = 3.14159265358979323846;
  const double ad = 1.0 / (1.0 + fr / (2 * pi * 25.0));
  const double dxhat = ad * (110.0 - 100.0) * fr;
  const double a = 1.0 / (1.0 + fr / (2 * pi * (20.0 + 0.0004 * dxhat)));
  EXPECT_NEAR(p.x, a * 110.0 + (1 - a) * 100.0, 1e-12);
  EXPECT_EQ(d.x, 1.0);
  t.on_tick(p, d);  // n = 1: p_ext = 110 + 10/5000 * 500 = 111
  const double dxhat2 = ad * (111.0 - (a * 110.0 + (1 - a) * 100.0)) * fr + (1 - ad) * dxhat;
  const double a2 = 1.0 / (1.0 + fr / (2 * pi * (20.0 + 0.0004 * dxhat2)));
  EXPECT_NEAR(p.x, a2 * 111.0 + (1 - a2) * (a * 110.0 + (1 - a) * 100.0), 1e-12);
}

}  // namespace
}  // namespace ff::stress
