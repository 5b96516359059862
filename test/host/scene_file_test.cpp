#include "frictionfield/host/scene_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "frictionfield/core/scene_plan.hpp"
#include "frictionfield/core/scenes.hpp"
#include "support/scratch_path.hpp"

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

// Every element kind and key once.
const std::string kEveryKind =
      "rendering directional\n"
      "evaluation table 8 float height\n"
      "element point_sink weight -0.5 centre 600 400 radius 12 feather 15\n"
      "element path_sink weight 0.7 a 0.5 band 10 20 curve polyline 0,300 300,200 799,250\n"
      "element path_sink weight 0.2 curve sine 240 120 400 10\n"
      "element tunnel weight 1 x_start 100 length 400 width 60 20 scale 10 y_centre 240\n"
      "element saddle weight 0.001 centre 400 240\n"
      "element texture weight 0.3 wavelength 100 80 height 5\n";

TEST(SceneFile, RoundTripsEveryElementKind) {
  const std::string& text = kEveryKind;
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

TEST(SceneFile, WritesEveryFloatBackExactly) {
  // Nine significant digits name every float; six would turn 600.0001 into 600.
  SceneDefinition a;
  a.rendering = Rendering::Directional;
  FieldElement e = FieldElement::point_sink({600.0001f, 0.1f}, 0.123456789f);
  e.point.radius = 1.0f / 3.0f;
  a.add(e);
  SceneDefinition b;
  std::string err;
  ASSERT_TRUE(parse_scene_text(format_scene_text(a), b, err)) << err;
  EXPECT_EQ(b.elements[0].point.centre.x, 600.0001f);
  EXPECT_EQ(b.elements[0].point.centre.y, 0.1f);
  EXPECT_EQ(b.elements[0].weight, 0.123456789f);
  EXPECT_EQ(b.elements[0].point.radius, 1.0f / 3.0f);
}

TEST(SceneFile, WritesTheConstantAndTheBias) {
  SceneDefinition constant;
  constant.rendering = Rendering::Constant;
  constant.constant = 0.25f;
  SceneDefinition position;
  position.rendering = Rendering::PositionOnly;
  position.bias = -0.3f;
  position.add(FieldElement::point_sink({1.0f, 2.0f}));
  SceneDefinition back;
  std::string err;
  ASSERT_TRUE(parse_scene_text(format_scene_text(constant), back, err)) << err;
  EXPECT_EQ(back.rendering, Rendering::Constant);
  EXPECT_EQ(back.constant, 0.25f);
  ASSERT_TRUE(parse_scene_text(format_scene_text(position), back, err)) << err;
  EXPECT_EQ(back.rendering, Rendering::PositionOnly);
  EXPECT_EQ(back.bias, -0.3f);
}

TEST(SceneFile, EveryValueLandsInItsField) {
  // The round trip above cannot see a value that is never stored (both sides
  // keep the default): here each one is read back against the text.
  const std::string text = kEveryKind + "element path_sink curve cubic -150 50 260 500\n";
  SceneDefinition s;
  std::string err;
  ASSERT_TRUE(parse_scene_text(text, s, err)) << err;
  EXPECT_EQ(s.rendering, Rendering::Directional);
  EXPECT_EQ(s.evaluation, Evaluation::Table);
  EXPECT_EQ(s.table.spacing_px, 8.0f);
  EXPECT_EQ(s.table.storage, TableStorage::Float32);
  ASSERT_EQ(s.element_count, 7);

  const FieldElement& point = s.elements[0];
  EXPECT_EQ(point.kind, ElementKind::PointSink);
  EXPECT_EQ(point.weight, -0.5f);
  EXPECT_EQ(point.point.centre.x, 600.0f);
  EXPECT_EQ(point.point.centre.y, 400.0f);
  EXPECT_EQ(point.point.radius, 12.0f);
  EXPECT_EQ(point.point.feather, 15.0f);

  const FieldElement& poly = s.elements[1];
  EXPECT_EQ(poly.kind, ElementKind::PathSink);
  EXPECT_EQ(poly.valley.a, 0.5f);
  EXPECT_EQ(poly.valley.band_half_width, 10.0f);
  EXPECT_EQ(poly.valley.band_feather, 20.0f);
  EXPECT_EQ(poly.valley.curve.kind, CurveKind::Polyline);
  ASSERT_EQ(poly.valley.curve.count, 3);
  EXPECT_EQ(poly.valley.curve.points[1].x, 300.0f);
  EXPECT_EQ(poly.valley.curve.points[1].y, 200.0f);
  EXPECT_EQ(poly.valley.curve.points[2].x, 799.0f);

  const PathCurve& sine = s.elements[2].valley.curve;
  EXPECT_EQ(sine.kind, CurveKind::Sine);
  EXPECT_EQ(sine.y0, 240.0f);
  EXPECT_EQ(sine.amplitude, 120.0f);
  EXPECT_EQ(sine.wavelength, 400.0f);
  EXPECT_EQ(sine.x0, 10.0f);

  const FieldElement& tunnel = s.elements[3];
  EXPECT_EQ(tunnel.kind, ElementKind::Tunnel);
  EXPECT_EQ(tunnel.tunnel.x_start, 100.0f);
  EXPECT_EQ(tunnel.tunnel.length, 400.0f);
  EXPECT_EQ(tunnel.tunnel.width_start, 60.0f);
  EXPECT_EQ(tunnel.tunnel.width_end, 20.0f);
  EXPECT_EQ(tunnel.tunnel.scale, 10.0f);
  EXPECT_EQ(tunnel.tunnel.y_centre, 240.0f);

  EXPECT_EQ(s.elements[4].kind, ElementKind::Saddle);
  EXPECT_EQ(s.elements[4].weight, 0.001f);

  const FieldElement& texture = s.elements[5];
  EXPECT_EQ(texture.kind, ElementKind::Texture);
  EXPECT_EQ(texture.texture.wavelength_x, 100.0f);
  EXPECT_EQ(texture.texture.wavelength_y, 80.0f);
  EXPECT_EQ(texture.texture.height, 5.0f);

  const PathCurve& cubic = s.elements[6].valley.curve;
  EXPECT_EQ(cubic.kind, CurveKind::Cubic);
  EXPECT_EQ(cubic.rise, -150.0f);
  EXPECT_EQ(cubic.x0, 50.0f);
  EXPECT_EQ(cubic.y0, 260.0f);
  EXPECT_EQ(cubic.length, 500.0f);
}

TEST(SceneFile, APolylinePointIsTwoFiniteNumbersAroundOneComma) {
  const char* bad[] = {",5", "1,", "1,2x", "1x,2", "inf,2", "1,inf", "nan,1", "1,nan"};
  for (const char* p : bad) {
    const std::string text = std::string("element path_sink curve polyline 0,0 ") + p + " 900,0\n";
    SceneDefinition s;
    std::string err;
    EXPECT_FALSE(parse_scene_text(text, s, err)) << p;
    EXPECT_NE(err.find("x,y pairs"), std::string::npos) << p << ": " << err;
  }
  std::string sixteen = "element path_sink curve polyline";
  for (int i = 0; i < 16; ++i) sixteen += " " + std::to_string(10 * i) + ",5";
  SceneDefinition s;
  std::string err;
  ASSERT_TRUE(parse_scene_text(sixteen + "\n", s, err)) << err;
  EXPECT_EQ(s.elements[0].valley.curve.count, 16);
  EXPECT_FALSE(parse_scene_text(sixteen + " 200,5\n", s, err));
  EXPECT_NE(err.find("more than 16 points"), std::string::npos) << err;
}

TEST(SceneFile, TheRenderingLineNamesTheMode) {
  const struct { const char* line; Rendering mode; } cases[] = {
      {"", Rendering::Directional},  // elements without a rendering line: a field to follow, not a flat 0.5
      {"rendering constant\n", Rendering::Constant},
      {"rendering position\n", Rendering::PositionOnly},
      {"rendering directional\n", Rendering::Directional},
  };
  for (const auto& c : cases) {
    SceneDefinition s;
    std::string err;
    ASSERT_TRUE(parse_scene_text(std::string(c.line) + "element vortex centre 1 1\n", s, err)) << err;
    EXPECT_EQ(s.rendering, c.mode) << c.line;
  }
}

TEST(SceneFile, TheLastEvaluationLineHolds) {
  SceneDefinition s;
  std::string err;
  ASSERT_TRUE(parse_scene_text("evaluation table 8\nevaluation closed\nelement vortex\n", s, err)) << err;
  EXPECT_EQ(s.evaluation, Evaluation::ClosedForm);
  ASSERT_TRUE(parse_scene_text("evaluation closed\nevaluation table 8\nelement vortex\n", s, err)) << err;
  EXPECT_EQ(s.evaluation, Evaluation::Table);
  EXPECT_EQ(s.table.storage, TableStorage::Int16);  // the defaults when the line stops at the spacing
  EXPECT_EQ(s.table.source, TableSource::TabulatedGradient);
  ASSERT_TRUE(parse_scene_text("rendering position\nbias -0.25\nelement vortex\n", s, err)) << err;
  EXPECT_EQ(s.bias, -0.25f);
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
      {"evaluation table 4 int16 slope\n", "gradient or height"},
      {"rendering position\nbias\n", "line 2: bias needs a number"},
      {"rendering constant sideways\n", "line 1: unexpected 'sideways'"},
      {"rendering position\nelement point_sink feather 0\n", "line 2: element point_sink: 'feather' 0 must be > 0"},
      {"element path_sink band 0 0\n", "line 1: element path_sink: 'band' 0 must be > 0"},
      {"element path_sink curve cubic -200 100 240 -600\n", "line 1: curve cubic: the length L -600 must be > 0"},
      {"", "line 1: no directives"},
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
      "element point_sink feather 0\n",  // the core divides by the feathers and the length
      "element path_sink band 10 0\n",
      "element path_sink curve cubic -200 100 240 0\n",
      "element path_sink curve cubic -200 100 240 -600\n",
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

TEST(SceneFile, NumbersAreDecimalAndNeverSilentlyZero) {
  struct Case { const char* text; const char* error; };
  const Case cases[] = {
      // strtof reads these as 8, 16 and 1: docs/spec.md says numbers are decimal.
      {"element vortex weight 0x1p3\n", "line 1: 'weight' needs finite number(s): 0x1p3 is not a decimal number"},
      {"element vortex centre 0X10 5\n", "line 1: 'centre' needs finite number(s): 0X10 is not a decimal number"},
      {"rendering constant\nconstant 0x1p0\n", "line 2: constant needs a number: 0x1p0 is not a decimal number"},
      // 1e-999 is below the smallest float (1.4e-45): it would be a weight of 0, the element dropped.
      {"element vortex weight 1e-999\n",
       "line 1: 'weight' needs finite number(s): 1e-999 is too small for a float (it would be 0)"},
      {"element path_sink curve polyline 0,1e-999 9,0\n",
       "line 1: polyline points are x,y pairs: 1e-999 is too small for a float (it would be 0)"},
      {"element vortex weight 1e39\n", "line 1: 'weight' needs finite number(s): 1e39 is too large for a float"},
      // Printed as typed: float(1.0000001) = 1.00000012 shows as 1 with six digits.
      {"rendering constant\nconstant 1.0000001\n", "line 2: constant 1.0000001 is outside [0, 1] (an amplitude)"},
      {"rendering position\nbias -1.0000001\nelement vortex\n", "line 2: bias -1.0000001 is outside [-1, 1]"},
      {"evaluation table 0.9999999\nelement vortex\n", "line 1: table spacing 0.9999999 is outside [1, 100] px"},
      {"element point_sink radius -1e-45\n", "line 1: element point_sink: 'radius' -1e-45 must be >= 0"},
  };
  for (const Case& c : cases) {
    SceneDefinition s;
    std::string err;
    EXPECT_FALSE(parse_scene_text(c.text, s, err)) << c.text;
    EXPECT_EQ(err, c.error) << c.text;
  }
  // Zero written as zero stays zero; a subnormal is not 0; decimal forms strtof and the docs share.
  SceneDefinition s;
  std::string err;
  ASSERT_TRUE(parse_scene_text("element vortex weight 1 centre 0e-999 -0.000\nelement vortex weight 1e-45\n"
                               "element vortex weight +.5e+1 centre 5. 1E2\n",
                               s, err))
      << err;
  EXPECT_EQ(s.elements[0].point.centre.x, 0.0f);
  EXPECT_GT(s.elements[1].weight, 0.0f);
  EXPECT_EQ(s.elements[2].weight, 5.0f);
  EXPECT_EQ(s.elements[2].point.centre.x, 5.0f);
  EXPECT_EQ(s.elements[2].point.centre.y, 100.0f);
}

TEST(SceneFile, ALeadingByteOrderMarkIsSkipped) {
  // An editor's UTF-8 BOM before 'rendering' made it "unknown directive '\xEF\xBB\xBFrendering'".
  SceneDefinition s;
  std::string err;
  ASSERT_TRUE(parse_scene_text("\xEF\xBB\xBFrendering constant\nconstant 0.25\n", s, err)) << err;
  EXPECT_EQ(s.rendering, Rendering::Constant);
  EXPECT_EQ(s.constant, 0.25f);
  // Only at the start: elsewhere it is still not a directive.
  EXPECT_FALSE(parse_scene_text("rendering constant\n\xEF\xBB\xBF" "constant 0.25\n", s, err));
  EXPECT_EQ(err.rfind("line 2: unknown directive", 0), 0u) << err;
}

TEST(SceneFile, RefusesAFileLargerThanAnySceneWithoutReadingItAll) {
  // /dev/zero never ends: it was read whole until std::bad_alloc (exit 134).
  SceneDefinition s;
  std::string err;
  EXPECT_FALSE(read_scene_file("/dev/zero", s, err));
  EXPECT_EQ(err, "/dev/zero: larger than 1 MiB: not a scene file (a scene is a few KB)");
  // 1 MiB exactly (a valid scene padded with comment lines) is still read; one byte more is not.
  const std::string path = support::scratch_path("scene_file_one_mib.txt");
  std::string text = "rendering constant\nconstant 0.25\n";
  const std::string comment = "# padding\n";
  while (text.size() + comment.size() <= kMaxSceneFileBytes) text += comment;
  text += std::string(kMaxSceneFileBytes - text.size() - 1, '#') + "\n";
  ASSERT_EQ(text.size(), 1048576u);
  { std::ofstream(path, std::ios::binary) << text; }
  EXPECT_TRUE(read_scene_file(path, s, err)) << err;
  { std::ofstream(path, std::ios::binary) << text << "\n"; }
  EXPECT_FALSE(read_scene_file(path, s, err));
  EXPECT_EQ(err, path + ": larger than 1 MiB: not a scene file (a scene is a few KB)");
}

TEST(SceneFile, RefusesADirectoryAnEmptyFileAndAMissingOne) {
  SceneDefinition s;
  std::string err;
  const std::string dir = support::scratch_path("scene_dir");
  std::filesystem::create_directories(dir);
  EXPECT_FALSE(read_scene_file(dir, s, err));
  EXPECT_EQ(err, dir + ": is a folder, not a file");
  const std::string empty = dir + "/ff_empty_scene.txt";
  { std::ofstream(empty).flush(); }
  EXPECT_FALSE(read_scene_file(empty, s, err));
  EXPECT_NE(err.find("no directives"), std::string::npos) << err;
  const std::string bad = dir + "/ff_bad_scene.txt";
  { std::ofstream(bad) << "rendering sideways\n"; }
  EXPECT_FALSE(read_scene_file(bad, s, err));
  EXPECT_EQ(err.rfind(bad + ": line 1: rendering is", 0), 0u) << err;
  const std::string missing = dir + "/ff_no_such_scene.txt";
  EXPECT_FALSE(read_scene_file(missing, s, err));
  EXPECT_EQ(err, missing + ": cannot open: No such file or directory");
}

}  // namespace
}  // namespace ff::host
