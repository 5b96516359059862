#pragma once
// A linear frequency chirp on the AD9834, stepped from the main loop: the
// thesis found the plate's resonances with a 25-70 kHz chirp over 30 s. Each
// step writes the new word into the register that is not playing and then
// switches FSEL, so the output never plays a half-written word and stays
// phase-continuous. Integer arithmetic only.
#include <cstdint>

#include "frictionfield/drivers/ad9834.hpp"

namespace ff {

struct SweepConfig {
  uint32_t start_hz = 25000;
  uint32_t stop_hz = 70000;          // may be below start_hz (downward sweep)
  uint32_t duration_us = 30000000;   // 30 s
  uint32_t step_interval_us = 1000;  // at most one register update per interval
};

struct SweepStep {
  uint32_t elapsed_us = 0;  // since begin(), clamped to the duration
  uint32_t word = 0;        // now playing
  uint64_t millihz = 0;     // its frequency
};

class FrequencySweep {
 public:
  explicit FrequencySweep(Ad9834& dds) : dds_(dds) {}

  // Starts at start_hz. False (nothing written) if the configuration is
  // unusable: zero duration or interval, a frequency above MCLK / 2.
  bool begin(const SweepConfig& config, uint32_t now_us);
  // Main loop. Returns true when it wrote a new frequency (then `out` says
  // which); the last step lands exactly on stop_hz and ends the sweep.
  bool step(uint32_t now_us, SweepStep& out);
  void stop() { running_ = false; }

  bool running() const { return running_; }
  uint32_t steps_written() const { return steps_; }
  uint32_t word_at(uint32_t elapsed_us) const;

 private:
  BusStatus play(uint32_t word);

  Ad9834& dds_;
  SweepConfig config_;
  uint32_t start_word_ = 0;
  uint32_t stop_word_ = 0;
  uint32_t begin_us_ = 0;
  uint32_t next_us_ = 0;
  uint32_t steps_ = 0;
  bool running_ = false;
};

}  // namespace ff
