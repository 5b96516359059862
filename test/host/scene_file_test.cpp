#include "frictionfield/host/scene_file.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "frictionfield/core/scene_plan.hpp"
#include "frictionfield/core/scenes.hpp"

namespace ff::host {
namespace {

float amp(const SceneDefinition& s, Vec2 p, Vec2 d) {
  ScenePlan plan;
  EXPECT_EQ(plan.prepare(s, nullptr, 0), PrepareStatus::Ok);
  return plan.amplitude(p, d);
}

TEST(SceneFile, TheHeightmapWrittenAsAGeneralSceneIsTheHeightmap) {
  const char* text =
      "# the spec's heightmap, target top, as a general scene\n"
      "rendering directional\n"
      "element path_sink weight 0.5 a 0.2 curve cubic -200\n"
      "element point_sink weight 0.5 centre 700 40\n";
  SceneDefinition s;
  std::string err;
  ASSERT_TRUE(parse_scene_text(text, s, err)) << err;
  const SceneDefinition builtin = scenes::heightmap(Target::Top);
  for (float x = 0; x < 800; x += 37)
    for (float y = 0; y < 480; y += 29)
      EXPECT_EQ(amp(s, {x, y}, {0.6f, 0.8f}), amp(builtin, {x, y}, {0.6f, 0.8f}));
}

TEST(SceneFile, RoundTripsEveryElementKind) {
  const char* text =
      "rendering directional\n"
      "evaluation table 8 float height\n"
      "element point_sink weight -0.5 centre 600 400 radius 12 feather 15\n"
      "element path_sink weight 0.7 a 0.5 band 10 20 curve polyline 0,300 300,200 799,250\n"
      "element path_sink weight 0.2 curve sine 240 120 400 10\n"
      "element tunnel weight 1 x_start 100 length 400 width 60 20 scale 10 y_centre 240\n"
      "element saddle weight 0.001 centre 400 240\n"
      "element texture weight 0.3 wavelength 100 80 height 5\n";
  SceneDefinition a, b;
  std::string err;
  ASSERT_TRUE(parse_scene_text(text, a, err)) << err;
  ASSERT_TRUE(parse_scene_text(format_scene_text(a), b, err)) << err;
  EXPECT_EQ(format_scene_text(a), format_scene_text(b));
  EXPECT_EQ(a.element_count, 6);
  EXPECT_EQ(b.elements[1].valley.curve.count, 3);
  EXPECT_EQ(b.table.source, TableSource::HeightCentralDifferences);
  EXPECT_FLOAT_EQ(b.elements[3].tunnel.scale, 10.0f);
}

TEST(SceneFile, ErrorsSayWhichLineAndWhy) {
  struct Case { const char* text; const char* says; };
  const Case cases[] = {
      {"rendering sideways\n", "line 1: rendering is"},
      {"rendering directional\nelement blob weight 1\n", "line 2: unknown element"},
      {"element point_sink weight nan centre 1 2\n", "'weight' needs finite"},
      {"element point_sink centre 1\n", "'centre' needs"},
      {"element path_sink curve polyline 5,1 4,2\n", "increasing x"},
      {"element vortex weight 1 centre 1 2 extra\n", "unknown key 'extra'"},
      {"frobnicate\n", "unknown directive"},
      {"evaluation table 4 int8\n", "int16 or float"},
  };
  for (const Case& c : cases) {
    SceneDefinition s;
    std::string err;
    EXPECT_FALSE(parse_scene_text(c.text, s, err)) << c.text;
    EXPECT_NE(err.find(c.says), std::string::npos) << err;
  }
  std::string nine = "rendering directional\n";
  for (int i = 0; i < 9; ++i) nine += "element vortex weight 1 centre 1 2\n";
  SceneDefinition s;
  std::string err;
  EXPECT_FALSE(parse_scene_text(nine, s, err));
  EXPECT_NE(err.find("more than 8"), std::string::npos);
}

TEST(SceneFile, RefusesValuesItWouldOtherwiseClampOrIgnore) {
  const char* cases[] = {
      "rendering constant\nconstant 7\n",
      "rendering constant\nconstant -0.1\n",
      "rendering position\nbias 3\nelement point_sink centre 1 1\n",
      "element point_sink weight 1 centre 1 1 radius -5\n",
      "element path_sink curve cubic -200 a 0\n",
      "element tunnel width 0 20\n",
      "element texture wavelength 0 10\n",
      "evaluation table 0\nelement vortex centre 1 1\n",
      "",                          // nothing at all: would render flat
      "# only a comment\n",
      "rendering directional\n",  // no element: flat
  };
  for (const char* text : cases) {
    SceneDefinition s;
    std::string err;
    EXPECT_FALSE(parse_scene_text(text, s, err)) << text;
    EXPECT_FALSE(err.empty()) << text;
  }
  SceneDefinition s;
  std::string err;
  EXPECT_TRUE(parse_scene_text("rendering constant\nconstant 1\n", s, err)) << err;
  EXPECT_FLOAT_EQ(s.constant, 1.0f);
}

TEST(SceneFile, RefusesADirectoryAndAnEmptyFile) {
  SceneDefinition s;
  std::string err;
  const std::string dir = ::testing::TempDir();
  EXPECT_FALSE(read_scene_file(dir, s, err));
  EXPECT_NE(err.find("directory"), std::string::npos) << err;
  const std::string empty = dir + "/ff_empty_scene.txt";
  { std::ofstream(empty).flush(); }
  EXPECT_FALSE(read_scene_file(empty, s, err));
  EXPECT_NE(err.find("no directives"), std::string::npos) << err;
}

}  // namespace
}  // namespace ff::host
