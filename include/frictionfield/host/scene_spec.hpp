#pragma once
// The words a researcher uses to pick a condition, shared by ff-replay,
// ffctl and the scene renderer: --scene, --target, --strength, tunnel
// geometry, --scene-file for general scenes, table evaluation options.
#include <string>

#include "frictionfield/core/condition.hpp"

namespace CLI {
class App;
}

namespace ff::host {

struct SceneSpec {
  std::string scene = "heightmap";  // see scene_names()
  std::string target = "middle";    // top | middle | bottom
  float strength = 1.0f;            // s in (0, 1]
  std::string scene_file;           // --scene-file: implies --scene file
  bool scene_given = false;         // --scene was on the command line (set by add_scene_options)
  // Steering tunnel (pilots A and B).
  float tunnel_x_start = 100.0f;
  float tunnel_length = 400.0f;
  float tunnel_width_start = 60.0f;
  float tunnel_width_end = 20.0f;
  float tunnel_scale = 1.0f;
  // Evaluation: "closed" or "table"; table spacing and storage.
  std::string evaluation = "closed";
  float table_spacing = 4.0f;
  std::string table_storage = "int16";  // int16 | float
  std::string table_source = "gradient";  // gradient | height
  float idle_amplitude = 0.0f;
  bool inverted_dac = false;  // AD9834 FSADJUST wired as in Analog Devices' circuit note
};

// "heightmap, frictionmap, neutral, ..." for help texts.
const char* scene_names();

// Registers the shared options on a CLI11 app. --scene-file F sets
// spec.scene to "file" (a different --scene with it is a usage error).
void add_scene_options(CLI::App& app, SceneSpec& spec);

// The scene make_condition builds: "file" when a scene file is given.
std::string resolved_scene(const SceneSpec& spec);

// Builds the condition; false with a readable message on error. Values out
// of range (strength outside (0, 1], idle amplitude outside [0, 1], tunnel
// widths or lengths <= 0, ...) are refused, never clamped; so is a scene the
// core's preparation refuses (the PrepareStatus in words), before any device
// is touched.
bool make_condition(const SceneSpec& spec, Condition& out, std::string& error);

// The words that select this condition, only those that apply to the scene
// (e.g. "--scene heightmap --target top --strength 0.66"), for metadata.
std::string scene_words(const SceneSpec& spec);

}  // namespace ff::host
