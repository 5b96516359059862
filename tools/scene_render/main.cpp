// ff-scene-render: samples a scene on a grid so it can be drawn
// (render_scene.py and plot_replay.py turn this into pictures): the
// normalised field and the amplitude felt when moving in a chosen direction.
#include <CLI/CLI.hpp>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <memory>
#include <sstream>

#include "frictionfield/core/haptic_pipeline.hpp"
#include "frictionfield/host/cli_conventions.hpp"
#include "frictionfield/host/scene_hash.hpp"
#include "frictionfield/host/scene_spec.hpp"
#include "frictionfield/host/trace_csv.hpp"

int main(int argc, char** argv) {
  CLI::App app{
      "ff-scene-render: sample a frictionfield scene on a grid (CSV on stdout).\n"
      "First '#' metadata lines (tool, scene words, scene_hash as in ff-replay's output, needs,\n"
      "max_gradient, direction_deg), then the columns x,y,gx,gy,amplitude where\n"
      "(gx, gy) = G / (2 max|G|) and amplitude is A_s for a finger moving in --direction\n"
      "(position-only scenes ignore it).\n"
      "Draw it with tools/scene_render/render_scene.py.\n\n"
      "Exit codes: 0 ok; 2 bad usage or a scene that cannot be built (the message says why)."};
  ff::host::SceneSpec spec;
  float step = 4.0f;
  float direction_deg = 0.0f;
  ff::host::add_scene_options(app, spec);
  app.add_option("--step", step, "grid step in px")->capture_default_str()->check(CLI::Range(1.0f, 100.0f));
  app.add_option("--direction", direction_deg, "direction of motion in degrees (0 = right, 90 = down)")
      ->capture_default_str()
      ->check(CLI::Range(-360.0f, 360.0f));
  if (const int code = ff::host::parse_command_line(app, argc, argv); code >= 0) return code;

  ff::Condition c;
  std::string error;
  if (!ff::host::make_condition(spec, c, error)) {
    std::cerr << "ff-scene-render: " << error << "\n";
    return ff::host::kExitBadUsage;
  }
  auto pipeline = std::make_unique<ff::HapticPipeline>();
  const ff::PrepareStatus st = pipeline->set_condition(c);
  if (st != ff::PrepareStatus::Ok) {
    std::cerr << "ff-scene-render: cannot prepare the scene: " << ff::to_string(st) << "\n";
    return ff::host::kExitBadUsage;
  }
  const ff::ScenePlan& plan = pipeline->plan();
  const ff::AmplitudeMap& map = pipeline->amplitude_map();
  const float rad = direction_deg * ff::kPi / 180.0f;
  const ff::Vec2 dir{std::cos(rad), std::sin(rad)};
  const char* needs = plan.needs() == ff::Needs::Nothing ? "nothing"
                      : plan.needs() == ff::Needs::Position ? "position" : "position+direction";
  char number[32];
  std::snprintf(number, sizeof number, "%.6f", static_cast<double>(plan.stats().max_gradient));
  std::ostringstream meta;
  ff::host::write_metadata(meta, {{"tool", std::string("ff-scene-render ") + ff::host::project_version()},
                                  {"scene", ff::host::scene_words(spec)},
                                  {"scene_hash", ff::host::hash_hex(ff::host::condition_hash(c))},
                                  {"needs", needs},
                                  {"max_gradient", number},
                                  {"table_bytes", std::to_string(plan.stats().table_bytes)},
                                  {"direction_deg", std::to_string(direction_deg)}});
  std::fputs(meta.str().c_str(), stdout);
  std::printf("x,y,gx,gy,amplitude\n");
  for (float y = 0.0f; y <= ff::kScreenMaxY; y += step) {
    for (float x = 0.0f; x <= ff::kScreenMaxX; x += step) {
      const ff::Vec2 g = plan.normalized_gradient({x, y});
      const float a = map.scale(plan.amplitude({x, y}, dir));
      std::printf("%.1f,%.1f,%.5f,%.5f,%.5f\n", static_cast<double>(x), static_cast<double>(y),
                  static_cast<double>(g.x), static_cast<double>(g.y), static_cast<double>(a));
    }
  }
  // A full disk or a closed pipe: the rows did not all arrive (docs/tools.md: exit 2).
  if (std::fflush(stdout) != 0 || std::ferror(stdout)) {
    std::cerr << "ff-scene-render: cannot write standard output: " << std::strerror(errno) << "\n";
    return ff::host::kExitBadUsage;
  }
  return ff::host::kExitOk;
}
