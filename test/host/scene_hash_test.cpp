// The condition hash field by field: every field a condition's rendering reads
// changes the hash, a field its kind does not read leaves it alone, and one
// condition's hash is worked out here from its bytes with the published
// FNV-1a 64 definition (an independent implementation, checked against the
// published test vector), so the fingerprint in old output files stays valid.
#include "frictionfield/host/scene_hash.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <functional>
#include <initializer_list>
#include <vector>

namespace ff::host {
namespace {

// FNV-1a 64 as published (offset basis 0xcbf29ce484222325, prime 0x100000001b3).
uint64_t fnv1a64(const std::vector<uint8_t>& bytes) {
  uint64_t h = 0xcbf29ce484222325ull;
  for (uint8_t b : bytes) {
    h ^= b;
    h *= 0x100000001b3ull;
  }
  return h;
}

void put_f32(std::vector<uint8_t>& out, float v) {
  uint32_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<uint8_t>(bits >> (8 * i)));
}

// AmplitudeSettings{}: strength 1, no S-curve, idle 0, the linear two-point calibration.
void put_default_amplitude(std::vector<uint8_t>& out) {
  for (float v : {1.0f, 0.0f, 0.0f}) put_f32(out, v);
  out.push_back(2);
  for (float v : {0.0f, 0.0f, 1.0f, 4095.0f}) put_f32(out, v);
}

TEST(ConditionHash, TheTestsOwnFnvMatchesThePublishedVector) {
  EXPECT_EQ(fnv1a64({}), 0xcbf29ce484222325ull);
  EXPECT_EQ(fnv1a64({'a'}), 0xaf63dc4c8601ec8cull);
  EXPECT_EQ(fnv1a64({'f', 'o', 'o', 'b', 'a', 'r'}), 0x85944171f73967e8ull);
}

TEST(ConditionHash, TheDefaultConditionHashesItsCanonicalBytes) {
  // Condition{}: a constant 0.5 scene, closed form, no elements, no sampled
  // map; strength 1, no S-curve, idle 0; the linear two-point calibration.
  std::vector<uint8_t> bytes;
  bytes.push_back(0);  // Rendering::Constant
  put_f32(bytes, 0.5f);
  bytes.push_back(0);  // Evaluation::ClosedForm
  bytes.push_back(0);  // no elements
  bytes.push_back(0);  // no sampled map
  put_default_amplitude(bytes);
  EXPECT_EQ(condition_hash(Condition{}), fnv1a64(bytes));
  EXPECT_EQ(hash_hex(condition_hash(Condition{})).size(), 16u);
}

TEST(ConditionHash, ASampledMapHashesItsSizeThenItsSamples) {
  static const float heights[6] = {0.0f, 1.0f, 2.0f, 3.0f, 4.0f, 5.0f};
  Condition c;
  c.scene.sampled = {heights, 3, 2, 4.0f};
  std::vector<uint8_t> bytes;
  bytes.push_back(0);  // Rendering::Constant
  put_f32(bytes, 0.5f);
  bytes.push_back(0);  // Evaluation::ClosedForm
  bytes.push_back(0);  // no elements
  bytes.push_back(1);  // a sampled map: cols, rows (u32 little-endian), spacing, samples
  for (uint8_t b : {3, 0, 0, 0, 2, 0, 0, 0}) bytes.push_back(b);
  put_f32(bytes, 4.0f);
  for (float v : heights) put_f32(bytes, v);
  put_default_amplitude(bytes);
  EXPECT_EQ(condition_hash(c), fnv1a64(bytes));
}

TEST(ConditionHash, OnePointSinkHashesItsCanonicalBytes) {
  Condition c;
  c.scene.rendering = Rendering::Directional;
  FieldElement e = FieldElement::point_sink({3.0f, 4.0f}, -2.0f);
  e.point.radius = 5.0f;
  e.point.feather = 6.0f;
  ASSERT_TRUE(c.scene.add(e));
  std::vector<uint8_t> bytes;
  bytes.push_back(2);  // Rendering::Directional: neither constant nor bias
  bytes.push_back(0);  // Evaluation::ClosedForm
  bytes.push_back(1);
  bytes.push_back(0);  // ElementKind::PointSink
  for (float v : {-2.0f, 3.0f, 4.0f, 5.0f, 6.0f}) put_f32(bytes, v);
  bytes.push_back(0);
  put_default_amplitude(bytes);
  EXPECT_EQ(condition_hash(c), fnv1a64(bytes));
}

TEST(ConditionHash, APolylinePathSinkHashesItsCanonicalBytes) {
  // The curve's fields in the header's order, then its point count and points.
  Condition c;
  c.scene.rendering = Rendering::Directional;
  const Vec2 pts[] = {{0.0f, 10.0f}, {50.0f, 20.0f}};
  FieldElement e = FieldElement::path_sink(PathCurve::polyline(pts, 2), 0.5f, 3.0f);
  e.valley.band_half_width = 7.0f;
  e.valley.band_feather = 9.0f;
  ASSERT_TRUE(c.scene.add(e));
  const PathCurve& k = c.scene.elements[0].valley.curve;
  std::vector<uint8_t> bytes = {2, 0, 1, 1};  // directional, closed form, one element, PathSink
  put_f32(bytes, 3.0f);
  bytes.push_back(static_cast<uint8_t>(CurveKind::Polyline));
  for (float v : {k.x0, k.y0, k.length, k.rise, k.amplitude, k.wavelength}) put_f32(bytes, v);
  bytes.push_back(2);
  for (float v : {0.0f, 10.0f, 50.0f, 20.0f}) put_f32(bytes, v);
  for (float v : {0.5f, 7.0f, 9.0f}) put_f32(bytes, v);
  bytes.push_back(0);
  put_default_amplitude(bytes);
  EXPECT_EQ(condition_hash(c), fnv1a64(bytes));
}

using Change = std::function<void(Condition&)>;

struct Case {
  const char* what;
  Change change;
};

// Each change applied to its own copy of `base`: does the hash follow it?
void expect_hash_moves(const Condition& base, std::initializer_list<Case> cases, bool moves) {
  const uint64_t h = condition_hash(base);
  for (const Case& k : cases) {
    Condition c = base;
    k.change(c);
    EXPECT_EQ(condition_hash(c) != h, moves) << k.what;
  }
}
void expect_changes(const Condition& base, std::initializer_list<Case> cases) { expect_hash_moves(base, cases, true); }
void expect_unchanged(const Condition& base, std::initializer_list<Case> cases) { expect_hash_moves(base, cases, false); }

Condition with_element(const FieldElement& e) {
  Condition c;
  c.scene.rendering = Rendering::Directional;
  c.scene.add(e);
  return c;
}

FieldElement& first(Condition& c) { return c.scene.elements[0]; }

TEST(ConditionHash, EveryFieldAPointSinkReadsCountsAndNoOther) {
  const Condition base = with_element(FieldElement::point_sink({100.0f, 200.0f}));
  expect_changes(base, {
      {"kind", [](Condition& c) { first(c).kind = ElementKind::Vortex; }},
      {"weight", [](Condition& c) { first(c).weight = 2.0f; }},
      {"centre x", [](Condition& c) { first(c).point.centre.x += 1.0f; }},
      {"centre y", [](Condition& c) { first(c).point.centre.y += 1.0f; }},
      {"radius", [](Condition& c) { first(c).point.radius += 1.0f; }},
      {"feather", [](Condition& c) { first(c).point.feather += 1.0f; }},
  });
  expect_unchanged(base, {
      {"valley a", [](Condition& c) { first(c).valley.a += 1.0f; }},
      {"tunnel length", [](Condition& c) { first(c).tunnel.length += 1.0f; }},
      {"texture height", [](Condition& c) { first(c).texture.height += 1.0f; }},
  });
}

TEST(ConditionHash, EveryFieldAPathSinkReadsCountsAndNoOther) {
  const Vec2 pts[] = {{0.0f, 0.0f}, {100.0f, 50.0f}, {200.0f, 0.0f}};
  const Condition base = with_element(FieldElement::path_sink(PathCurve::polyline(pts, 3), 0.2f));
  expect_changes(base, {
      {"a", [](Condition& c) { first(c).valley.a = 0.3f; }},
      {"band half width", [](Condition& c) { first(c).valley.band_half_width += 1.0f; }},
      {"band feather", [](Condition& c) { first(c).valley.band_feather += 1.0f; }},
      {"curve kind", [](Condition& c) { first(c).valley.curve.kind = CurveKind::Sine; }},
      {"curve x0", [](Condition& c) { first(c).valley.curve.x0 += 1.0f; }},
      {"curve y0", [](Condition& c) { first(c).valley.curve.y0 += 1.0f; }},
      {"curve length", [](Condition& c) { first(c).valley.curve.length += 1.0f; }},
      {"curve rise", [](Condition& c) { first(c).valley.curve.rise += 1.0f; }},
      {"curve amplitude", [](Condition& c) { first(c).valley.curve.amplitude += 1.0f; }},
      {"curve wavelength", [](Condition& c) { first(c).valley.curve.wavelength += 1.0f; }},
      {"point count", [](Condition& c) { first(c).valley.curve.count = 2; }},
      {"last point", [](Condition& c) { first(c).valley.curve.points[2].y += 1.0f; }},
  });
  expect_unchanged(base, {
      {"a point past the count", [](Condition& c) { first(c).valley.curve.points[3].x = 7.0f; }},
      {"point centre", [](Condition& c) { first(c).point.centre.x += 1.0f; }},
      {"point radius", [](Condition& c) { first(c).point.radius += 1.0f; }},
  });
}

TEST(ConditionHash, EveryFieldATunnelReadsCountsAndNoOther) {
  const Condition base = with_element(FieldElement::tunnel_valley(TunnelParams{}));
  expect_changes(base, {
      {"x start", [](Condition& c) { first(c).tunnel.x_start += 1.0f; }},
      {"length", [](Condition& c) { first(c).tunnel.length += 1.0f; }},
      {"width start", [](Condition& c) { first(c).tunnel.width_start += 1.0f; }},
      {"width end", [](Condition& c) { first(c).tunnel.width_end += 1.0f; }},
      {"scale", [](Condition& c) { first(c).tunnel.scale += 1.0f; }},
      {"y centre", [](Condition& c) { first(c).tunnel.y_centre += 1.0f; }},
  });
  expect_unchanged(base, {
      {"valley curve", [](Condition& c) { first(c).valley.curve.rise += 1.0f; }},
      {"point centre", [](Condition& c) { first(c).point.centre.y += 1.0f; }},
  });
}

TEST(ConditionHash, AVortexAndASaddleReadTheirCentreOnly) {
  for (const FieldElement& e : {FieldElement::vortex({10.0f, 20.0f}), FieldElement::saddle({10.0f, 20.0f})}) {
    const Condition base = with_element(e);
    expect_changes(base, {
        {"centre x", [](Condition& c) { first(c).point.centre.x += 1.0f; }},
        {"centre y", [](Condition& c) { first(c).point.centre.y += 1.0f; }},
    });
    expect_unchanged(base, {
        {"radius", [](Condition& c) { first(c).point.radius += 1.0f; }},
        {"feather", [](Condition& c) { first(c).point.feather += 1.0f; }},
    });
  }
}

TEST(ConditionHash, EveryFieldATextureReadsCountsAndNoOther) {
  const Condition base = with_element(FieldElement::sine_texture(50.0f, 60.0f, 2.0f));
  expect_changes(base, {
      {"wavelength x", [](Condition& c) { first(c).texture.wavelength_x += 1.0f; }},
      {"wavelength y", [](Condition& c) { first(c).texture.wavelength_y += 1.0f; }},
      {"height", [](Condition& c) { first(c).texture.height += 1.0f; }},
  });
  expect_unchanged(base, {
      {"point centre", [](Condition& c) { first(c).point.centre.x += 1.0f; }},
  });
}

TEST(ConditionHash, TheSceneLevelFieldsCountWhereTheRenderingReadsThem) {
  Condition constant;  // Rendering::Constant
  expect_changes(constant, {
      {"constant", [](Condition& c) { c.scene.constant = 0.25f; }},
      {"rendering", [](Condition& c) { c.scene.rendering = Rendering::PositionOnly; }},
  });
  expect_unchanged(constant, {{"bias", [](Condition& c) { c.scene.bias = 0.25f; }}});

  Condition position;
  position.scene.rendering = Rendering::PositionOnly;
  expect_changes(position, {{"bias", [](Condition& c) { c.scene.bias = 0.25f; }}});
  expect_unchanged(position, {{"constant", [](Condition& c) { c.scene.constant = 0.25f; }}});

  const Condition directional = with_element(FieldElement::saddle({0.0f, 0.0f}));
  expect_changes(directional, {
      {"a second element", [](Condition& c) { c.scene.add(FieldElement::saddle({0.0f, 0.0f})); }},
      {"evaluation", [](Condition& c) { c.scene.evaluation = Evaluation::Table; }},
  });
  expect_unchanged(directional, {
      {"table spacing, closed form", [](Condition& c) { c.scene.table.spacing_px = 8.0f; }},
      {"an element past the count", [](Condition& c) { c.scene.elements[1].weight = 3.0f; }},
  });

  Condition table = directional;
  table.scene.evaluation = Evaluation::Table;
  expect_changes(table, {
      {"spacing", [](Condition& c) { c.scene.table.spacing_px = 8.0f; }},
      {"storage", [](Condition& c) { c.scene.table.storage = TableStorage::Float32; }},
      {"source", [](Condition& c) { c.scene.table.source = TableSource::HeightCentralDifferences; }},
  });
}

TEST(ConditionHash, TheSampledMapCountsWithItsSizeAndEverySample) {
  static const float heights[6] = {0.0f, 1.0f, 2.0f, 3.0f, 4.0f, 5.0f};
  static const float other[6] = {0.0f, 1.0f, 2.0f, 3.0f, 4.0f, 5.5f};
  Condition base = with_element(FieldElement::saddle({0.0f, 0.0f}));
  base.scene.sampled = {heights, 3, 2, 4.0f};
  Condition none = base;
  none.scene.sampled = {};
  EXPECT_NE(condition_hash(base), condition_hash(none));
  expect_changes(base, {
      {"cols", [](Condition& c) { c.scene.sampled.cols = 2; }},
      {"rows", [](Condition& c) { c.scene.sampled.rows = 1; }},
      {"spacing", [](Condition& c) { c.scene.sampled.spacing_px = 2.0f; }},
      {"shape, same samples", [](Condition& c) { c.scene.sampled.cols = 2, c.scene.sampled.rows = 3; }},
      {"last sample", [](Condition& c) { c.scene.sampled.heights = other; }},
  });
  // A map without samples is no map, whatever its other fields say.
  expect_unchanged(none, {{"size without samples", [](Condition& c) { c.scene.sampled.cols = 3; }}});
}

TEST(ConditionHash, EveryAmplitudeSettingCounts) {
  expect_changes(Condition{}, {
      {"strength", [](Condition& c) { c.amplitude.strength = 0.5f; }},
      {"s-curve", [](Condition& c) { c.amplitude.s_curve = 1.0f; }},
      {"idle amplitude", [](Condition& c) { c.amplitude.idle_amplitude = 0.1f; }},
      {"calibration count", [](Condition& c) { c.amplitude.calibration.count = 3; }},
      {"calibration amplitude", [](Condition& c) { c.amplitude.calibration.amplitude[1] = 0.9f; }},
      {"calibration code", [](Condition& c) { c.amplitude.calibration.code[1] = 4000.0f; }},
  });
  expect_unchanged(Condition{}, {
      {"a point past the count", [](Condition& c) { c.amplitude.calibration.code[2] = 7.0f; }},
      {"-0 for 0", [](Condition& c) { c.amplitude.s_curve = -0.0f; }},
  });
}

}  // namespace
}  // namespace ff::host
