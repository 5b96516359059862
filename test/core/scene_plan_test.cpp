// Preparation: what a plan keeps, what it refuses, and tables against the closed form.
#include "frictionfield/core/scene_plan.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <memory>
#include <vector>

#include "frictionfield/core/haptic_pipeline.hpp"
#include "frictionfield/core/scenes.hpp"

namespace ff {
namespace {

struct Arena {
  std::vector<uint32_t> words = std::vector<uint32_t>(kTableSlotBytes / 4);
  void* data() { return words.data(); }
  size_t size() const { return words.size() * 4; }
};

// Max |amplitude difference| in DAC LSB between two plans over a grid and 16
// directions, skipping points within `skip_px` of `skip`.
double max_lsb_difference(const ScenePlan& a, const ScenePlan& b, Vec2 skip = {-1e9f, -1e9f}, float skip_px = 0.0f,
                          double* rms = nullptr, float edge_px = 0.0f) {
  double worst = 0, sum2 = 0;
  long n = 0;
  for (int y = 0; y < 480; y += 3) {
    for (int x = 0; x < 800; x += 3) {
      const Vec2 p{static_cast<float>(x) + 0.37f, static_cast<float>(y) + 0.61f};
      if (length(p - skip) < skip_px) continue;
      if (p.x < edge_px || p.y < edge_px || p.x > kScreenMaxX - edge_px || p.y > kScreenMaxY - edge_px) continue;
      for (int k = 0; k < 16; ++k) {
        const float ang = 2.0f * kPi * static_cast<float>(k) / 16.0f;
        const Vec2 d{std::cos(ang), std::sin(ang)};
        const double e = std::fabs(static_cast<double>(a.amplitude(p, d)) - static_cast<double>(b.amplitude(p, d))) * 4095.0;
        worst = std::fmax(worst, e);
        sum2 += e * e;
        ++n;
      }
    }
  }
  if (rms) *rms = std::sqrt(sum2 / static_cast<double>(n));
  return worst;
}

TEST(ScenePlan, DropsZeroWeightTermsAndReportsMemory) {
  SceneDefinition s = scenes::heightmap(Target::Top);
  s.add(FieldElement::vortex({400, 240}, 0.0f));
  ScenePlan plan;
  ASSERT_EQ(plan.prepare(s, nullptr, 0), PrepareStatus::Ok);
  ScenePlan reference;
  ASSERT_EQ(reference.prepare(scenes::heightmap(Target::Top), nullptr, 0), PrepareStatus::Ok);
  EXPECT_EQ(max_lsb_difference(plan, reference), 0.0);
  EXPECT_EQ(plan.stats().table_bytes, 0u);
  EXPECT_EQ(plan.stats().plan_bytes, sizeof(ScenePlan));
  EXPECT_GT(plan.stats().gradient_evaluations, 400u);
  EXPECT_LT(plan.stats().gradient_evaluations, 1500u);  // no full-screen scan: 2 ms on the M4
}

TEST(ScenePlan, RefusesBadScenesAndKeepsTheOldOne) {
  ScenePlan plan;
  ASSERT_EQ(plan.prepare(scenes::frictionmap(Target::Middle), nullptr, 0), PrepareStatus::Ok);
  SceneDefinition bad = scenes::heightmap(Target::Top);
  bad.elements[0].valley.a = NAN;
  EXPECT_EQ(plan.prepare(bad, nullptr, 0), PrepareStatus::InvalidParameter);
  bad = scenes::heightmap(Target::Top);
  bad.elements[1].weight = INFINITY;
  EXPECT_EQ(plan.prepare(bad, nullptr, 0), PrepareStatus::InvalidParameter);
  bad = scenes::heightmap(Target::Top);
  bad.element_count = 9;
  EXPECT_EQ(plan.prepare(bad, nullptr, 0), PrepareStatus::TooManyElements);
  bad = scenes::heightmap(Target::Top);
  bad.evaluation = Evaluation::Table;
  bad.table.spacing_px = 1.0f;  // 800 x 480 x 2 x int16 = 1.5 MB: over the slot
  Arena arena;
  EXPECT_EQ(plan.prepare(bad, arena.data(), arena.size()), PrepareStatus::TableTooLarge);
  // Still the frictionmap.
  EXPECT_EQ(plan.needs(), Needs::Position);
  EXPECT_FLOAT_EQ(plan.amplitude({400, 240}, {}), 1.0f);
}

// The protocol carries a polyline's count as a byte: a path of fewer than
// two points, or of more than the curve holds, is refused, not rendered.
TEST(ScenePlan, RefusesAPathOfTooFewOrTooManyPoints) {
  const Vec2 pts[] = {{100, 240}, {400, 100}, {700, 40}};
  SceneDefinition s;
  s.rendering = Rendering::Directional;
  ASSERT_TRUE(s.add(FieldElement::path_sink(PathCurve::polyline(pts, 3), 20.0f)));
  ScenePlan plan;
  ASSERT_EQ(plan.prepare(s, nullptr, 0), PrepareStatus::Ok);
  for (int count : {0, 1, kMaxPolylinePoints + 1, 255}) {
    s.elements[0].valley.curve.count = static_cast<uint8_t>(count);
    EXPECT_EQ(plan.prepare(s, nullptr, 0), PrepareStatus::InvalidParameter) << count;
  }
  // Nor a point that is not finite, or one that turns back in x.
  for (Vec2 middle : {Vec2{NAN, 100}, Vec2{400, INFINITY}, Vec2{100, 100}, Vec2{50, 100}}) {
    s.elements[0].valley.curve = PathCurve::polyline(pts, 3);
    s.elements[0].valley.curve.points[1] = middle;
    EXPECT_EQ(plan.prepare(s, nullptr, 0), PrepareStatus::InvalidParameter) << middle.x << " " << middle.y;
  }
}

TEST(ScenePlan, RefusesANonFiniteConstantOrBias) {
  ScenePlan plan;
  for (float bad : {NAN, INFINITY, -INFINITY}) {
    SceneDefinition s = scenes::neutral();
    s.constant = bad;
    EXPECT_EQ(plan.prepare(s, nullptr, 0), PrepareStatus::InvalidParameter) << bad;
    s = scenes::frictionmap(Target::Middle);
    s.bias = bad;
    EXPECT_EQ(plan.prepare(s, nullptr, 0), PrepareStatus::InvalidParameter) << bad;
  }
}

// A table of heights cannot hold a vortex (it has no height), but a vortex
// of weight 0 contributes nothing and is dropped before that is asked.
TEST(ScenePlan, AHeightTableRefusesAVortexUnlessItWeighsNothing) {
  SceneDefinition s = scenes::heightmap(Target::Top);
  s.evaluation = Evaluation::Table;
  s.table = {8.0f, TableStorage::Float32, TableSource::HeightCentralDifferences};
  ASSERT_TRUE(s.add(FieldElement::vortex({400, 240}, 0.0f)));
  ScenePlan plan;
  Arena arena;
  EXPECT_EQ(plan.prepare(s, arena.data(), arena.size()), PrepareStatus::Ok);
  s.elements[s.element_count - 1].weight = 1e-3f;
  EXPECT_EQ(plan.prepare(s, arena.data(), arena.size()), PrepareStatus::InvalidParameter);
  s.table.source = TableSource::TabulatedGradient;  // a gradient table holds it
  EXPECT_EQ(plan.prepare(s, arena.data(), arena.size()), PrepareStatus::Ok);
}

// The frictionmap (position only) from a float table of 8 px: 101 x 61 nodes.
SceneDefinition frictionmap_table() {
  SceneDefinition s = scenes::frictionmap(Target::Middle);
  s.evaluation = Evaluation::Table;
  s.table = {8.0f, TableStorage::Float32, TableSource::TabulatedGradient};
  return s;
}

// A position-only table costs one evaluation per node and no search.
TEST(ScenePlan, APositionTableCountsOneEvaluationPerNode) {
  const SceneDefinition s = frictionmap_table();
  ScenePlan plan;
  Arena arena;
  ASSERT_EQ(plan.prepare(s, arena.data(), arena.size()), PrepareStatus::Ok);
  EXPECT_EQ(plan.stats().table_cols, 101);
  EXPECT_EQ(plan.stats().table_rows, 61);
  EXPECT_EQ(plan.stats().gradient_evaluations, 101u * 61u);
}

// Only a directional scene has a direction field: a position-only table is
// never read as one (it holds one channel, not two; the memory after it
// holds NaN here).
TEST(ScenePlan, APositionOnlySceneHasNoDirectionField) {
  const SceneDefinition s = frictionmap_table();
  ScenePlan plan;
  Arena arena;
  std::fill(arena.words.begin(), arena.words.end(), 0x7FC00000u);  // NaN
  ASSERT_EQ(plan.prepare(s, arena.data(), arena.size()), PrepareStatus::Ok);
  for (Vec2 p : {Vec2{0, 0}, Vec2{400, 240}, Vec2{800, 480}, Vec2{799, 1}}) {
    EXPECT_EQ(plan.normalized_gradient(p).x, 0.0f) << p.x << " " << p.y;
    EXPECT_EQ(plan.normalized_gradient(p).y, 0.0f) << p.x << " " << p.y;
  }
}

// A tunnel whose narrow end lies off the screen is steepest there, but only
// the screen is rendered: max|G| is the screen's, against a 1 px scan of it.
TEST(ScenePlan, MaxGradientIsTheScreensNotATunnelEndsOffIt) {
  TunnelParams t;
  t.x_start = -100.0f;
  t.length = 600.0f;
  t.width_start = 5.0f;
  t.width_end = 60.0f;
  SceneDefinition s;
  s.rendering = Rendering::Directional;
  ASSERT_TRUE(s.add(FieldElement::tunnel_valley(t)));
  ScenePlan plan;
  ASSERT_EQ(plan.prepare(s, nullptr, 0), PrepareStatus::Ok);
  double scanned = 0.0;
  for (int y = 0; y <= 480; ++y) {
    for (int x = 0; x <= 800; ++x) {
      const Vec2 g = plan.field({static_cast<float>(x), static_cast<float>(y)});
      scanned = std::fmax(scanned, std::hypot(static_cast<double>(g.x), static_cast<double>(g.y)));
    }
  }
  const double found = static_cast<double>(plan.stats().max_gradient);
  EXPECT_GT(found, scanned * (1.0 - 1e-4));
  EXPECT_LT(found, scanned * (1.0 + 1e-3));
}

TEST(ScenePlan, FlatFieldRendersNeutral) {
  SceneDefinition s;
  s.rendering = Rendering::Directional;
  ScenePlan plan;
  ASSERT_EQ(plan.prepare(s, nullptr, 0), PrepareStatus::Ok);
  EXPECT_EQ(plan.stats().max_gradient, 0.0f);
  EXPECT_FLOAT_EQ(plan.amplitude({100, 100}, {1, 0}), 0.5f);
}

TEST(ScenePlan, NonFiniteInputsGiveFiniteAmplitude) {
  ScenePlan plan;
  ASSERT_EQ(plan.prepare(scenes::heightmap(Target::Bottom), nullptr, 0), PrepareStatus::Ok);
  for (Vec2 p : {Vec2{NAN, 5}, Vec2{INFINITY, 5}, Vec2{1e30f, -1e30f}, Vec2{700, 440}}) {
    for (Vec2 d : {Vec2{NAN, 0}, Vec2{1, 0}, Vec2{INFINITY, 0}, Vec2{1e30f, 1e30f}}) {
      const float a = plan.amplitude(p, d);
      EXPECT_TRUE(std::isfinite(a));
      EXPECT_GE(a, 0.0f);
      EXPECT_LE(a, 1.0f);
    }
  }
  EXPECT_FLOAT_EQ(plan.amplitude({700, 440}, {1, 0}), 0.5f);  // the cone's apex
}

TEST(ScenePlan, GeneralSceneOfSinksPathsAndVortexPreparesAndIsBounded) {
  SceneDefinition s;
  s.rendering = Rendering::Directional;
  s.add(FieldElement::point_sink({200, 100}, 1.0f));
  s.add(FieldElement::point_sink({600, 400}, -0.5f));  // a source
  const Vec2 pts[] = {{0, 300}, {300, 200}, {799, 250}};
  s.add(FieldElement::path_sink(PathCurve::polyline(pts, 3), 0.2f, 0.7f));
  s.add(FieldElement::vortex({400, 240}, 0.002f));
  s.add(FieldElement::saddle({400, 240}, 0.001f));
  s.add(FieldElement::sine_texture(100, 80, 5, 0.3f));
  ScenePlan plan;
  ASSERT_EQ(plan.prepare(s, nullptr, 0), PrepareStatus::Ok);
  // |G_norm| <= 1/2 everywhere on a fine grid: the max search really found the max.
  double worst = 0;
  for (int y = 0; y < 480; ++y)
    for (int x = 0; x < 800; ++x)
      worst = std::fmax(worst, static_cast<double>(length(plan.normalized_gradient({static_cast<float>(x), static_cast<float>(y)}))));
  EXPECT_LE(worst, 0.5 + 1e-6);
  EXPECT_GE(worst, 0.5 - 1e-3);
}

struct TableCase {
  float spacing;
  TableStorage storage;
  TableSource source;
  double max_lsb;  // stated bound, away from the cone apex
  double rms_lsb;
};

class HeightmapTable : public ::testing::TestWithParam<TableCase> {};

TEST_P(HeightmapTable, StaysWithinItsStatedBound) {
  const TableCase c = GetParam();
  ScenePlan closed;
  ASSERT_EQ(closed.prepare(scenes::heightmap(Target::Top), nullptr, 0), PrepareStatus::Ok);
  SceneDefinition s = scenes::heightmap(Target::Top);
  s.evaluation = Evaluation::Table;
  s.table = {c.spacing, c.storage, c.source};
  Arena arena;
  ScenePlan table;
  ASSERT_EQ(table.prepare(s, arena.data(), arena.size()), PrepareStatus::Ok);
  EXPECT_EQ(table.stats().table_bytes,
            GridTable::bytes_needed(c.spacing, c.source == TableSource::TabulatedGradient ? 2 : 1, c.storage));
  double rms = 0;
  // The cone's apex is a kink no table resolves: bounds hold beyond two cells of it.
  // A height table's central differences turn one-sided within one spacing
  // of the screen's edge (HeightTableIsOneSidedAtTheEdges): checked there.
  const float edge = c.source == TableSource::HeightCentralDifferences ? c.spacing : 0.0f;
  const double worst = max_lsb_difference(table, closed, target_point(Target::Top), 2.0f * c.spacing, &rms, edge);
  EXPECT_LE(worst, c.max_lsb);
  EXPECT_LE(rms, c.rms_lsb);
  RecordProperty("max_lsb", std::to_string(worst));
  std::printf("table %.0f px %s %s: max %.2f LSB, rms %.3f LSB, %u bytes\n", static_cast<double>(c.spacing),
              c.storage == TableStorage::Int16 ? "int16" : "float",
              c.source == TableSource::TabulatedGradient ? "gradient" : "height", worst, rms, table.stats().table_bytes);
}

INSTANTIATE_TEST_SUITE_P(
    Spacings, HeightmapTable,
    // Bounds measured on this grid plus ~20 %: the valley (a = 1/5) turns its
    // slope over ~5 px, which bilinear tables at >= 4 px cannot follow; that is
    // why closed form is every built-in scene's default (docs/benchmarks.md).
    ::testing::Values(TableCase{4.0f, TableStorage::Int16, TableSource::TabulatedGradient, 100.0, 5.5},
                      TableCase{8.0f, TableStorage::Float32, TableSource::TabulatedGradient, 170.0, 11.5},
                      TableCase{8.0f, TableStorage::Int16, TableSource::TabulatedGradient, 170.0, 11.5},
                      TableCase{16.0f, TableStorage::Int16, TableSource::TabulatedGradient, 400.0, 34.0},
                      TableCase{4.0f, TableStorage::Float32, TableSource::HeightCentralDifferences, 170.0, 9.0}));

TEST(ScenePlan, FrictionmapTableMatchesClosedForm) {
  ScenePlan closed;
  ASSERT_EQ(closed.prepare(scenes::frictionmap(Target::Bottom), nullptr, 0), PrepareStatus::Ok);
  SceneDefinition s = scenes::frictionmap(Target::Bottom);
  s.evaluation = Evaluation::Table;
  s.table = {4.0f, TableStorage::Int16, TableSource::TabulatedGradient};
  Arena arena;
  ScenePlan table;
  ASSERT_EQ(table.prepare(s, arena.data(), arena.size()), PrepareStatus::Ok);
  EXPECT_EQ(table.needs(), Needs::Position);
  double rms = 0;
  EXPECT_LE(max_lsb_difference(table, closed, {}, 0.0f, &rms), 160.0);  // measured 133: S5 over 20 px
  EXPECT_LE(rms, 22.0);  // measured 18.8
}

// The plane Z = gx x + gy y sampled at 10 px over the screen (nodes 0 .. 800
// by 0 .. 480) into `z`, as a directional scene of a float table.
SceneDefinition sampled_plane(std::vector<float>& z, float gx, float gy) {
  const uint16_t cols = 81, rows = 49;
  z.assign(cols * rows, 0.0f);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) z[r * cols + c] = 10.0f * (gx * static_cast<float>(c) + gy * static_cast<float>(r));
  SceneDefinition s;
  s.rendering = Rendering::Directional;
  s.sampled = {z.data(), cols, rows, 10.0f};
  s.table.storage = TableStorage::Float32;
  return s;
}

TEST(ScenePlan, SampledHeightMapGradientByCentralDifferences) {
  // A plane Z = 0.5 x - 0.25 y sampled at 10 px: G = (0.5, -0.25) everywhere inside.
  std::vector<float> z;
  SceneDefinition s = sampled_plane(z, 0.5f, -0.25f);
  Arena arena;
  ScenePlan plan;
  ASSERT_EQ(plan.prepare(s, arena.data(), arena.size()), PrepareStatus::Ok);
  const Vec2 g = plan.field({400, 240});
  EXPECT_NEAR(static_cast<double>(g.x), 0.5, 1e-4);
  EXPECT_NEAR(static_cast<double>(g.y), -0.25, 1e-4);
  z[100] = NAN;
  EXPECT_EQ(plan.prepare(s, arena.data(), arena.size()), PrepareStatus::InvalidSampledMap);
}

TEST(ScenePlan, RefusesAHeightTableThatOverflows) {
  // A saddle centred 1e20 px away: Z = ((x - xc)^2 - (y - yc)^2) / 2 is
  // (1e40 - 1e40) / 2 in float, inf - inf = NaN at every node, so every
  // central difference is NaN and the scene would render 0.5 everywhere.
  ScenePlan plan;
  ASSERT_EQ(plan.prepare(scenes::heightmap(Target::Top), nullptr, 0), PrepareStatus::Ok);
  SceneDefinition s;
  s.rendering = Rendering::Directional;
  s.add(FieldElement::saddle({1e20f, 1e20f}));
  s.add(FieldElement::point_sink({400.0f, 240.0f}, 1e-3f));
  s.evaluation = Evaluation::Table;
  s.table = {8.0f, TableStorage::Float32, TableSource::HeightCentralDifferences};
  Arena arena;
  EXPECT_EQ(plan.prepare(s, arena.data(), arena.size()), PrepareStatus::NonFiniteField);
  EXPECT_STRNE(to_string(PrepareStatus::NonFiniteField), "?");
  EXPECT_EQ(plan.needs(), Needs::PositionAndDirection);  // the old scene stays
  EXPECT_GT(plan.stats().max_gradient, 0.9f);
  // The same saddle in closed form has a finite gradient (d, not d^2): fine.
  s.evaluation = Evaluation::ClosedForm;
  EXPECT_EQ(plan.prepare(s, nullptr, 0), PrepareStatus::Ok);
}

TEST(ScenePlan, RefusesAClosedFormFieldThatOverflows) {
  // Two saddles centred at x = 3e38: each G_x = x - 3e38, so the sum is
  // about -6e38 on the whole screen, past FLT_MAX = 3.4e38: -inf, and the
  // normalised gradient would be NaN (0 * inf). Found by the scene_file fuzzer.
  ScenePlan plan;
  ASSERT_EQ(plan.prepare(scenes::heightmap(Target::Top), nullptr, 0), PrepareStatus::Ok);
  SceneDefinition twice;
  twice.rendering = Rendering::Directional;
  twice.add(FieldElement::saddle({3e38f, 0.0f}));
  twice.add(FieldElement::saddle({3e38f, 0.0f}));
  EXPECT_EQ(plan.prepare(twice, nullptr, 0), PrepareStatus::NonFiniteField);
  EXPECT_EQ(plan.needs(), Needs::PositionAndDirection);  // the old scene stays
  EXPECT_GT(plan.stats().max_gradient, 0.9f);
  // One saddle at (3e38, 3e38): both components (-3e38, 3e38 - y) are finite
  // but |G| = 3e38 sqrt(2) = 4.2e38 is not: refused as well.
  SceneDefinition corner;
  corner.rendering = Rendering::Directional;
  corner.add(FieldElement::saddle({3e38f, 3e38f}));
  EXPECT_EQ(plan.prepare(corner, nullptr, 0), PrepareStatus::NonFiniteField);
  // One saddle at (3e38, 0): |G| is about 3e38, inside float: prepared.
  SceneDefinition once;
  once.rendering = Rendering::Directional;
  once.add(FieldElement::saddle({3e38f, 0.0f}));
  ASSERT_EQ(plan.prepare(once, nullptr, 0), PrepareStatus::Ok);
  EXPECT_TRUE(is_finite(plan.normalized_gradient({400.0f, 240.0f})));
  // A lone texture of height 1e38 and wavelength 100 px: max|G| =
  // 1e38 * 2 pi / 100 = 6.283e36, finite although 1e38 * 2 pi is not.
  SceneDefinition bumps;
  bumps.rendering = Rendering::Directional;
  bumps.add(FieldElement::sine_texture(100.0f, 100.0f, 1e38f));
  ASSERT_EQ(plan.prepare(bumps, nullptr, 0), PrepareStatus::Ok);
  EXPECT_NEAR(static_cast<double>(plan.stats().max_gradient) / 6.283185e36, 1.0, 1e-5);
}

// The review's worst scenes: valleys along a 16-point zigzag (the dearest
// element: a 15-segment walk per evaluation).
PathCurve zigzag() {
  const Vec2 pts[16] = {{0, 100}, {50, 300}, {100, 120}, {150, 330}, {200, 90}, {250, 360}, {300, 80}, {350, 380},
                        {400, 70}, {450, 390}, {500, 60}, {550, 400}, {600, 50}, {650, 410}, {700, 40}, {750, 420}};
  return PathCurve::polyline(pts, 16);
}

SceneDefinition zigzag_valleys(int count, float weight) {
  SceneDefinition s;
  s.rendering = Rendering::Directional;
  for (int i = 1; i <= count; ++i) s.add(FieldElement::path_sink(zigzag(), 0.1f * static_cast<float>(i), weight));
  return s;
}

TEST(ScenePlan, RefusesTheReviewsWorstScenesAsTooCostlyToPrepare) {
  // Measured under qemu before the budget: 127.5 M, 260.7 M and 68.7 M M4
  // instructions, past the 1 s hardware watchdog at 2 cycles per instruction.
  // 7 valleys + a 16 px texture: a 16 / 8 = 2 px scan, (799 / 2 + 2) x
  // (479 / 2 + 2) = 401 x 241 = 96,641 evaluations of 8 terms at 120 + 8 x 220
  // = 1,880 instructions: 182 M > 36 M.
  SceneDefinition closed = zigzag_valleys(7, 1.0f);
  closed.add(FieldElement::sine_texture(16, 16, 1));
  SceneDefinition tiny = zigzag_valleys(7, 1e-20f);  // |G|^2 underflows: was searched twice
  tiny.add(FieldElement::sine_texture(16, 16, 1e-20f));
  // 8 valleys, 4 px int16 table: 201 x 121 nodes, twice (the range first),
  // at 200 + 8 x 220 = 1,960: 95.3 M > 36 M.
  SceneDefinition table = zigzag_valleys(8, 1.0f);
  table.evaluation = Evaluation::Table;
  table.table = {4.0f, TableStorage::Int16, TableSource::TabulatedGradient};
  SceneDefinition heights = table;
  heights.table.source = TableSource::HeightCentralDifferences;
  Arena arena;
  for (const SceneDefinition* s : {&closed, &tiny, &table, &heights}) {
    ScenePlan plan;
    ASSERT_EQ(plan.prepare(scenes::heightmap(Target::Top), nullptr, 0), PrepareStatus::Ok);
    EXPECT_EQ(plan.prepare(*s, arena.data(), arena.size()), PrepareStatus::TooCostlyToPrepare);
    // Refused before any work, and the old scene stays.
    EXPECT_EQ(plan.stats().gradient_evaluations, 770u);
    EXPECT_EQ(plan.needs(), Needs::PositionAndDirection);
  }
  EXPECT_STRNE(to_string(PrepareStatus::TooCostlyToPrepare), "?");
  // The host's pipeline (ffctl, ff-sim) refuses it the same way.
  auto pipeline = std::make_unique<HapticPipeline>();
  Condition c;
  c.scene = closed;
  EXPECT_EQ(pipeline->set_condition(c), PrepareStatus::TooCostlyToPrepare);
}

TEST(ScenePlan, CountedPreparationWorkStaysWithinTheBudget) {
  // Accepted scenes spend at most the budget, priced from their counted
  // evaluations: 7 point sinks + a 48 px texture (a 6 px scan, 135 x 81 =
  // 10,935 evaluations + 6 x 512 compass at most, x 1,880 = 26.3 M: fits);
  // the review's 7 valleys with a 40 px texture instead (a 5 px scan, 161 x 97
  // = 15,617 + 7 x 15 x 4 seeds + 3,072 = 19,109 x 1,880 = 35.9 M: just fits;
  // 21.3 M instructions under qemu); an 8 px int16 table of the 8 valleys
  // (101 x 61 nodes x 2 x 1,960 = 24.2 M + a 32 px search of the table, 3,968
  // x 720 = 2.9 M); and every built-in scene.
  SceneDefinition textured;
  textured.rendering = Rendering::Directional;
  for (int i = 0; i < 7; ++i) textured.add(FieldElement::point_sink({100.0f * static_cast<float>(i + 1), 240.0f}));
  textured.add(FieldElement::sine_texture(48, 48, 10));
  SceneDefinition valleys_textured = zigzag_valleys(7, 1.0f);
  valleys_textured.add(FieldElement::sine_texture(40, 40, 1));
  SceneDefinition table = zigzag_valleys(8, 1.0f);
  table.evaluation = Evaluation::Table;
  table.table = {8.0f, TableStorage::Int16, TableSource::TabulatedGradient};
  std::vector<SceneDefinition> accepted = {textured,           valleys_textured, table,
                                           scenes::neutral(),  scenes::familiarisation_path(),
                                           scenes::bump_map(), scenes::vortex()};
  for (Target t : {Target::Top, Target::Middle, Target::Bottom}) {
    accepted.push_back(scenes::heightmap(t));
    accepted.push_back(scenes::frictionmap(t));
    accepted.push_back(scenes::pilot_c_valley(t));
  }
  for (scenes::TunnelMode mode : {scenes::TunnelMode::Converging, scenes::TunnelMode::Diverging}) {
    accepted.push_back(scenes::steering_tunnel(TunnelParams{}, mode));
  }
  Arena arena;
  for (const SceneDefinition& s : accepted) {
    ScenePlan plan;
    ASSERT_EQ(plan.prepare(s, arena.data(), arena.size()), PrepareStatus::Ok);
    EXPECT_LE(plan.stats().modelled_instructions, kMaxPreparationInstructions);
  }
  ScenePlan plan;
  ASSERT_EQ(plan.prepare(textured, nullptr, 0), PrepareStatus::Ok);
  // 10,935 scan evaluations and a few dozen per compass climb, 1,880 each.
  EXPECT_GE(plan.stats().gradient_evaluations, 10935u);
  EXPECT_LE(plan.stats().gradient_evaluations, 10935u + 6u * 512u);
  EXPECT_EQ(plan.stats().modelled_instructions, plan.stats().gradient_evaluations * 1880u);
}

TEST(ScenePlan, RefusesASecondScaledSearchPastTheBudget) {
  // The textured scene above with every |G| near 1e-20: |G|^2 underflows, so
  // the search is run again scaled. One search fits (<= 26.3 M), two do not
  // (>= 10,935 x 1,880 = 20.6 M spent + 26.3 M): refused rather than
  // stalling the loop.
  SceneDefinition tiny;
  tiny.rendering = Rendering::Directional;
  for (int i = 0; i < 7; ++i) {
    tiny.add(FieldElement::point_sink({100.0f * static_cast<float>(i + 1), 240.0f}, 1e-20f));
  }
  tiny.add(FieldElement::sine_texture(48, 48, 1e-20f));
  ScenePlan plan;
  EXPECT_EQ(plan.prepare(tiny, nullptr, 0), PrepareStatus::TooCostlyToPrepare);
  // Two point sinks at 1e-20 beside a flat texture of weight 1 (the weights
  // are normalised by 1: the sinks' |G| stays near 1e-20): a 32 px search
  // (26 x 16 = 416 + 3,072 at most, x 780 = 2.7 M) fits twice; max|G| = 2e-20 beside
  // both, where their unit pulls add.
  SceneDefinition pair;
  pair.rendering = Rendering::Directional;
  pair.add(FieldElement::point_sink({300.0f, 240.0f}, 1e-20f));
  pair.add(FieldElement::point_sink({500.0f, 240.0f}, 1e-20f));
  pair.add(FieldElement::sine_texture(4000, 4000, 1e-30f));
  ASSERT_EQ(plan.prepare(pair, nullptr, 0), PrepareStatus::Ok);
  EXPECT_LE(plan.stats().modelled_instructions, kMaxPreparationInstructions);
  EXPECT_NEAR(plan.stats().max_gradient / 2e-20f, 1.0f, 1e-3f);
}

TEST(ScenePlan, MaxGradientOfHugeWeightsSaturatesInsteadOfOverflowing) {
  // A saddle of weight 1e36 centred on the screen: |G| = |p - c| reaches
  // sqrt(400^2 + 240^2) = 466.5 at the corners, so max|G| = 4.7e38 in the
  // definition's units, past FLT_MAX = 3.4e38: reported as FLT_MAX, and the
  // rendering (weights normalised) is the weight-1 scene's.
  SceneDefinition heavy;
  heavy.rendering = Rendering::Directional;
  heavy.add(FieldElement::saddle({400.0f, 240.0f}, 1e36f));
  SceneDefinition unit = heavy;
  unit.elements[0].weight = 1.0f;
  ScenePlan a, b;
  ASSERT_EQ(a.prepare(heavy, nullptr, 0), PrepareStatus::Ok);
  ASSERT_EQ(b.prepare(unit, nullptr, 0), PrepareStatus::Ok);
  EXPECT_TRUE(std::isfinite(a.stats().max_gradient));
  EXPECT_EQ(a.stats().max_gradient, FLT_MAX);
  EXPECT_NEAR(static_cast<double>(b.stats().max_gradient), std::hypot(400.0, 240.0), 0.5);
  EXPECT_EQ(max_lsb_difference(a, b), 0.0);
}

TEST(ScenePlan, MaxGradientIsScaleFreeWhereSquaresLeaveFloat) {
  // max|G| is searched on |G|^2; a sampled map is not normalised, so heights
  // of 1e30 (squares overflow) or 1e-30 (squares underflow) must give the
  // plane's |G| = |(0.5, -0.25)| = 0.5590170 times the scale all the same.
  const double expected = std::hypot(0.5, 0.25);
  for (float scale : {1.0f, 1e30f, 1e-30f}) {
    std::vector<float> z;
    const SceneDefinition s = sampled_plane(z, 0.5f * scale, -0.25f * scale);
    Arena arena;
    ScenePlan plan;
    ASSERT_EQ(plan.prepare(s, arena.data(), arena.size()), PrepareStatus::Ok) << scale;
    EXPECT_NEAR(static_cast<double>(plan.stats().max_gradient) / static_cast<double>(scale) / expected, 1.0, 1e-5)
        << scale;
  }
  // Closed form: weights are normalised, so 1e30 and 1e-30 give one
  // rendering and max|G| in proportion (a sink's |G| = |w|, a saddle's
  // |w| |p - c| <= |w| hypot(400, 240) at the screen's corners).
  for (float w : {1e30f, 1e-30f}) {
    SceneDefinition s;
    s.rendering = Rendering::Directional;
    s.add(FieldElement::saddle({400.0f, 240.0f}, w));
    s.add(FieldElement::point_sink({100.0f, 100.0f}, w));
    SceneDefinition unit = s;
    unit.elements[0].weight = unit.elements[1].weight = 1.0f;
    ScenePlan a, b;
    ASSERT_EQ(a.prepare(s, nullptr, 0), PrepareStatus::Ok);
    ASSERT_EQ(b.prepare(unit, nullptr, 0), PrepareStatus::Ok);
    EXPECT_NEAR(static_cast<double>(a.stats().max_gradient) / static_cast<double>(w) /
                    static_cast<double>(b.stats().max_gradient),
                1.0, 1e-6)
        << w;
    EXPECT_EQ(max_lsb_difference(a, b), 0.0) << w;
  }
}

TEST(ScenePlan, HeightTableIsOneSidedAtTheEdges) {
  // The plane Z = 0.5 x sampled at 10 px, nodes at x = 0 .. 800. Central
  // differences one spacing either side, the samples clamped to the grid:
  //   inside:          (Z(x + 10) - Z(x - 10)) / 20 = 0.5
  //   x = 0.37:        (Z(10.37) - Z(0)) / 20       = 0.5 * 10.37 / 20  = 0.259250
  //   x = 799.63:      (Z(800) - Z(789.63)) / 20     = 0.5 * 10.37 / 20  = 0.259250
  // so a height table renders about half the slope within one spacing of the
  // screen's edge: that, not tabulation error, is the edge's large deviation.
  std::vector<float> z;
  const SceneDefinition s = sampled_plane(z, 0.5f, 0.0f);
  Arena arena;
  ScenePlan plan;
  ASSERT_EQ(plan.prepare(s, arena.data(), arena.size()), PrepareStatus::Ok);
  EXPECT_NEAR(static_cast<double>(plan.field({400.0f, 240.0f}).x), 0.5, 1e-5);
  EXPECT_NEAR(static_cast<double>(plan.field({0.37f, 240.0f}).x), 0.259250, 1e-4);
  EXPECT_NEAR(static_cast<double>(plan.field({799.63f, 240.0f}).x), 0.259250, 1e-4);
  EXPECT_NEAR(static_cast<double>(plan.field({400.0f, 0.61f}).y), 0.0, 1e-6);
}

}  // namespace
}  // namespace ff
