#pragma once
// The chatter at rest, split at every stop: the first kStopTransientUs of
// each rest, while the direction filter still reads the stroke's
// deceleration (up to ~70 ms with a wandering sensor), and the steady rest
// after it; and how long after each stop
// the rendered amplitude is back at rest (within kSettledBand of 0.5 for
// kSettledHoldUs). A goal on the chatter alone does not tell the two apart.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace ff::bench {

constexpr uint64_t kStopTransientUs = 100000;
constexpr double kSettledBand = 0.05;      // |A - 0.5| on the raw 0..1 scale
constexpr uint64_t kSettledHoldUs = 50000;

class RestChatter {
 public:
  // One tracked tick, in time order, of a resting finger: its amplitude's
  // deviation from 0.5.
  void resting(uint64_t t_us, double deviation);
  // Any other tick (moving, lifted, untracked; or the trace's end): a rest ends.
  void not_resting();

  size_t ticks() const { return ticks_; }
  double rms() const;           // over every resting tick
  double steady_rms() const;    // over those kStopTransientUs or more into their rest
  double transient_share() const;  // of the squared deviation, in the first kStopTransientUs
  size_t stops() const { return settle_us_.size() + unsettled_; }
  size_t unsettled() const { return unsettled_; }  // rests that ended before settling
  // Time from each settled rest's first tick to the first tick of a stretch
  // of kSettledHoldUs (or up to the rest's end) within kSettledBand.
  double settle_median_ms() const;
  double settle_max_ms() const;

 private:
  size_t ticks_ = 0, steady_ticks_ = 0, unsettled_ = 0;
  double sum_squared_ = 0.0, steady_sum_squared_ = 0.0;
  bool in_rest_ = false, settled_ = false, in_band_ = false;
  uint64_t rest_start_us_ = 0, band_since_us_ = 0;
  std::vector<uint64_t> settle_us_;
};

}  // namespace ff::bench
