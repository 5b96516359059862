#include "stress_traces.hpp"

#include <algorithm>
#include <cmath>

namespace ff::stress {

namespace {
uint64_t micros(double seconds) { return static_cast<uint64_t>(std::llround(seconds * 1e6)); }
}  // namespace

Motion random_motion(Rng& rng, uint64_t start_us, double seconds, bool lifts) {
  Motion m(start_us, {rng.uniform(20.0, 780.0), rng.uniform(20.0, 460.0)});
  const uint64_t until = start_us + micros(seconds);
  while (m.end() < until) {
    const double r = rng.uniform();
    if (r < 0.65) {
      const reference::DVec to{rng.uniform(5.0, 794.0), rng.uniform(5.0, 474.0)};
      const double dist = std::hypot(to.x - m.current().x, to.y - m.current().y);
      const double speed = rng.log_uniform(50.0, 1500.0);  // mean speed of the stroke
      m.stroke(to, std::max(0.05, dist / speed));
    } else if (r < 0.9 || !lifts) {
      m.rest(rng.uniform(0.02, 0.6));
    } else {
      m.lift(rng.uniform(0.01, 0.5));
    }
  }
  return m;
}

SensorStyle random_sensor(Rng& rng) {
  SensorStyle s;
  s.period_us = rng.uniform(4000.0, 6000.0);
  s.jitter_us = rng.uniform(0.0, 400.0);
  s.noise_px = rng.chance(0.2) ? 0.0 : rng.uniform(0.0, 2.5);
  s.quantum_px = rng.chance(0.5) ? 0.0 : (rng.chance(0.5) ? 0.5 : 1.0);
  s.repeat_lift_reports = rng.chance(0.5);
  return s;
}

std::vector<Report> sense(const Motion& m, const SensorStyle& style, Rng& rng) {
  std::vector<Report> out;
  bool was_touching = false;
  uint64_t last_at = 0;
  for (double k = 0.0;; k += 1.0) {
    const double jitter = style.jitter_us > 0.0 ? rng.uniform(-style.jitter_us, style.jitter_us) : 0.0;
    const double offset = std::max(0.0, k * style.period_us + jitter);
    uint64_t at = m.start() + static_cast<uint64_t>(std::llround(offset));
    if (at <= last_at && !out.empty()) at = last_at + 1;  // the sensor's own stamps increase
    if (at > m.end()) break;
    last_at = at;
    Report r;
    r.at = at;
    r.s.t_us = static_cast<uint32_t>(at);
    r.s.touch = m.touching(at);
    if (r.s.touch) {
      reference::DVec p = m.position(at);
      p.x += style.noise_px * rng.gaussian();
      p.y += style.noise_px * rng.gaussian();
      if (style.quantum_px > 0.0) {
        p.x = std::round(p.x / style.quantum_px) * style.quantum_px;
        p.y = std::round(p.y / style.quantum_px) * style.quantum_px;
      }
      r.s.x = static_cast<float>(p.x);
      r.s.y = static_cast<float>(p.y);
    } else if (!was_touching && !style.repeat_lift_reports) {
      continue;  // one touch = 0 report per lift
    }
    was_touching = r.s.touch;
    out.push_back(r);
  }
  return out;
}

std::vector<TickTime> regular_ticks(uint64_t start, uint64_t end) {
  std::vector<TickTime> t;
  t.reserve((end - start) / 500 + 1);
  for (uint64_t at = start; at <= end; at += 500) t.push_back({at, static_cast<uint32_t>(at)});
  return t;
}

void insert_report(std::vector<Report>& reports, const Report& r) {
  auto it = std::upper_bound(reports.begin(), reports.end(), r.at,
                             [](uint64_t v, const Report& x) { return v < x.at; });
  reports.insert(it, r);
}

}  // namespace ff::stress
