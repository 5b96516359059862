#pragma once
// Finger motion, sensor reports and tick times for the stress suite. Time is
// kept in 64-bit microseconds ("real time"); what the device sees is the
// 32-bit stamp, so a trace that starts near 2^32 wraps mid-stroke.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "frictionfield/core/sensor_sample.hpp"
#include "support/reference/reference_amplitude.hpp"
#include "support/reference/reference_scene.hpp"
#include "support/reference/reference_tracker.hpp"
#include "stress_random.hpp"
#include "support/models/motion.hpp"

namespace ff::stress {

// A sensor report delivered at real time `at`; s.t_us is its (maybe wrong) stamp.
struct Report {
  uint64_t at = 0;
  SensorSample s;
};

// A tick at real time `at` told that the time is `now`.
struct TickTime {
  uint64_t at = 0;
  uint32_t now = 0;
};

// The finger: strokes (minimum jerk), rests and lifts, back to back, on a
// 64-bit microsecond timeline starting at `start_us` (test/support/models/motion).
class Motion {
 public:
  Motion(uint64_t start_us, reference::DVec p) : start_(start_us), motion_({p.x, p.y}) {}
  void stroke(reference::DVec to, double seconds) { motion_.stroke_for({to.x, to.y}, std::max(1e-6, seconds)); }
  void rest(double seconds) { motion_.hold(seconds, true); }
  void lift(double seconds) { motion_.lift(seconds, motion_.position()); }
  uint64_t start() const { return start_; }
  uint64_t end() const { return start_ + static_cast<uint64_t>(std::llround(motion_.duration_s() * 1e6)); }
  reference::DVec current() const { return {motion_.position().x, motion_.position().y}; }
  bool touching(uint64_t t) const { return state(t).touching; }
  reference::DVec position(uint64_t t) const {
    const tracegen::Point p = state(t).position;
    return {p.x, p.y};
  }

 private:
  tracegen::TrueState state(uint64_t t) const { return motion_.at(static_cast<double>(t - start_) * 1e-6); }
  uint64_t start_;
  tracegen::Motion motion_;
};

// Random strokes between random on-screen points at 50..1500 px/s, rests and
// (if allowed) lifts, for about `seconds`.
Motion random_motion(Rng& rng, uint64_t start_us, double seconds, bool lifts);

struct SensorStyle {
  double period_us = 5000.0;  // zForce ~200 Hz
  double jitter_us = 300.0;   // uniform +- this
  double noise_px = 0.5;      // Gaussian, 1 sigma
  double quantum_px = 0.0;    // 0: none
  bool repeat_lift_reports = false;  // touch = 0 every period while lifted (else once)
};
SensorStyle random_sensor(Rng& rng);

// Reports of `m` from its start to its end, stamped with the true time.
std::vector<Report> sense(const Motion& m, const SensorStyle& style, Rng& rng);

// Ticks every 500 us from `start` while at <= end.
std::vector<TickTime> regular_ticks(uint64_t start, uint64_t end);

// Inserts `r` keeping reports ordered by delivery time (after equal times).
void insert_report(std::vector<Report>& reports, const Report& r);

}  // namespace ff::stress
