#include "frictionfield/core/path_curve.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <new>

#include "support/reference/reference_scene.hpp"

namespace ff {
namespace {

TEST(PathCurve, CubicMatchesSpecAtNamedPoints) {
  const PathCurve top = PathCurve::cubic(-200.0f);
  // Start, middle and end of the top path: 240, 140, 40; slope 0 at both joins.
  EXPECT_FLOAT_EQ(top.at(100.0f).y, 240.0f);
  EXPECT_FLOAT_EQ(top.at(400.0f).y, 140.0f);
  EXPECT_FLOAT_EQ(top.at(700.0f).y, 40.0f);
  EXPECT_FLOAT_EQ(top.at(100.0f).slope, 0.0f);
  EXPECT_FLOAT_EQ(top.at(700.0f).slope, 0.0f);
  // Steepest at the middle: y' = 1.5 T / L = -0.5.
  EXPECT_FLOAT_EQ(top.at(400.0f).slope, -0.5f);
  // Flat outside [100, 700].
  EXPECT_FLOAT_EQ(top.at(20.0f).y, 240.0f);
  EXPECT_FLOAT_EQ(top.at(790.0f).y, 40.0f);
  EXPECT_FLOAT_EQ(top.at(790.0f).slope, 0.0f);
}

TEST(PathCurve, CubicAgreesWithDoubleReferenceEverywhere) {
  for (float T : {-200.0f, 0.0f, 200.0f}) {
    const PathCurve c = PathCurve::cubic(T);
    for (int x = 0; x < 800; x += 3) {
      const CurvePoint p = c.at(static_cast<float>(x));
      EXPECT_NEAR(static_cast<double>(p.y), reference::experiment_path_at(x, T).y, 1e-4) << x;
      EXPECT_NEAR(static_cast<double>(p.slope), reference::experiment_path_at(x, T).slope, 1e-6) << x;
    }
  }
}

TEST(PathCurve, PolylineInterpolatesAndRejectsBadPoints) {
  const Vec2 pts[] = {{100, 240}, {400, 100}, {700, 40}};
  const PathCurve c = PathCurve::polyline(pts, 3);
  ASSERT_EQ(c.count, 3);
  EXPECT_FLOAT_EQ(c.at(250.0f).y, 170.0f);
  EXPECT_FLOAT_EQ(c.at(250.0f).slope, -140.0f / 300.0f);
  EXPECT_FLOAT_EQ(c.at(50.0f).y, 240.0f);
  EXPECT_FLOAT_EQ(c.at(750.0f).y, 40.0f);
  const Vec2 backwards[] = {{100, 240}, {90, 100}};
  EXPECT_EQ(PathCurve::polyline(backwards, 2).count, 0);
  const Vec2 nan_point[] = {{100, 240}, {200, NAN}};
  EXPECT_EQ(PathCurve::polyline(nan_point, 2).count, 0);
}

// Fewer than two points or more than the table holds: an empty polyline,
// which is flat at y = 0 everywhere (the sanitizer build checks it reads no
// point it does not have).
TEST(PathCurve, APolylineOfTooFewOrTooManyPointsIsEmptyAndFlat) {
  Vec2 pts[kMaxPolylinePoints + 1];
  for (int i = 0; i <= kMaxPolylinePoints; ++i) pts[i] = {10.0f * static_cast<float>(i + 1), 240.0f};
  for (const PathCurve& c : {PathCurve::polyline(pts, 1), PathCurve::polyline(pts, 0), PathCurve::polyline(nullptr, 3),
                             PathCurve::polyline(pts, kMaxPolylinePoints + 1)}) {
    EXPECT_EQ(c.kind, CurveKind::Polyline);
    EXPECT_EQ(c.count, 0);
    for (float x : {-5.0f, 0.0f, 5.0f, 100.0f, 799.0f}) {
      EXPECT_EQ(c.at(x).y, 0.0f) << x;
      EXPECT_EQ(c.at(x).slope, 0.0f) << x;
    }
  }
  EXPECT_EQ(PathCurve::polyline(pts, kMaxPolylinePoints).count, kMaxPolylinePoints);
  // Built in memory that held anything (a reused scene slot): still flat at 0,
  // so nothing outside the points it has was read.
  alignas(PathCurve) unsigned char raw[sizeof(PathCurve)];
  std::memset(raw, 0xFF, sizeof raw);
  PathCurve* empty = new (raw) PathCurve;
  empty->kind = CurveKind::Polyline;
  EXPECT_EQ(empty->at(100.0f).y, 0.0f);
  EXPECT_EQ(empty->at(100.0f).slope, 0.0f);
}

TEST(PathCurve, SineHasItsSlope) {
  const PathCurve c = PathCurve::sine(240.0f, 120.0f, 400.0f, 0.0f);
  EXPECT_NEAR(static_cast<double>(c.at(100.0f).y), 360.0, 1e-3);  // quarter wave: crest
  EXPECT_NEAR(static_cast<double>(c.at(100.0f).slope), 0.0, 1e-5);
  EXPECT_NEAR(static_cast<double>(c.at(0.0f).slope), 120.0 * 2 * M_PI / 400.0, 1e-5);
}

}  // namespace
}  // namespace ff
