#pragma once
// The replay shared by the observers that bound the heightmap error from
// below (direction_bound.hpp, heading_bound.hpp): each report read at the
// time the sensor scanned it, with the truth there, and the amplitude the
// observer renders at every moving tick, against the ideal renderer's, and at
// every resting tick, against 0.5.
#include <cmath>
#include <vector>

#include "tracking_evaluation.hpp"

namespace ff::bench {

// `make(c)` builds one observer per case, with
//   void report(const tracegen::TraceSample& s, const tracegen::TrueState& truth, uint64_t scanned_us,
//               double scan_s, bool touch_down);
//   double amplitude(const ScenePlan& heightmap, const TickTruth& tick) const;
// called for every valid touching report scanned by a tick (in order; touch_down
// at the first of each touch), and at the moving and the resting ticks of a touch.
struct ObserverErrors {
  double heightmap_rms = 0.0;  // A - A_ideal over the moving ticks (as Metrics::heightmap_rms counts them,
                               // from the first report of each touch)
  double rest_rms = 0.0;       // A - 0.5 over the resting ticks (Metrics::heightmap_rest_rms)
};
template <class Make>
ObserverErrors observer_errors(const std::vector<PreparedCase>& cases, double moving_speed_px_s, Make make) {
  double sum = 0.0, rest_sum = 0.0;
  size_t moving = 0, resting = 0;
  for (const PreparedCase& c : cases) {
    auto observer = make(c);
    const std::vector<tracegen::TraceSample>& samples = c.trace.samples;
    size_t next = 0;
    bool touching = false;
    for (const TickTruth& tick : c.ticks) {
      for (; next < samples.size(); ++next) {  // every report scanned by this tick
        const tracegen::TraceSample& s = samples[next];
        const double scan_us = static_cast<double>(s.t_us) - s.latency_us;
        if (scan_us > static_cast<double>(tick.t_us)) break;
        if (!s.touch || !std::isfinite(s.x) || !std::isfinite(s.y)) {
          touching = touching && s.touch;
          continue;
        }
        const uint64_t scanned = static_cast<uint64_t>(std::llround(scan_us));
        observer.report(s, c.trace.truth_at(scanned), scanned, scan_us * 1e-6, !touching);
        touching = true;
      }
      if (!touching) continue;
      if (tick.state.resting) {
        const double r = observer.amplitude(*c.heightmap, tick) - 0.5;
        rest_sum += r * r;
        ++resting;
      }
      if (!judged_moving(tick.state, moving_speed_px_s)) continue;
      const double e = observer.amplitude(*c.heightmap, tick) - static_cast<double>(tick.heightmap_ideal);
      sum += e * e;
      ++moving;
    }
  }
  auto rms = [](double squares, size_t n) { return n > 0 ? std::sqrt(squares / static_cast<double>(n)) : 0.0; };
  return {rms(sum, moving), rms(rest_sum, resting)};
}

}  // namespace ff::bench
