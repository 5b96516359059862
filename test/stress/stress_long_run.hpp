#pragma once
// Three simulated hours at 2 kHz with the finger down the whole time,
// through three wraps of the 32-bit microsecond clock: the same one-minute
// cycle of strokes, a noise-free 5 s rest and (every tenth cycle) a lift,
// repeated. Measures drift at rest, tracking error per cycle and counters.
#include <cstdint>
#include <vector>

#include "frictionfield/core/haptic_pipeline.hpp"

namespace ff::stress {

struct LongRunResult {
  uint64_t seconds = 0;
  uint64_t ticks = 0;
  uint64_t cycles = 0;
  uint64_t lifts = 0;
  uint64_t bad_ticks = 0;       // amplitude non-finite / out of [0, 1], DAC wrong
  double wall_seconds = 0.0;
  double worst_rest_offset = 0.0;  // px, filtered vs sensor at the end of each rest
  double first_max_error = 0.0, worst_max_error = 0.0;    // px, while stroking, per cycle
  double first_mean_error = 0.0, worst_mean_error = 0.0;  // px
  uint32_t pipeline_ticks = 0;
  FaultCounters faults;
  std::vector<double> max_error_per_cycle, rest_offset_per_cycle;
};

LongRunResult long_run(const TrackerConfig& tracker, uint64_t seconds, uint64_t seed);

}  // namespace ff::stress
