#pragma once
// float32 against the double reference (test/support/reference): the closed-form
// rendering of random scenes at random points and directions, the core's
// max|G|, and the whole thesis chain (docs/spec.md#thesis-tracker + heightmap) on random
// clean traces.
#include <cstdint>
#include <string>

namespace ff::stress {

struct RenderingPrecision {
  int scenes = 0;
  uint64_t evaluations = 0;
  double worst_amplitude = 0.0;          // |A_float - A_double|, both normalised by the core's max|G|
  double worst_max_builtin = 0.0;        // relative max|G| error, the thesis' scenes
  double worst_max_general = 0.0;        // relative max|G| error, random general scenes
  std::string worst_max_scene;           // the general scene with the largest error, as text
};
RenderingPrecision rendering_precision(uint64_t seed, int scenes, int points_per_scene = 400);

struct ChainPrecision {
  int traces = 0;
  uint64_t ticks = 0;
  uint64_t moving_ticks = 0;     // filtered speed >= 50 px/s: the direction is well defined
  double worst_position = 0.0;   // px
  double worst_amplitude = 0.0;  // while moving
};
ChainPrecision thesis_chain_precision(uint64_t seed, int traces);

}  // namespace ff::stress
