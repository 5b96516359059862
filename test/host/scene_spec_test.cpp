// The scene words as a user types them (through CLI11, as every tool parses
// them) and the condition hash that names a condition in output files.
#include "frictionfield/host/scene_spec.hpp"

#include <gtest/gtest.h>

#include <CLI/CLI.hpp>
#include <fstream>
#include <sstream>

#include "frictionfield/core/scenes.hpp"
#include "frictionfield/host/scene_file.hpp"
#include "frictionfield/host/scene_hash.hpp"
#include "support/scratch_path.hpp"

namespace ff::host {
namespace {

struct Parsed {
  SceneSpec spec;
  bool ok = false;
  std::string error;
};

Parsed parse(std::vector<std::string> words) {
  Parsed p;
  CLI::App app;
  add_scene_options(app, p.spec);
  std::reverse(words.begin(), words.end());  // CLI11 takes them last first
  try {
    app.parse(words);
    p.ok = true;
  } catch (const CLI::ParseError& e) {
    p.error = e.what();
  }
  return p;
}

// One file per test: ctest runs the tests of this file in parallel processes.
std::string scene_file(const char* text) {
  const std::string path = support::scratch_path(std::string("scene_spec_") +
                                                 ::testing::UnitTest::GetInstance()->current_test_info()->name() + ".txt");
  std::ofstream(path) << text;
  return path;
}

TEST(SceneSpec, ASceneFileImpliesTheFileScene) {
  const std::string path = scene_file("rendering constant\nconstant 0.25\n");
  const Parsed p = parse({"--scene-file", path});
  ASSERT_TRUE(p.ok) << p.error;
  EXPECT_EQ(p.spec.scene, "file");  // what ffctl reads to choose the message kind
  Condition c;
  std::string error;
  ASSERT_TRUE(make_condition(p.spec, c, error)) << error;
  EXPECT_EQ(c.scene.rendering, Rendering::Constant);
  EXPECT_FLOAT_EQ(c.scene.constant, 0.25f);
  EXPECT_TRUE(parse({"--scene", "file", "--scene-file", path}).ok);
  EXPECT_TRUE(parse({"--scene-file", path, "--scene", "file"}).ok);
}

TEST(SceneSpec, ASceneFileWithAnotherSceneIsAUsageError) {
  const std::string path = scene_file("rendering constant\nconstant 0.25\n");
  for (const auto& words : {std::vector<std::string>{"--scene", "heightmap", "--scene-file", path},
                            std::vector<std::string>{"--scene-file", path, "--scene", "neutral"}}) {
    const Parsed p = parse(words);
    EXPECT_FALSE(p.ok);
    EXPECT_NE(p.error.find("drop one"), std::string::npos) << p.error;
  }
  // Built in code, without the command line: the same rule.
  SceneSpec spec;
  spec.scene = "neutral";
  spec.scene_given = true;
  spec.scene_file = path;
  Condition c;
  std::string error;
  EXPECT_FALSE(make_condition(spec, c, error));
  EXPECT_NE(error.find("drop one"), std::string::npos) << error;
}

TEST(SceneSpec, TheFileSceneNeedsAFile) {
  const Parsed p = parse({"--scene", "file"});
  ASSERT_TRUE(p.ok) << p.error;
  Condition c;
  std::string error;
  EXPECT_FALSE(make_condition(p.spec, c, error));
  EXPECT_NE(error.find("needs --scene-file PATH"), std::string::npos) << error;
}

TEST(SceneSpec, OutOfRangeWordsAreRefusedNotClamped) {
  const std::vector<std::vector<std::string>> bad = {
      {"--strength", "1.5"}, {"--strength", "0"}, {"--strength", "-0.3"}, {"--idle-amplitude", "2"},
      {"--scene", "tunnel-converging", "--width-end", "0"}, {"--scene", "tunnel-neutral", "--tunnel-length", "-4"},
      {"--evaluation", "table", "--table-spacing", "0.1"}, {"--target", "left"}, {"--scene", "hightmap"},
      {"--scene", "tunnel-converging", "--tunnel-x-start", "inf"}, {"--scene", "tunnel-neutral", "--width-start", "nan"},
      {"--evaluation", "table", "--table-storage", "int8"}, {"--evaluation", "table", "--table-source", "slope"},
      {"--evaluation", "tabel"}};
  for (const auto& words : bad) {
    const Parsed p = parse(words);
    ASSERT_TRUE(p.ok) << p.error;
    Condition c;
    std::string error;
    EXPECT_FALSE(make_condition(p.spec, c, error)) << words[0] << " " << words[1];
    EXPECT_FALSE(error.empty());
  }
}

// The condition the words make, next to the one the core's builders make.
Condition built(const std::vector<std::string>& words) {
  const Parsed p = parse(words);
  EXPECT_TRUE(p.ok) << p.error;
  Condition c;
  std::string error;
  EXPECT_TRUE(make_condition(p.spec, c, error)) << error;
  return c;
}

Condition of(const SceneDefinition& scene) {
  Condition c;
  c.scene = scene;
  return c;
}

TEST(SceneSpec, EachSceneNameBuildsThatScene) {
  const struct { std::vector<std::string> words; SceneDefinition scene; } cases[] = {
      {{"--scene", "heightmap", "--target", "top"}, scenes::heightmap(Target::Top)},
      {{"--scene", "heightmap", "--target", "middle"}, scenes::heightmap(Target::Middle)},
      {{"--scene", "heightmap", "--target", "bottom"}, scenes::heightmap(Target::Bottom)},
      {{"--scene", "frictionmap", "--target", "top"}, scenes::frictionmap(Target::Top)},
      {{"--scene", "neutral"}, scenes::neutral()},
      {{"--scene", "tunnel-converging"}, scenes::steering_tunnel(TunnelParams{}, scenes::TunnelMode::Converging)},
      {{"--scene", "tunnel-diverging"}, scenes::steering_tunnel(TunnelParams{}, scenes::TunnelMode::Diverging)},
      {{"--scene", "tunnel-neutral"}, scenes::steering_tunnel(TunnelParams{}, scenes::TunnelMode::Neutral)},
      {{"--scene", "pilot-c", "--target", "bottom"}, scenes::pilot_c_valley(Target::Bottom)},
      {{"--scene", "familiarisation-path"}, scenes::familiarisation_path()},
      {{"--scene", "bump-map"}, scenes::bump_map()},
      {{"--scene", "vortex"}, scenes::vortex()},
  };
  for (const auto& c : cases) {
    EXPECT_EQ(condition_hash(built(c.words)), condition_hash(of(c.scene))) << c.words[1];
  }
}

TEST(SceneSpec, WhatTheCorePreparationRefusesIsRefusedWithItsReason) {
  // A vortex has no height to tabulate; a 1 px float gradient table is
  // 801 x 481 nodes x 2 channels x 4 bytes = 3.1 MB, far over the 96 KiB
  // slot; two saddles at x = 3e38 add up to a gradient of -6e38, past float.
  const std::string vortex = scene_file("evaluation table 8 float height\nelement vortex centre 400 240\n");
  const std::string saddles = support::scratch_path("scene_spec_two_saddles_at_3e38.txt");
  std::ofstream(saddles) << "element saddle centre 3e38 0\nelement saddle centre 3e38 0\n";
  const std::string invalid =
      "cannot prepare the scene: a vortex has no height to tabulate (no potential makes its swirl): use table "
      "source gradient, or closed evaluation";
  const struct { std::vector<std::string> words; std::string error; } cases[] = {
      {{"--scene-file", vortex}, invalid},
      {{"--scene", "vortex", "--evaluation", "table", "--table-source", "height"}, invalid},
      {{"--scene", "heightmap", "--evaluation", "table", "--table-spacing", "1", "--table-storage", "float"},
       "cannot prepare the scene: table larger than the RAM budget"},
      {{"--scene-file", saddles},
       "cannot prepare the scene: field not finite on the screen (heights or gradients overflow float)"},
  };
  for (const auto& c : cases) {
    const Parsed p = parse(c.words);
    ASSERT_TRUE(p.ok) << p.error;
    Condition condition;
    std::string error;
    EXPECT_FALSE(make_condition(p.spec, condition, error)) << c.words[1];
    EXPECT_EQ(error, c.error) << c.words[1];
  }
}

TEST(SceneSpec, EveryOptionReachesTheCondition) {
  TunnelParams tunnel;
  tunnel.x_start = 50.0f;
  tunnel.length = 300.0f;
  tunnel.width_start = 40.0f;
  tunnel.width_end = 30.0f;
  tunnel.scale = 10.0f;
  EXPECT_EQ(condition_hash(built({"--scene", "tunnel-diverging", "--tunnel-x-start", "50", "--tunnel-length", "300",
                                  "--width-start", "40", "--width-end", "30", "--tunnel-scale", "10"})),
            condition_hash(of(scenes::steering_tunnel(tunnel, scenes::TunnelMode::Diverging))));

  const Condition table = built({"--scene", "bump-map", "--evaluation", "table", "--table-spacing", "8",
                                 "--table-storage", "float", "--table-source", "height"});
  EXPECT_EQ(table.scene.evaluation, Evaluation::Table);
  EXPECT_EQ(table.scene.table.spacing_px, 8.0f);
  EXPECT_EQ(table.scene.table.storage, TableStorage::Float32);
  EXPECT_EQ(table.scene.table.source, TableSource::HeightCentralDifferences);
  const Condition table_defaults = built({"--scene", "vortex", "--evaluation", "table"});
  EXPECT_EQ(table_defaults.scene.table.storage, TableStorage::Int16);
  EXPECT_EQ(table_defaults.scene.table.source, TableSource::TabulatedGradient);

  const Condition amplitude = built({"--strength", "0.33", "--idle-amplitude", "0.2", "--inverted-dac"});
  EXPECT_EQ(amplitude.amplitude.strength, 0.33f);
  EXPECT_EQ(amplitude.amplitude.idle_amplitude, 0.2f);
  const DacCalibration inverted = DacCalibration::inverted();
  ASSERT_EQ(amplitude.amplitude.calibration.count, inverted.count);
  for (int i = 0; i < inverted.count; ++i) {
    EXPECT_EQ(amplitude.amplitude.calibration.code[i], inverted.code[i]);
  }
}

TEST(SceneSpec, TheWordsWrittenOutBuildTheSameCondition) {
  // scene_words() goes into every output file's metadata: read back, it must
  // name the condition the file was made with.
  const std::string path = scene_file("rendering constant\nconstant 0.25\n");
  const std::vector<std::vector<std::string>> specs = {
      {"--scene", "frictionmap", "--target", "bottom", "--strength", "0.66"},
      {"--scene", "tunnel-converging", "--tunnel-x-start", "50", "--tunnel-length", "300", "--width-start", "40",
       "--width-end", "30", "--tunnel-scale", "10"},
      {"--scene", "bump-map", "--evaluation", "table", "--table-spacing", "8", "--table-storage", "float",
       "--table-source", "height", "--idle-amplitude", "0.2", "--inverted-dac"},
      {"--scene-file", path},
  };
  for (const auto& words : specs) {
    const std::string written = scene_words(parse(words).spec);
    std::vector<std::string> again;
    std::istringstream in(written);
    for (std::string w; in >> w;) again.push_back(w);
    EXPECT_EQ(condition_hash(built(again)), condition_hash(built(words))) << written;
  }
}

TEST(SceneSpec, SceneWordsNameOnlyWhatApplies) {
  EXPECT_EQ(scene_words(parse({"--scene", "heightmap", "--target", "top", "--strength", "0.66"}).spec),
            "--scene heightmap --target top --strength 0.66");
  EXPECT_EQ(scene_words(parse({"--scene", "vortex", "--target", "top"}).spec), "--scene vortex --strength 1");
}

TEST(SceneSpec, AScenePathIsOneShellWordWhateverItsName) {
  // Unquoted, "my scene's.txt" split into two words with an open quote: a
  // scene file with an apostrophe or a space could not be drawn again from
  // a file's metadata (render_scene.py, plot_replay.py split with shlex).
  EXPECT_EQ(scene_words(parse({"--scene-file", "my scene's.txt"}).spec),
            "--scene file --scene-file 'my scene'\\''s.txt' --strength 1");
  EXPECT_EQ(scene_words(parse({"--scene-file", "dir/plain-1.txt"}).spec),
            "--scene file --scene-file dir/plain-1.txt --strength 1");
}

TEST(SceneSpec, TheHashNamesTheConditionNotTheWords) {
  // FNV-1a 64 of nothing is its offset basis (the published constant).
  EXPECT_EQ(hash_hex(0xcbf29ce484222325ull), "cbf29ce484222325");
  Condition a, b;
  std::string error;
  ASSERT_TRUE(make_condition(parse({"--scene", "heightmap", "--target", "top"}).spec, a, error));
  ASSERT_TRUE(make_condition(parse({"--target", "top", "--scene", "heightmap"}).spec, b, error));
  EXPECT_EQ(condition_hash(a), condition_hash(b));
  // The heightmap written out as a general scene file is the same condition.
  const std::string path = scene_file(format_scene_text(scenes::heightmap(Target::Top)).c_str());
  Condition f;
  ASSERT_TRUE(make_condition(parse({"--scene-file", path}).spec, f, error)) << error;
  EXPECT_EQ(condition_hash(f), condition_hash(a));
  ASSERT_TRUE(make_condition(parse({"--scene", "heightmap", "--target", "bottom"}).spec, b, error));
  EXPECT_NE(condition_hash(b), condition_hash(a));
  // Anything that changes the rendering changes the hash.
  Condition c = a;
  c.amplitude.strength = 0.66f;
  EXPECT_NE(condition_hash(c), condition_hash(a));
  c = a;
  c.scene.elements[0].weight += 1e-6f;
  EXPECT_NE(condition_hash(c), condition_hash(a));
  c = a;
  c.amplitude.calibration = DacCalibration::inverted();
  EXPECT_NE(condition_hash(c), condition_hash(a));
  // -0 and 0 render the same.
  c = a;
  c.amplitude.idle_amplitude = -0.0f;
  EXPECT_EQ(condition_hash(c), condition_hash(a));
}

}  // namespace
}  // namespace ff::host
