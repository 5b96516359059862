#include "frictionfield/drivers/load_cells.hpp"

#include <cmath>

#include "frictionfield/bus/clock.hpp"

namespace ff {

LoadCellMonitor::LoadCellMonitor(Adc& adc, const LoadCellConfig& config) : adc_(adc), config_(config) {
  const LoadCellConfig defaults;
  if (config_.period_us == 0) config_.period_us = defaults.period_us;
  if (!std::isfinite(config_.millinewton_per_count)) config_.millinewton_per_count = defaults.millinewton_per_count;
  if (!std::isfinite(config_.over_force_mN)) config_.over_force_mN = defaults.over_force_mN;
  if (!(config_.rezero_limit_mN >= 0.0f)) config_.rezero_limit_mN = defaults.rezero_limit_mN;
}

void LoadCellMonitor::start(uint32_t now_us) {
  started_ = true;
  tared_ = false;
  zero_counts_ = 0.0f;
  tare_counts_ = 0.0f;
  filled_ = 0;
  next_us_ = now_us + config_.period_us;
}

bool LoadCellMonitor::read_sum(uint32_t& sum) {
  sum = 0;
  for (uint8_t channel : config_.channels) {
    uint16_t v = 0;
    if (adc_.read(channel, v) != BusStatus::Ok) {
      if (read_errors_ != UINT32_MAX) ++read_errors_;
      return false;
    }
    sum += v;
  }
  return true;
}

bool LoadCellMonitor::step(uint32_t now_us, bool finger_present, LoadReading& out) {
  if (!started_ || !deadline_reached(now_us, next_us_)) return false;
  next_us_ += config_.period_us;  // keep the 30 ms cadence (the thesis subtracts 30 ms)
  if (deadline_reached(now_us, next_us_)) {  // more than a period late: skip, do not burst
    ++missed_periods_;
    next_us_ = now_us + config_.period_us;
  }
  uint32_t sum;
  if (!read_sum(sum)) return false;  // counted; the previous reading stands

  out = LoadReading{};
  out.t_us = now_us;
  if (!tared_ && finger_present) {  // a finger during the tare: start it again
    filled_ = 0;
    return true;
  }
  window_[head_] = sum;
  window_free_[head_] = !finger_present;
  head_ = (head_ + 1) % kLoadAverageLength;
  if (filled_ < kLoadAverageLength) ++filled_;

  float mean = 0.0f;
  uint32_t lowest = UINT32_MAX, highest = 0;
  for (int i = 0; i < filled_; ++i) {
    const uint32_t v = window_[(head_ - 1 - i + kLoadAverageLength) % kLoadAverageLength];
    mean += static_cast<float>(v);
    if (v < lowest) lowest = v;
    if (v > highest) highest = v;
  }
  mean /= static_cast<float>(filled_);

  if (!tared_) {
    if (filled_ < kLoadAverageLength) return true;  // tare still collecting
    zero_counts_ = mean;
    tare_counts_ = mean;
    tared_ = true;
    filled_ = 0;  // the average starts afresh from the zero
    out.tared = true;
    return true;
  }

  bool all_free = filled_ == kLoadAverageLength;
  for (int i = 0; i < kLoadAverageLength; ++i) all_free = all_free && window_free_[i];
  if (all_free && mean != zero_counts_) {
    // Measured from the tare, not from the last zero: a load that arrives a
    // little at a time would otherwise be followed step by step and zeroed away.
    const float drift_mN = (mean - tare_counts_) * config_.millinewton_per_count;
    const float spread_mN = static_cast<float>(highest - lowest) * config_.millinewton_per_count;
    if (std::fabs(drift_mN) > config_.rezero_limit_mN) {
      ++rezeros_refused_;
    } else if (spread_mN <= config_.rezero_limit_mN) {  // the readings agree: the plate is at rest
      zero_counts_ = mean;
      ++rezeros_;
      out.rezeroed = true;
    }
  }

  out.tared = true;
  out.latest_mN = (static_cast<float>(sum) - zero_counts_) * config_.millinewton_per_count;
  out.force_mN = (mean - zero_counts_) * config_.millinewton_per_count;
  out.over_force = out.force_mN > config_.over_force_mN;
  return true;
}

}  // namespace ff
