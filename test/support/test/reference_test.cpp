// The double reference itself: its closed-form gradients against central
// differences of its own heights, its max|G|, paths, profiles and amplitudes
// against hand-derived values, and the strength and DAC numbers of
// docs/spec.md#amplitude.
#include <gtest/gtest.h>

#include <cmath>

#include "stress_random.hpp"
#include "stress_scenes.hpp"
#include "support/reference/reference_amplitude.hpp"
#include "support/reference/reference_scene.hpp"
#include "support/reference/reference_tracker.hpp"
#include "support/reference/spec_scenes.hpp"

namespace ff::reference {
namespace {

using stress::base_seed;
using stress::random_general_scene;
using stress::Rng;
constexpr double kPi = 3.14159265358979323846;

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
      const DVec g = element_gradient(el, x, y);
      const double gx = (element_height(el, x + h, y) - element_height(el, x - h, y)) / (2 * h);
      const double gy = (element_height(el, x, y + h) - element_height(el, x, y - h)) / (2 * h);
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
  const SceneDefinition scenes_to_check[] = {spec::heightmap(-200.0), spec::heightmap(0.0), spec::pilot_c(200.0),
                                             spec::bump_map(), spec::vortex()};
  for (const SceneDefinition& s : scenes_to_check) {
    const ReferenceScene r(s);
    const double scan = dense_max(r);
    EXPECT_GE(r.max_gradient(), scan * (1.0 - 1e-12));
    EXPECT_LE(r.max_gradient(), scan * (1.0 + 1e-3));  // the pixel grid is within 0.1 % of the true maximum
  }
  // Hand-derived: the vortex around (400, 240) peaks at the far corners, |(-239, 399)| or |(240, -400)|.
  EXPECT_NEAR(ReferenceScene(spec::vortex()).max_gradient(), std::hypot(400.0, 240.0), 1e-9);
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
  const double fr = 2000.0, pi = kPi;
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

TEST(ReferenceScene, EveryPixelSearchMatchesHandDerivedMaxima) {
  // Vortex around (400, 240): the farthest screen point is the corner (0, 0).
  EXPECT_NEAR(ReferenceScene(spec::vortex(), kEveryPixel).max_gradient(), std::hypot(400.0, 240.0), 1e-9);
  // Bumps h sin(kx) sin(ky): |G| = h k at most, h = 20, k = 2 pi / 160.
  EXPECT_NEAR(ReferenceScene(spec::bump_map(), kEveryPixel).max_gradient(), 20.0 * 2.0 * kPi / 160.0, 1e-9);
  // Heightmap middle: valley and cone gradients align at (700, 0): u = -240,
  // a u = -48, |dZ_path/du| = 48^2 / (1 + 48^2) = 2304 / 2305, |G_cone| = 1.
  // (a = 0.2f widened: 48 becomes 48.0000007, 3e-10 relative.)
  EXPECT_NEAR(ReferenceScene(spec::heightmap(0.0), kEveryPixel).max_gradient(), 0.5 * (1.0 + 2304.0 / 2305.0), 1e-9);
}

TEST(ReferenceScene, VortexFieldIsTheRotatedOffset) {
  const DVec g = ReferenceScene(spec::vortex()).field(410.0, 250.0);
  EXPECT_DOUBLE_EQ(g.x, -10.0);
  EXPECT_DOUBLE_EQ(g.y, 10.0);
}

TEST(ReferenceScene, HeightmapAmplitudeOnTheFlatStart) {
  // At (50, 240) the middle path is flat and the finger is on it (u = 0):
  // G = 1/2 (0, 0) + 1/2 (-1, 0). Moving right, towards the target, is downhill.
  ReferenceScene scene(spec::heightmap(0.0));
  const double m = 0.5 * (1.0 + 2304.0 / 2305.0);
  scene.use_max_gradient(m);
  EXPECT_NEAR(scene.raw_amplitude(50.0, 240.0, 1.0, 0.0), 0.5 + 0.25 / m, 1e-12);
  EXPECT_NEAR(scene.raw_amplitude(50.0, 240.0, -1.0, 0.0), 0.5 - 0.25 / m, 1e-12);
  EXPECT_NEAR(scene.raw_amplitude(50.0, 240.0, 0.0, 1.0), 0.5, 1e-12);
}

TEST(ReferenceScene, FrictionmapProfileIsTheQuinticBand) {
  // Left of x = 100 the top path is flat at y = 240: A = S5((30 - |u|) / 20).
  const ReferenceScene scene(spec::frictionmap(-200.0));
  EXPECT_DOUBLE_EQ(scene.profile(50.0, 240.0), 1.0);
  EXPECT_DOUBLE_EQ(scene.profile(50.0, 250.0), 1.0);
  EXPECT_NEAR(scene.profile(50.0, 260.0), 0.5, 1e-12);
  EXPECT_NEAR(scene.profile(50.0, 215.0), 6.0 / 1024 - 15.0 / 256 + 10.0 / 64, 1e-12);
  EXPECT_DOUBLE_EQ(scene.profile(50.0, 270.0), 0.0);
}

TEST(ReferencePath, CubicJoinsFlatAndEndsAtTheTarget) {
  EXPECT_DOUBLE_EQ(experiment_path_at(100.0, -200.0).y, 240.0);
  EXPECT_DOUBLE_EQ(experiment_path_at(700.0, -200.0).y, 40.0);
  EXPECT_DOUBLE_EQ(experiment_path_at(50.0, -200.0).y, 240.0);
  EXPECT_DOUBLE_EQ(experiment_path_at(750.0, -200.0).y, 40.0);
  EXPECT_NEAR(experiment_path_at(400.0, -200.0).y, 140.0, 1e-12);            // half the rise at the middle
  EXPECT_NEAR(experiment_path_at(400.0, -200.0).slope, 1.5 * -200.0 / 600.0, 1e-12);  // 3T / (2L)
  EXPECT_NEAR(experiment_path_at(100.0, -200.0).slope, 0.0, 1e-12);
  EXPECT_NEAR(experiment_path_at(700.0, -200.0).slope, 0.0, 1e-12);
  // The same curve as scene data.
  PathCurve c;
  c.kind = CurveKind::Cubic;
  c.x0 = 100.0f;
  c.y0 = 240.0f;
  c.length = 600.0f;
  c.rise = -200.0f;
  EXPECT_DOUBLE_EQ(path_at(c, 400.0).y, experiment_path_at(400.0, -200.0).y);
}

TEST(ReferencePath, SineAndPolylineByHand) {
  PathCurve sine;
  sine.kind = CurveKind::Sine;
  sine.x0 = 0.0f;
  sine.y0 = 240.0f;
  sine.amplitude = 120.0f;
  sine.wavelength = 400.0f;
  EXPECT_NEAR(path_at(sine, 100.0).y, 360.0, 1e-9);  // a quarter wave up
  EXPECT_NEAR(path_at(sine, 0.0).slope, 120.0 * 2.0 * kPi / 400.0, 1e-12);
  PathCurve poly;
  poly.kind = CurveKind::Polyline;
  poly.count = 3;
  poly.points[0] = {100.0f, 100.0f};
  poly.points[1] = {200.0f, 300.0f};
  poly.points[2] = {400.0f, 300.0f};
  EXPECT_DOUBLE_EQ(path_at(poly, 50.0).y, 100.0);   // flat before the first point
  EXPECT_DOUBLE_EQ(path_at(poly, 150.0).y, 200.0);  // halfway up the first segment
  EXPECT_DOUBLE_EQ(path_at(poly, 150.0).slope, 2.0);
  EXPECT_DOUBLE_EQ(path_at(poly, 500.0).y, 300.0);  // flat after the last
}

}  // namespace
}  // namespace ff::reference
