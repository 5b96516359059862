#pragma once
// The four load cells under the plate fixtures (docs/spec.md#load-cells): every
// 30 ms the four ADC readings are summed, converted with
//   load_mN = 1.0712 * load * 9.81      (load: summed counts above the zero)
// and averaged over the last 5 readings. The zero is the mean of the first 5
// readings after start (tare; restarted if a finger is present meanwhile),
// and is re-taken while no finger is present (the thesis saw the zero drift
// with temperature): once the last 5 readings were all taken without a
// finger and agree (highest minus lowest within rezero_limit_mN), the zero
// snaps to their mean, provided that mean is within rezero_limit_mN of the
// tare. Further from the tare is something resting on the plate, not drift,
// however slowly it came: refused (counted) and left visible. Over-force:
// the average above 0.5 N.
#include <cstdint>

#include "frictionfield/bus/adc.hpp"

namespace ff {

struct LoadCellConfig {
  uint8_t channels[4] = {0, 1, 2, 3};
  uint32_t period_us = 30000;
  float millinewton_per_count = 1.0712f * 9.81f;
  float over_force_mN = 500.0f;
  float rezero_limit_mN = 100.0f;
};

constexpr int kLoadAverageLength = 5;

struct LoadReading {
  uint32_t t_us = 0;
  float force_mN = 0.0f;    // moving average of the last 5, zero removed; 0 until tared
  float latest_mN = 0.0f;   // this reading alone
  bool tared = false;
  bool over_force = false;  // force_mN > over_force_mN
  bool rezeroed = false;    // the zero was re-taken at this reading
};

class LoadCellMonitor {
 public:
  LoadCellMonitor(Adc& adc, const LoadCellConfig& config = LoadCellConfig());

  // Starts the tare; the first reading falls one period later.
  void start(uint32_t now_us);
  // Main loop: takes a reading when a period has passed and returns true with
  // `out` filled. `finger_present` comes from the touch sensor.
  bool step(uint32_t now_us, bool finger_present, LoadReading& out);

  bool tared() const { return tared_; }
  float zero_counts() const { return zero_counts_; }
  uint32_t read_errors() const { return read_errors_; }
  uint32_t rezeros() const { return rezeros_; }
  uint32_t rezeros_refused() const { return rezeros_refused_; }
  uint32_t missed_periods() const { return missed_periods_; }

 private:
  bool read_sum(uint32_t& sum);

  Adc& adc_;
  LoadCellConfig config_;
  uint32_t next_us_ = 0;
  bool started_ = false;
  bool tared_ = false;
  float zero_counts_ = 0.0f;
  float tare_counts_ = 0.0f;  // the zero taken at start(): re-zeroes stay within the limit of it
  uint32_t window_[kLoadAverageLength] = {};  // raw sums, newest at head_ - 1
  bool window_free_[kLoadAverageLength] = {};  // taken without a finger
  int head_ = 0;
  int filled_ = 0;
  uint32_t read_errors_ = 0;
  uint32_t rezeros_ = 0;
  uint32_t rezeros_refused_ = 0;
  uint32_t missed_periods_ = 0;
};

}  // namespace ff
