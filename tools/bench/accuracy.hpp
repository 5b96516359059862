#pragma once
// Amplitude error of a prepared ScenePlan against the double-precision
// reference, over a dense grid and 16 directions of motion, in DAC LSB
// (1/4095 of the amplitude range, strength 1).
#include <vector>

#include "frictionfield/core/scene_plan.hpp"
#include "bench_cases.hpp"
#include "support/reference/reference_scene.hpp"

namespace ff::bench {

// The double reference of a benchmarked scene: the spec's own scene
// (test/support/reference/spec_scenes) for the built-in ones, the bench's
// definition for the general ones; max|G| from every pixel, refined to 1e-9 px.
reference::ReferenceScene reference_scene_for(SceneId id);

constexpr int kDirections = 16;
constexpr double kLsb = 1.0 / 4095.0;
constexpr double kInteriorMarginPx = 16.0;  // the widest table spacing

struct Accuracy {
  double max_lsb = 0.0;
  double rms_lsb = 0.0;
  double p99_lsb = 0.0;           // 99th percentile (to 0.01 LSB): the worst outside isolated spots
  double max_interior_lsb = 0.0;  // at least kInteriorMarginPx inside the screen's edges
  reference::DVec worst_position;  // where the largest error is
  double worst_direction_deg = 0.0; // direction of motion there (0 = +x, 90 = +y, screen down)
  long samples = 0;
};

// The reference evaluated once per scene on the grid x = 0.5 + i step,
// y = 0.5 + j step (between pixel centres: never on a table node, never on a
// cone apex); every strategy of the scene is then compared with it.
class ReferenceGrid {
 public:
  ReferenceGrid(const reference::ReferenceScene& scene, double step_px);

  double max_gradient() const { return max_g_; }
  size_t points() const { return points_.size(); }
  Accuracy measure(const ScenePlan& plan) const;

 private:
  reference::ReferenceScene scene_;
  double max_g_ = 0.0;
  std::vector<reference::DVec> points_;
  std::vector<reference::DVec> field_;  // directional scenes
  std::vector<double> value_;            // position-only and constant scenes
};

}  // namespace ff::bench
