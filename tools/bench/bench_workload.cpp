#include "bench_workload.hpp"

#include <cmath>

#include "frictionfield/core/path_curve.hpp"

namespace ff::bench {

namespace {

uint32_t next(uint32_t& state) {
  state = state * 1664525u + 1013904223u;  // Numerical Recipes LCG: same sequence everywhere
  return state >> 8;                        // 24 bits: exact in a float
}

float unit_interval(uint32_t& state) { return static_cast<float>(next(state)) * (1.0f / 16777216.0f); }

}  // namespace

void make_eval_points(EvalPoint (&out)[kEvalPoints]) {
  uint32_t state = 12345u;
  for (EvalPoint& p : out) {
    p.position = {unit_interval(state) * kScreenMaxX, unit_interval(state) * kScreenMaxY};
    const float angle = 2.0f * kPi * unit_interval(state);
    p.direction = {std::cos(angle), std::sin(angle)};
  }
}

uint32_t eval_checksum(const ScenePlan& plan, const EvalPoint* points, int count) {
  uint32_t sum = 0;
  for (int i = 0; i < count; ++i) {
    const float a = plan.amplitude(points[i].position, points[i].direction);
    sum += static_cast<uint32_t>(std::lround(a * 4095.0f));
  }
  return sum;
}

bool FingerStroke::report_before(int tick, SensorSample& out) const {
  if (tick % kSampleEveryTicks != 0 || tick > kMovingTicks) return false;
  out.t_us = tick_time(tick);
  if (tick == kMovingTicks) {  // the lift
    out.touch = false;
    out.x = out.y = 0.0f;
    return true;
  }
  const float t_s = static_cast<float>(tick) * 0.0005f;
  const float x = 100.0f + 600.0f * t_s;
  const float y = PathCurve::cubic(target_rise(Target::Top)).at(x).y +
                  30.0f * std::sin(2.0f * kPi * 3.0f * t_s);
  out.x = x;
  out.y = y;
  out.touch = true;
  return true;
}

}  // namespace ff::bench
