#include "stress_long_run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include "frictionfield/core/scenes.hpp"
#include "stress_random.hpp"
#include "stress_traces.hpp"

namespace ff::stress {

namespace {

constexpr uint64_t kCycleUs = 60000000;     // one minute, a whole number of ticks
constexpr uint64_t kTicksPerCycle = kCycleUs / kTickPeriodUs;
constexpr uint64_t kRestUs = 5000000;

struct CycleReport {
  uint64_t offset;  // us into the cycle
  float x, y;
  bool touch;
};

struct Cycle {
  std::vector<CycleReport> reports;   // with a lift
  std::vector<CycleReport> no_lift;   // the same without it
  std::vector<float> truth_x, truth_y;  // per tick
  std::vector<bool> stroking;         // per tick: the finger moves
  uint64_t rest_end_tick = 0;         // first tick after the rest
  Vec2 rest_point;                    // float, as the sensor reports it
};

// One minute: strokes from P0 for ~52 s, a 5 s noise-free rest, back to P0.
Cycle make_cycle(uint64_t seed) {
  Rng rng(seed);
  const reference::DVec p0{400.0, 240.0};
  Motion m(0, p0);
  while (m.end() < 52000000) {
    const reference::DVec to{rng.uniform(30.0, 770.0), rng.uniform(30.0, 450.0)};
    m.stroke(to, rng.uniform(0.3, 1.5));
    if (rng.chance(0.3)) m.rest(rng.uniform(0.05, 0.3));
  }
  const reference::DVec rest{rng.uniform(100.0, 700.0), rng.uniform(100.0, 380.0)};
  m.stroke(rest, 0.5);
  const uint64_t rest_start = m.end();
  m.rest(static_cast<double>(kRestUs) * 1e-6);
  const uint64_t lift_start = m.end();
  m.lift(0.3);
  m.stroke(p0, static_cast<double>(kCycleUs - m.end()) * 1e-6);

  Cycle c;
  c.rest_point = {static_cast<float>(rest.x), static_cast<float>(rest.y)};
  c.rest_end_tick = (rest_start + kRestUs) / kTickPeriodUs;
  for (uint64_t k = 0;; ++k) {
    const uint64_t t = k * 5000 + static_cast<uint64_t>(rng.integer(0, 300));
    if (t >= kCycleUs) break;
    const bool lifted = t >= lift_start && t < lift_start + 300000;
    const reference::DVec p = m.position(t);
    const reference::DVec q = m.position(t + 1000);
    const bool moving = p.x != q.x || p.y != q.y;
    const double noise = moving ? 0.7 : 0.0;  // the rest is noise-free: drift shows
    const CycleReport r{t, static_cast<float>(p.x + noise * rng.gaussian()), static_cast<float>(p.y + noise * rng.gaussian()), true};
    c.no_lift.push_back(r);  // without the lift the finger just rests on
    if (lifted && t > lift_start + 5000) continue;  // one touch = 0 report per lift
    c.reports.push_back(lifted ? CycleReport{t, 0.0f, 0.0f, false} : r);
  }
  for (uint64_t k = 0; k < kTicksPerCycle; ++k) {
    const uint64_t t = k * kTickPeriodUs;
    const reference::DVec p = m.position(t);
    const reference::DVec q = m.position(t + 1000);
    c.truth_x.push_back(static_cast<float>(p.x));
    c.truth_y.push_back(static_cast<float>(p.y));
    const bool moving = p.x != q.x || p.y != q.y;
    c.stroking.push_back(moving && (t < lift_start || t > lift_start + 600000));  // settle after touch-down
  }
  return c;
}

struct CycleStats {
  double max_error = 0.0;   // px, while stroking
  double sum_error = 0.0;
  uint64_t n = 0;
  double rest_error = 0.0;  // px, last tick of the rest
};

}  // namespace

LongRunResult long_run(const TrackerConfig& tracker, uint64_t seconds, uint64_t seed) {
  // Whole one-minute cycles, at least one (a shorter run left none, and the
  // first-minute figures read an empty list: ff-stress-report crashed).
  const uint64_t cycles = std::max<uint64_t>(1, (seconds * 1000000 + kCycleUs - 1) / kCycleUs);
  const Cycle cycle = make_cycle(seed);
  auto pipeline = std::make_unique<HapticPipeline>(tracker);
  Condition condition;
  condition.scene = scenes::heightmap(Target::Middle);
  pipeline->set_condition(condition);

  // Start 30 s before the wrap: it wraps mid-stroke at 30 s, 71.6 min and 143.2 min.
  const uint64_t start = (uint64_t{1} << 32) - 30000000;
  std::vector<CycleStats> stats(cycles);
  uint64_t bad_ticks = 0, lifts = 0, ticks = 0;
  const auto t0 = std::chrono::steady_clock::now();
  for (uint64_t c = 0; c < cycles; ++c) {
    const bool lift = c % 10 == 9;
    const std::vector<CycleReport>& reports = lift ? cycle.reports : cycle.no_lift;
    lifts += lift ? 1 : 0;
    const uint64_t base = start + c * kCycleUs;
    size_t next = 0;
    CycleStats& s = stats[c];
    for (uint64_t k = 0; k < kTicksPerCycle; ++k, ++ticks) {
      const uint64_t offset = k * kTickPeriodUs;
      while (next < reports.size() && reports[next].offset <= offset) {
        const CycleReport& r = reports[next++];
        pipeline->post_sample({static_cast<uint32_t>(base + r.offset), r.x, r.y, r.touch});
      }
      const TickOutput o = pipeline->tick(static_cast<uint32_t>(base + offset));
      if (!std::isfinite(o.amplitude) || o.amplitude < 0.0f || o.amplitude > 1.0f || o.dac > kDacMax ||
          (o.present && o.dac != static_cast<uint16_t>(o.amplitude * 4095.0f + 0.5f))) {
        ++bad_ticks;
      }
      if (cycle.stroking[k] && o.present) {
        const double e = std::hypot(static_cast<double>(o.position.x) - static_cast<double>(cycle.truth_x[k]),
                                    static_cast<double>(o.position.y) - static_cast<double>(cycle.truth_y[k]));
        s.max_error = std::max(s.max_error, e);
        s.sum_error += e;
        ++s.n;
      }
      if (k + 1 == cycle.rest_end_tick) {
        s.rest_error = o.present ? std::hypot(static_cast<double>(o.position.x) - static_cast<double>(cycle.rest_point.x),
                                              static_cast<double>(o.position.y) - static_cast<double>(cycle.rest_point.y))
                                 : 1e9;
      }
    }
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  LongRunResult r;
  r.seconds = cycles * kCycleUs / 1000000;
  r.ticks = ticks;
  r.cycles = cycles;
  r.lifts = lifts;
  r.bad_ticks = bad_ticks;
  r.wall_seconds = wall;
  r.first_max_error = stats.front().max_error;
  r.first_mean_error = stats.front().sum_error / static_cast<double>(stats.front().n);
  for (const CycleStats& s : stats) {
    r.worst_rest_offset = std::max(r.worst_rest_offset, s.rest_error);
    r.worst_max_error = std::max(r.worst_max_error, s.max_error);
    r.worst_mean_error = std::max(r.worst_mean_error, s.sum_error / static_cast<double>(s.n));
    r.max_error_per_cycle.push_back(s.max_error);
    r.rest_offset_per_cycle.push_back(s.rest_error);
  }
  r.pipeline_ticks = pipeline->ticks();
  r.faults = pipeline->faults();
  return r;
}

}  // namespace ff::stress
