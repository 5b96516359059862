#pragma once
// Drives a HapticPipeline through reports and tick times as docs/spec.md#tick-timing times a
// replay (every report delivered at or before a tick goes in before it), and
// checks every tick against the invariants and the double reference.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "frictionfield/core/haptic_pipeline.hpp"
#include "support/reference/reference_amplitude.hpp"
#include "support/reference/reference_scene.hpp"
#include "support/reference/reference_tracker.hpp"
#include "stress_traces.hpp"

namespace ff::stress {

struct RunConfig {
  TrackerConfig tracker = TrackerConfig::recommended();
  Condition condition;
  bool calibration_valid = true;  // what the generator built (invalid ones must fall back to linear)
};

struct Tick {
  uint64_t at = 0;
  TickOutput out;
};

struct RunResult {
  PrepareStatus status = PrepareStatus::Ok;
  std::vector<Tick> ticks;
  FaultCounters faults;
  uint32_t failed_posts = 0;  // post_sample() refused: the mailbox was full
};

// Fresh pipeline, set_condition, then the timeline. `observe` (optional) sees
// every tick with the pipeline (for checks that need the plan).
class TickObserver {
 public:
  virtual ~TickObserver() = default;
  virtual void on_tick(const HapticPipeline& pipeline, const Tick& tick) = 0;
};
RunResult run_pipeline(const RunConfig& config, const std::vector<Report>& reports,
                       const std::vector<TickTime>& ticks, TickObserver* observe = nullptr,
                       bool keep_ticks = true);

// Per-tick invariants (docs/spec.md#amplitude, #trace-files):
// amplitude finite and inside [0.5 - s/2, 0.5 + s/2] with a finger, exactly
// the idle amplitude without; DAC code in [0, 4095] and equal to the
// calibration of the amplitude; position on screen; |direction| <= 1; and
// the amplitude against the double reference evaluated at the tick's own
// position and direction (the float32 rendering error).
class InvariantChecker : public TickObserver {
 public:
  InvariantChecker(const RunConfig& config, double rendering_bound);
  void on_tick(const HapticPipeline& pipeline, const Tick& tick) override;

  uint64_t ticks = 0;
  uint64_t violations = 0;
  uint64_t dac_ties = 0;            // reference exactly between two codes: +-1 allowed
  double worst_rendering = 0.0;     // max |A_float - A_double| (closed-form scenes)
  double worst_table = 0.0;         // the same for table scenes: tabulation error, reported only
  double max_gradient_error = 0.0;  // |max|G|_core - max|G|_double| / max|G|_double (closed-form directional scenes)
  std::string first_violation;

 private:
  void fail(const Tick& t, const std::string& what);
  reference::ReferenceScene scene_;
  reference::ReferenceAmplitude amplitude_;
  double rendering_bound_;
  bool closed_form_;
  bool first_tick_ = true;
};

// Ticks after `from_at` until a and b agree (same presence, |dpos| <= pos_tol,
// |damp| <= amp_tol) at every common tick to the end; -1 if they never do.
// Ticks are matched by real time.
// `last_difference` (optional) describes the last tick where they differed.
// Without a rest fade (the thesis' v_hat = dxhat / |dxhat| at any speed) the
// direction of a resting finger is whatever its last tiny motion left, so
// `amplitude_at_rest = false` compares amplitudes only while b's finger
// moves (over 50 px/s across the last 10 ms).
int64_t recovery_ticks(const std::vector<Tick>& a, const std::vector<Tick>& b, uint64_t from_at,
                       double pos_tol = 0.5, double amp_tol = 0.02, std::string* last_difference = nullptr,
                       bool amplitude_at_rest = true);

// Bit-for-bit equality of two runs' outputs; empty when equal.
// `ignore_time`: compare everything but the reported tick time (shifted clocks).
std::string bitwise_difference(const std::vector<Tick>& a, const std::vector<Tick>& b, bool ignore_time = false);

}  // namespace ff::stress
