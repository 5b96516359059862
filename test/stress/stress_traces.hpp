#pragma once
// Finger motion, sensor reports and tick times for the stress suite. Time is
// kept in 64-bit microseconds ("real time"); what the device sees is the
// 32-bit stamp, so a trace that starts near 2^32 wraps mid-stroke.
#include <cstdint>
#include <vector>

#include "frictionfield/core/sensor_sample.hpp"
#include "reference_model.hpp"
#include "stress_random.hpp"

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

// The finger: strokes (minimum jerk), rests and lifts, back to back.
class Motion {
 public:
  Motion(uint64_t start_us, DVec p) : start_(start_us), end_(start_us), current_(p) {}
  void stroke(DVec to, double seconds);
  void rest(double seconds);
  void lift(double seconds);
  uint64_t start() const { return start_; }
  uint64_t end() const { return end_; }
  DVec current() const { return current_; }
  bool touching(uint64_t t) const;
  DVec position(uint64_t t) const;

 private:
  enum class Kind : uint8_t { Stroke, Rest, Lifted };
  struct Segment {
    uint64_t t0, t1;
    Kind kind;
    DVec from, to;
  };
  const Segment* at(uint64_t t) const;
  std::vector<Segment> segments_;
  uint64_t start_, end_;
  DVec current_;
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
