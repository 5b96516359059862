// ff-scene-render: samples a scene on a grid so it can be drawn
// (render_scene.py turns this into a PNG): the normalised field and the
// amplitude felt when moving in a chosen direction.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>

#include "frictionfield/core/haptic_pipeline.hpp"
#include "frictionfield/host/scene_spec.hpp"

int main(int argc, char** argv) {
  CLI::App app{
      "ff-scene-render: sample a frictionfield scene on a grid (CSV on stdout).\n"
      "Columns: x,y,gx,gy,amplitude where (gx, gy) = G / (2 max|G|) and amplitude is A_s\n"
      "for a finger moving in --direction (position-only scenes ignore it).\n"
      "Draw it with tools/scene_render/render_scene.py."};
  ff::host::SceneSpec spec;
  float step = 4.0f;
  float direction_deg = 0.0f;
  ff::host::add_scene_options(app, spec);
  app.add_option("--step", step, "grid step in px")->capture_default_str()->check(CLI::Range(1.0f, 100.0f));
  app.add_option("--direction", direction_deg, "direction of motion in degrees (0 = right, 90 = down)")
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  ff::Condition c;
  std::string error;
  if (!ff::host::make_condition(spec, c, error)) {
    std::cerr << "ff-scene-render: " << error << "\n";
    return 2;
  }
  auto pipeline = std::make_unique<ff::HapticPipeline>();
  const ff::PrepareStatus st = pipeline->set_condition(c);
  if (st != ff::PrepareStatus::Ok) {
    std::cerr << "ff-scene-render: cannot prepare the scene: " << ff::to_string(st) << "\n";
    return 2;
  }
  const ff::ScenePlan& plan = pipeline->plan();
  const ff::AmplitudeMap& map = pipeline->amplitude_map();
  const float rad = direction_deg * ff::kPi / 180.0f;
  const ff::Vec2 dir{std::cos(rad), std::sin(rad)};
  const char* needs = plan.needs() == ff::Needs::Nothing ? "nothing"
                      : plan.needs() == ff::Needs::Position ? "position" : "position+direction";
  std::printf("# scene=%s target=%s strength=%.3f needs=%s max_gradient=%.6f table_bytes=%u\n",
              spec.scene.c_str(), spec.target.c_str(), static_cast<double>(spec.strength), needs,
              static_cast<double>(plan.stats().max_gradient), plan.stats().table_bytes);
  std::printf("x,y,gx,gy,amplitude\n");
  for (float y = 0.0f; y <= ff::kScreenMaxY; y += step) {
    for (float x = 0.0f; x <= ff::kScreenMaxX; x += step) {
      const ff::Vec2 g = plan.normalized_gradient({x, y});
      const float a = map.scale(plan.amplitude({x, y}, dir));
      std::printf("%.1f,%.1f,%.5f,%.5f,%.5f\n", static_cast<double>(x), static_cast<double>(y),
                  static_cast<double>(g.x), static_cast<double>(g.y), static_cast<double>(a));
    }
  }
  return 0;
}
