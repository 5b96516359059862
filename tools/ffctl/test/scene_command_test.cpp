// The scene words of ffctl scene/record, as a researcher types them, into the
// SetCondition message; and back through the wire into the condition the
// firmware renders, which must be the one ff-replay builds from the same words.
#include <gtest/gtest.h>

#include <CLI/CLI.hpp>
#include <fstream>
#include <vector>

#include "frictionfield/core/scenes.hpp"
#include "frictionfield/host/scene_file.hpp"
#include "frictionfield/protocol/codec.hpp"
#include "scene_command.hpp"
#include "support/scratch_path.hpp"

namespace ff::ffctl {
namespace {

struct Parsed {
  bool ok = false;
  protocol::ConditionMessage message;
  std::string error;
  host::SceneSpec spec;
};

Parsed parse(std::vector<std::string> words) {
  Parsed p;
  CLI::App app{"scene"};
  host::add_scene_options(app, p.spec);
  std::vector<std::string> reversed(words.rbegin(), words.rend());  // CLI11 takes them back to front
  app.parse(reversed);
  p.ok = condition_message(p.spec, p.message, p.error);
  return p;
}

// What the firmware renders: the message encoded, decoded, turned into a condition.
Condition over_the_wire(const protocol::ConditionMessage& c) {
  protocol::Message m;
  m.type = protocol::MessageType::SetCondition;
  m.condition = c;
  std::vector<uint8_t> frame(protocol::kMaxFrame);
  frame.resize(protocol::encode(m, frame.data(), frame.size()));
  EXPECT_GT(frame.size(), 0u);
  protocol::Message back;
  EXPECT_EQ(protocol::decode(frame.data(), frame.size(), back), protocol::DecodeStatus::Ok);
  return back.condition.to_condition();
}

void expect_same_condition_as_ff_replay(const Parsed& p) {
  Condition native;
  std::string error;
  ASSERT_TRUE(host::make_condition(p.spec, native, error)) << error;
  const Condition device = over_the_wire(p.message);
  EXPECT_EQ(host::format_scene_text(device.scene), host::format_scene_text(native.scene));
  EXPECT_FLOAT_EQ(device.amplitude.strength, native.amplitude.strength);
  EXPECT_FLOAT_EQ(device.amplitude.idle_amplitude, native.amplitude.idle_amplitude);
  EXPECT_FLOAT_EQ(device.amplitude.s_curve, native.amplitude.s_curve);
  ASSERT_EQ(device.amplitude.calibration.count, native.amplitude.calibration.count);
  for (int i = 0; i < native.amplitude.calibration.count; ++i) {
    EXPECT_FLOAT_EQ(device.amplitude.calibration.amplitude[i], native.amplitude.calibration.amplitude[i]) << i;
    EXPECT_FLOAT_EQ(device.amplitude.calibration.code[i], native.amplitude.calibration.code[i]) << i;
  }
}

TEST(SceneCommand, ThesisConditionsTravelAsKindTargetAndStrength) {
  const Parsed h = parse({"--scene", "heightmap", "--target", "top", "--strength", "0.66"});
  ASSERT_TRUE(h.ok) << h.error;
  EXPECT_EQ(h.message.kind, protocol::ConditionKind::Heightmap);
  EXPECT_EQ(h.message.target, Target::Top);
  EXPECT_FLOAT_EQ(h.message.strength, 0.66f);
  EXPECT_EQ(h.message.scene.element_count, 0u);  // the firmware builds it itself
  expect_same_condition_as_ff_replay(h);

  const Parsed f = parse({"--scene", "frictionmap", "--target", "bottom", "--strength", "0.33"});
  ASSERT_TRUE(f.ok) << f.error;
  EXPECT_EQ(f.message.kind, protocol::ConditionKind::Frictionmap);
  EXPECT_EQ(f.message.target, Target::Bottom);
  expect_same_condition_as_ff_replay(f);

  const Parsed n = parse({"--scene", "neutral", "--idle-amplitude", "0.2"});
  ASSERT_TRUE(n.ok) << n.error;
  EXPECT_EQ(n.message.kind, protocol::ConditionKind::Neutral);
  EXPECT_FLOAT_EQ(n.message.idle_amplitude, 0.2f);
  expect_same_condition_as_ff_replay(n);
}

TEST(SceneCommand, AnInvertedDacTravelsWithTheCondition) {
  // The FSADJUST wiring that gives less current for more DAC volts: amplitude 1 at code 0.
  const Parsed p = parse({"--scene", "heightmap", "--inverted-dac"});
  ASSERT_TRUE(p.ok) << p.error;
  EXPECT_EQ(p.message.calibration.code_for(1.0f), 0);
  EXPECT_EQ(p.message.calibration.code_for(0.0f), 4095);
  expect_same_condition_as_ff_replay(p);
}

TEST(SceneCommand, EverythingElseTravelsWholeAsAGeneralScene) {
  for (const char* scene : {"tunnel-converging", "tunnel-diverging", "pilot-c", "familiarisation-path", "bump-map",
                            "vortex"}) {
    const Parsed p = parse({"--scene", scene, "--strength", "0.5"});
    ASSERT_TRUE(p.ok) << scene << ": " << p.error;
    EXPECT_EQ(p.message.kind, protocol::ConditionKind::General) << scene;
    EXPECT_GT(p.message.scene.element_count, 0u) << scene;
    expect_same_condition_as_ff_replay(p);
  }
  // A table-evaluated heightmap is not the closed-form one the firmware would build.
  const Parsed t = parse({"--scene", "heightmap", "--target", "middle", "--evaluation", "table", "--table-spacing", "8"});
  ASSERT_TRUE(t.ok) << t.error;
  EXPECT_EQ(t.message.kind, protocol::ConditionKind::General);
  EXPECT_EQ(t.message.scene.evaluation, Evaluation::Table);
  EXPECT_FLOAT_EQ(t.message.scene.table.spacing_px, 8.0f);
  expect_same_condition_as_ff_replay(t);
  // A scene file travels whole as what ff-replay builds from the same words,
  // with or without --scene file (src/host decides what --scene-file implies).
  const std::string path = support::scratch_path("scene_command_file.scene");
  {
    std::ofstream out(path);
    out << host::format_scene_text(scenes::heightmap(Target::Bottom));
  }
  for (const std::vector<std::string>& words : std::vector<std::vector<std::string>>{
           {"--scene", "file", "--scene-file", path}, {"--scene-file", path}}) {
    const Parsed f = parse(words);
    if (!f.ok) continue;  // src/host may refuse a combination: then nothing is sent
    EXPECT_EQ(f.message.kind, protocol::ConditionKind::General) << words.size();
    expect_same_condition_as_ff_replay(f);
  }
}

TEST(SceneCommand, WordsThatMakeNoConditionSaySo) {
  const Parsed target = parse({"--scene", "heightmap", "--target", "left"});
  EXPECT_FALSE(target.ok);
  EXPECT_NE(target.error.find("unknown target 'left'"), std::string::npos) << target.error;
  const Parsed strength = parse({"--strength", "1.5"});
  EXPECT_FALSE(strength.ok);
  EXPECT_NE(strength.error.find("strength must be in (0, 1]"), std::string::npos) << strength.error;
  const Parsed scene = parse({"--scene", "moon"});
  EXPECT_FALSE(scene.ok);
  EXPECT_NE(scene.error.find("unknown scene 'moon'"), std::string::npos) << scene.error;
}

TEST(SceneCommand, AScenePastThePreparationBudgetIsRefusedBeforeItIsSent) {
  // 7 valleys along a 16-point zigzag and a 16 px texture: a 2 px max|G| scan
  // of 401 x 241 nodes at 8 elements each, 182 M modelled M4 instructions
  // against 36 M (docs/spec.md#preparation-cost); the Teensy took 127.5 M
  // instructions and its hardware watchdog reset it before the Ack.
  SceneDefinition s;
  s.rendering = Rendering::Directional;
  const Vec2 zigzag[16] = {{0, 100},  {50, 300},  {100, 120}, {150, 330}, {200, 90},  {250, 360},
                           {300, 80}, {350, 380}, {400, 70},  {450, 390}, {500, 60},  {550, 400},
                           {600, 50}, {650, 410}, {700, 40},  {750, 420}};
  for (int i = 1; i <= 7; ++i) {
    s.add(FieldElement::path_sink(PathCurve::polyline(zigzag, 16), 0.1f * static_cast<float>(i), 1.0f));
  }
  s.add(FieldElement::sine_texture(16, 16, 1));
  const std::string path = support::scratch_path("scene_command_too_costly.scene");
  {
    std::ofstream out(path);
    out << host::format_scene_text(s);
  }
  const Parsed p = parse({"--scene-file", path});
  EXPECT_FALSE(p.ok);
  EXPECT_EQ(p.error, "cannot prepare the scene: " + std::string(to_string(PrepareStatus::TooCostlyToPrepare)));
}

}  // namespace
}  // namespace ff::ffctl
