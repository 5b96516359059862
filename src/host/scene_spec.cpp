#include "frictionfield/host/scene_spec.hpp"

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "frictionfield/core/scene_plan.hpp"
#include "frictionfield/core/scenes.hpp"
#include "frictionfield/host/scene_file.hpp"

namespace ff::host {

const char* scene_names() {
  return "heightmap, frictionmap, neutral, tunnel-converging, tunnel-diverging, tunnel-neutral, "
         "pilot-c, familiarisation-path, bump-map, vortex, file";
}

void add_scene_options(CLI::App& app, SceneSpec& spec) {
  app.add_option("--scene", spec.scene, std::string("scene to render: ") + scene_names())
      ->capture_default_str()
      ->each([&spec](const std::string&) { spec.scene_given = true; });
  app.add_option("--target", spec.target, "path target: top, middle or bottom")->capture_default_str();
  app.add_option("--strength", spec.strength, "haptic strength s in (0, 1]: 1, 0.66, 0.33 in the experiment")
      ->capture_default_str();
  // CLI11 runs option callbacks in the order the options were added, so
  // --scene is known here whatever the order on the command line.
  app.add_option("--scene-file", spec.scene_file, "general scene definition (implies --scene file)")
      ->each([&spec](const std::string&) {
        if (spec.scene_given && spec.scene != "file") {
          throw CLI::ValidationError("a scene file is --scene file, not --scene " + spec.scene +
                                     ": drop one of the two");
        }
        spec.scene = "file";
      });
  app.add_option("--tunnel-x-start", spec.tunnel_x_start, "steering tunnel: start x (px)")->capture_default_str();
  app.add_option("--tunnel-length", spec.tunnel_length, "steering tunnel: length (px)")->capture_default_str();
  app.add_option("--width-start", spec.tunnel_width_start, "steering tunnel: width at the start (px)")
      ->capture_default_str();
  app.add_option("--width-end", spec.tunnel_width_end, "steering tunnel: width at the end (px)")
      ->capture_default_str();
  app.add_option("--tunnel-scale", spec.tunnel_scale, "steering tunnel: valley scale s (1 pilot A, 10 pilot B)")
      ->capture_default_str();
  app.add_option("--evaluation", spec.evaluation, "closed (closed-form gradients) or table (lookup table)")
      ->capture_default_str();
  app.add_option("--table-spacing", spec.table_spacing, "lookup table node spacing (px)")->capture_default_str();
  app.add_option("--table-storage", spec.table_storage, "lookup table storage: int16 or float")
      ->capture_default_str();
  app.add_option("--table-source", spec.table_source,
                 "lookup table contents: gradient (tabulated) or height (central differences)")
      ->capture_default_str();
  app.add_option("--idle-amplitude", spec.idle_amplitude, "amplitude without a finger (0: the plate rests)")
      ->capture_default_str();
  app.add_flag("--inverted-dac", spec.inverted_dac,
               "decreasing DAC calibration (AD9834 FSADJUST wired as in Analog Devices' circuit note)");
}

namespace {

bool parse_target(const std::string& name, Target& out) {
  if (name == "top") out = Target::Top;
  else if (name == "middle") out = Target::Middle;
  else if (name == "bottom") out = Target::Bottom;
  else return false;
  return true;
}

}  // namespace

std::string resolved_scene(const SceneSpec& spec) {
  return spec.scene_file.empty() || spec.scene_given ? spec.scene : std::string("file");
}

namespace {

bool uses_target(const std::string& scene) {
  return scene == "heightmap" || scene == "frictionmap" || scene == "pilot-c";
}
bool is_tunnel(const std::string& scene) { return scene.rfind("tunnel-", 0) == 0; }

std::string number(float v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", static_cast<double>(v));
  return buf;
}

// Refused, never clamped: a condition that is not what was asked for is worse than none.
bool check_ranges(const SceneSpec& spec, const std::string& scene, std::string& error) {
  if (!(spec.strength > 0.0f && spec.strength <= 1.0f)) {
    error = "strength must be in (0, 1], got " + number(spec.strength) + " (the experiment uses 1, 0.66 and 0.33)";
    return false;
  }
  if (!(spec.idle_amplitude >= 0.0f && spec.idle_amplitude <= 1.0f)) {
    error = "idle amplitude " + number(spec.idle_amplitude) + " is outside [0, 1]";
    return false;
  }
  if (is_tunnel(scene)) {
    const struct { const char* name; float value; } positive[] = {
        {"--tunnel-length", spec.tunnel_length}, {"--width-start", spec.tunnel_width_start},
        {"--width-end", spec.tunnel_width_end}, {"--tunnel-scale", spec.tunnel_scale}};
    for (const auto& p : positive) {
      if (!(p.value > 0.0f && std::isfinite(p.value))) {
        error = std::string(p.name) + " " + number(p.value) + " must be a positive number";
        return false;
      }
    }
    if (!std::isfinite(spec.tunnel_x_start)) return error = "--tunnel-x-start must be a number", false;
  }
  if (spec.evaluation == "table" && !(spec.table_spacing >= 1.0f && spec.table_spacing <= 100.0f)) {
    error = "--table-spacing " + number(spec.table_spacing) + " is outside [1, 100] px";
    return false;
  }
  return true;
}

// A path as one shell word (POSIX quoting, as Python's shlex.split reads it):
// the words in metadata must split back into the words typed, whatever the
// file is called. Plain names stay as they are.
std::string shell_quoted(const std::string& word) {
  const bool plain = !word.empty() && word.find_first_not_of(
                                          "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_./+-=:,@%") ==
                                          std::string::npos;
  if (plain) return word;
  std::string quoted = "'";
  for (const char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

}  // namespace

std::string scene_words(const SceneSpec& spec) {
  const std::string scene = resolved_scene(spec);
  std::string w = "--scene " + scene;
  if (scene == "file") w += " --scene-file " + shell_quoted(spec.scene_file);
  if (uses_target(scene)) w += " --target " + spec.target;
  w += " --strength " + number(spec.strength);
  if (is_tunnel(scene)) {
    w += " --tunnel-x-start " + number(spec.tunnel_x_start) + " --tunnel-length " + number(spec.tunnel_length) +
         " --width-start " + number(spec.tunnel_width_start) + " --width-end " + number(spec.tunnel_width_end) +
         " --tunnel-scale " + number(spec.tunnel_scale);
  }
  if (spec.evaluation == "table") {
    w += " --evaluation table --table-spacing " + number(spec.table_spacing) + " --table-storage " +
         spec.table_storage + " --table-source " + spec.table_source;
  }
  if (spec.idle_amplitude != 0.0f) w += " --idle-amplitude " + number(spec.idle_amplitude);
  if (spec.inverted_dac) w += " --inverted-dac";
  return w;
}

namespace {
// What the core refuses as an invalid parameter in a height table (a vortex
// that weighs something), to say why.
bool vortex_in_a_height_table(const SceneDefinition& scene) {
  if (scene.evaluation != Evaluation::Table || scene.table.source != TableSource::HeightCentralDifferences) return false;
  for (uint8_t i = 0; i < scene.element_count; ++i)
    if (scene.elements[i].kind == ElementKind::Vortex && scene.elements[i].weight != 0.0f) return true;
  return false;
}
}  // namespace

bool make_condition(const SceneSpec& spec, Condition& out, std::string& error) {
  const std::string s = resolved_scene(spec);
  if (!spec.scene_file.empty() && s != "file") {
    error = "a scene file is --scene file, not --scene " + s + ": drop one of the two";
    return false;
  }
  Target target;
  if (!parse_target(spec.target, target)) {
    error = "unknown target '" + spec.target + "': use top, middle or bottom";
    return false;
  }
  if (!check_ranges(spec, s, error)) return false;
  TunnelParams tunnel;
  tunnel.x_start = spec.tunnel_x_start;
  tunnel.length = spec.tunnel_length;
  tunnel.width_start = spec.tunnel_width_start;
  tunnel.width_end = spec.tunnel_width_end;
  tunnel.scale = spec.tunnel_scale;

  Condition c;
  if (s == "heightmap") c.scene = scenes::heightmap(target);
  else if (s == "frictionmap") c.scene = scenes::frictionmap(target);
  else if (s == "neutral") c.scene = scenes::neutral();
  else if (s == "tunnel-converging") c.scene = scenes::steering_tunnel(tunnel, scenes::TunnelMode::Converging);
  else if (s == "tunnel-diverging") c.scene = scenes::steering_tunnel(tunnel, scenes::TunnelMode::Diverging);
  else if (s == "tunnel-neutral") c.scene = scenes::steering_tunnel(tunnel, scenes::TunnelMode::Neutral);
  else if (s == "pilot-c") c.scene = scenes::pilot_c_valley(target);
  else if (s == "familiarisation-path") c.scene = scenes::familiarisation_path();
  else if (s == "bump-map") c.scene = scenes::bump_map();
  else if (s == "vortex") c.scene = scenes::vortex();
  else if (s == "file") {
    if (spec.scene_file.empty()) {
      error = "--scene file needs --scene-file PATH";
      return false;
    }
    if (!read_scene_file(spec.scene_file, c.scene, error)) return false;
  } else {
    error = "unknown scene '" + s + "': use one of " + scene_names();
    return false;
  }

  if (spec.evaluation == "table") {
    c.scene.evaluation = Evaluation::Table;
    c.scene.table.spacing_px = spec.table_spacing;
    if (spec.table_storage == "int16") c.scene.table.storage = TableStorage::Int16;
    else if (spec.table_storage == "float") c.scene.table.storage = TableStorage::Float32;
    else return error = "table storage is int16 or float", false;
    if (spec.table_source == "gradient") c.scene.table.source = TableSource::TabulatedGradient;
    else if (spec.table_source == "height") c.scene.table.source = TableSource::HeightCentralDifferences;
    else return error = "table source is gradient or height", false;
  } else if (spec.evaluation != "closed" && !(s == "file" && spec.evaluation.empty())) {
    error = "evaluation is closed or table";
    return false;
  }

  c.amplitude.strength = spec.strength;
  c.amplitude.idle_amplitude = spec.idle_amplitude;
  if (spec.inverted_dac) c.amplitude.calibration = DacCalibration::inverted();
  // What the core's preparation refuses (a table too large for its slot, a
  // field past float) the device would refuse too, after it was touched:
  // prepared here as the device does, one slot.
  auto plan = std::make_unique<ScenePlan>();
  std::vector<unsigned char> table(kTableSlotBytes);
  const PrepareStatus status = plan->prepare(c.scene, table.data(), table.size());
  if (status != PrepareStatus::Ok) {
    error = std::string("cannot prepare the scene: ") + to_string(status);
    if (status == PrepareStatus::InvalidParameter && vortex_in_a_height_table(c.scene)) {
      error = "cannot prepare the scene: a vortex has no height to tabulate (no potential makes its swirl): "
              "use table source gradient, or closed evaluation";
    }
    return false;
  }
  out = c;
  return true;
}

}  // namespace ff::host
