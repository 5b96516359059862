#include "frictionfield/core/grid_table.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace ff {
namespace {

TEST(GridTable, SizesCoverTheScreen) {
  // 4 px: 201 x 121 nodes (0..800 covers pixel 799), 2 channels of int16.
  EXPECT_EQ(GridTable::bytes_needed(4.0f, 2, TableStorage::Int16), 201u * 121u * 2u * 2u);
  EXPECT_EQ(GridTable::bytes_needed(16.0f, 1, TableStorage::Float32), 51u * 31u * 4u);
  EXPECT_EQ(GridTable::bytes_needed(NAN, 1, TableStorage::Float32), SIZE_MAX);
}

TEST(GridTable, BilinearIsExactOnBilinearFunctions) {
  std::vector<float> mem(GridTable::bytes_needed(8.0f, 2, TableStorage::Float32) / 4);
  GridTable t;
  ASSERT_TRUE(t.init(mem.data(), mem.size() * 4, 101, 61, 8.0f, 2, TableStorage::Float32));
  auto f = [](Vec2 p) { return 3.0f + 0.5f * p.x - 0.25f * p.y + 0.001f * p.x * p.y; };
  t.fill([&](Vec2 p, float* out) {
    out[0] = f(p);
    out[1] = -f(p);
  });
  for (float x : {0.0f, 3.3f, 123.4f, 798.9f}) {
    for (float y : {0.0f, 7.7f, 250.5f, 479.0f}) {
      EXPECT_NEAR(static_cast<double>(t.sample({x, y}, 0)), static_cast<double>(f({x, y})), 2e-4);
      EXPECT_NEAR(static_cast<double>(t.sample2({x, y}).y), -static_cast<double>(f({x, y})), 2e-4);
    }
  }
}

TEST(GridTable, Int16QuantisesWithinHalfAStep) {
  std::vector<int16_t> mem(GridTable::bytes_needed(4.0f, 1, TableStorage::Int16) / 2);
  GridTable t;
  ASSERT_TRUE(t.init(mem.data(), mem.size() * 2, 201, 121, 4.0f, 1, TableStorage::Int16));
  t.fill([](Vec2 p, float* out) { out[0] = std::sin(p.x * 0.01f) * 50.0f; });
  const double step = 50.0 / 32767.0;
  for (int c = 0; c < 201; c += 13) {
    const float expected = std::sin(static_cast<float>(c) * 4.0f * 0.01f) * 50.0f;
    EXPECT_NEAR(static_cast<double>(t.node(c, 5, 0)), static_cast<double>(expected), 0.5 * step + 1e-5);
  }
}

TEST(GridTable, OutsideAndNaNPositionsStayInsideTheGrid) {
  std::vector<float> mem(51 * 31);
  GridTable t;
  ASSERT_TRUE(t.init(mem.data(), mem.size() * 4, 51, 31, 16.0f, 1, TableStorage::Float32));
  t.fill([](Vec2 p, float* out) { out[0] = p.x; });
  EXPECT_FLOAT_EQ(t.sample({-100.0f, 5.0f}, 0), 0.0f);
  EXPECT_FLOAT_EQ(t.sample({1e9f, 5.0f}, 0), 800.0f);
  EXPECT_FLOAT_EQ(t.sample({NAN, NAN}, 0), 0.0f);
  EXPECT_FLOAT_EQ(t.sample({INFINITY, -INFINITY}, 0), 800.0f);
}

// The corner node is read from the last cell (fraction 1), not as the first
// node of a cell past the table: what lies beyond the table (NaN here) is
// never read, even times a fraction of 0.
TEST(GridTable, TheCornerIsReadInsideTheTable) {
  std::vector<float> mem(51 * 31 + 64, NAN);
  GridTable t;
  ASSERT_TRUE(t.init(mem.data(), 51 * 31 * 4, 51, 31, 16.0f, 1, TableStorage::Float32));
  t.fill([](Vec2 p, float* out) { out[0] = p.x + 1000.0f * p.y; });
  EXPECT_EQ(t.sample({800.0f, 480.0f}, 0), 480800.0f);
  EXPECT_EQ(t.sample({800.0f, 240.0f}, 0), 240800.0f);
  std::vector<float> pairs(51 * 31 * 2 + 64, NAN);
  ASSERT_TRUE(t.init(pairs.data(), 51 * 31 * 2 * 4, 51, 31, 16.0f, 2, TableStorage::Float32));
  t.fill([](Vec2 p, float* out) {
    out[0] = p.x;
    out[1] = p.y;
  });
  EXPECT_EQ(t.sample2({800.0f, 480.0f}).x, 800.0f);
  EXPECT_EQ(t.sample2({800.0f, 480.0f}).y, 480.0f);
}

// init() starts a table afresh: nodes 0 whatever the memory held, and no
// int16 scale left over from an earlier table.
TEST(GridTable, InitClearsTheNodesAndTheScale) {
  std::vector<float> mem(51 * 31, NAN);
  GridTable t;
  ASSERT_TRUE(t.init(mem.data(), mem.size() * 4, 51, 31, 16.0f, 1, TableStorage::Int16));
  t.fill([](Vec2, float* out) { out[0] = 50.0f; });  // scale 50 / 32767 per step
  ASSERT_TRUE(t.init(mem.data(), mem.size() * 4, 51, 31, 16.0f, 1, TableStorage::Float32));
  EXPECT_EQ(t.sample({123.0f, 45.0f}, 0), 0.0f);
  t.set(7, 2, 0, 3.0f);
  EXPECT_EQ(t.node(7, 2, 0), 3.0f);
  EXPECT_EQ(t.sample({112.0f, 32.0f}, 0), 3.0f);
}

TEST(GridTable, RefusesMemoryThatDoesNotFit) {
  std::vector<float> mem(10);
  GridTable t;
  EXPECT_FALSE(t.init(mem.data(), mem.size() * 4, 51, 31, 16.0f, 1, TableStorage::Float32));
  EXPECT_FALSE(t.valid());
}

}  // namespace
}  // namespace ff
