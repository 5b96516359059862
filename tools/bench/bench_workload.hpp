#pragma once
// The inputs every cost measurement uses, identical on the host and on the
// Cortex-M4F: points and directions for scene evaluation, and a finger stroke
// (200 Hz samples, 2 kHz ticks) for the tracker and the whole tick.
// Portable: single precision, no allocation.
#include <cstdint>

#include "frictionfield/core/geometry.hpp"
#include "frictionfield/core/scene_plan.hpp"
#include "frictionfield/core/sensor_sample.hpp"

namespace ff::bench {

constexpr int kEvalPoints = 256;

struct EvalPoint {
  Vec2 position;   // spread over the screen (deterministic LCG)
  Vec2 direction;  // unit
};

void make_eval_points(EvalPoint (&out)[kEvalPoints]);

// Sum of the DAC codes round(A * 4095) of plan.amplitude() over the points:
// equal on two machines that compute the same amplitudes.
uint32_t eval_checksum(const ScenePlan& plan, const EvalPoint* points, int count);

// Touch-down at t0, 1 s of motion along heightmap-top's path (x 100 -> 700,
// 600 px/s) with a +-30 px sideways wave at 3 Hz, a report every 5 ms
// (every 10th tick), then a lift (touch = 0) and 30 ms of ticks so that the
// tracker sees the lift-off before the next stroke.
class FingerStroke {
 public:
  static constexpr int kMovingTicks = 2000;
  static constexpr int kSampleEveryTicks = 10;
  static constexpr int kLiftTicks = 60;
  static constexpr int kTotalTicks = kMovingTicks + kLiftTicks;
  static constexpr uint32_t kDurationUs = kTotalTicks * 500u;

  explicit FingerStroke(uint32_t t0_us) : t0_us_(t0_us) {}

  uint32_t tick_time(int tick) const { return t0_us_ + static_cast<uint32_t>(tick) * 500u; }
  // True if a report is due before `tick` (its time is at or before the tick's).
  bool report_before(int tick, SensorSample& out) const;

 private:
  uint32_t t0_us_;
};

}  // namespace ff::bench
