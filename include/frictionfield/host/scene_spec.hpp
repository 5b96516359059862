#pragma once
// The words a researcher uses to pick a condition, shared by ff-replay,
// ffctl and the scene renderer: --scene, --target, --strength, tunnel
// geometry, --scene-file for general scenes, table evaluation options.
#include <string>

#include "frictionfield/core/haptic_pipeline.hpp"

namespace CLI {
class App;
}

namespace ff::host {

struct SceneSpec {
  std::string scene = "heightmap";  // see scene_names()
  std::string target = "middle";    // top | middle | bottom
  float strength = 1.0f;            // s in (0, 1]
  std::string scene_file;           // for --scene file
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

// Registers the shared options on a CLI11 app.
void add_scene_options(CLI::App& app, SceneSpec& spec);

// Builds the condition; false with a readable message on error.
bool make_condition(const SceneSpec& spec, Condition& out, std::string& error);

}  // namespace ff::host
