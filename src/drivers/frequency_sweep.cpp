#include "frictionfield/drivers/frequency_sweep.hpp"

#include "frictionfield/bus/clock.hpp"

namespace ff {

bool FrequencySweep::begin(const SweepConfig& config, uint32_t now_us) {
  running_ = false;
  const uint64_t nyquist2 = dds_.mclk_hz();
  if (config.duration_us == 0 || config.step_interval_us == 0 || 2u * uint64_t{config.start_hz} > nyquist2 ||
      2u * uint64_t{config.stop_hz} > nyquist2) {
    return false;
  }
  config_ = config;
  start_word_ = ad9834::frequency_word(config.start_hz, dds_.mclk_hz());
  stop_word_ = ad9834::frequency_word(config.stop_hz, dds_.mclk_hz());
  begin_us_ = now_us;
  next_us_ = now_us + config.step_interval_us;
  steps_ = 0;
  if (play(start_word_) != BusStatus::Ok) return false;
  steps_ = 1;
  running_ = true;
  return true;
}

uint32_t FrequencySweep::word_at(uint32_t elapsed_us) const {
  if (elapsed_us >= config_.duration_us) return stop_word_;
  const int64_t span = static_cast<int64_t>(stop_word_) - static_cast<int64_t>(start_word_);  // |span| < 2^28
  return static_cast<uint32_t>(static_cast<int64_t>(start_word_) +
                               span * static_cast<int64_t>(elapsed_us) / static_cast<int64_t>(config_.duration_us));
}

bool FrequencySweep::step(uint32_t now_us, SweepStep& out) {
  if (!running_ || !deadline_reached(now_us, next_us_)) return false;
  uint32_t elapsed = elapsed_since(now_us, begin_us_);
  if (elapsed > config_.duration_us) elapsed = config_.duration_us;
  const uint32_t word = word_at(elapsed);
  if (play(word) != BusStatus::Ok) return false;  // counted by the driver; retried next interval
  ++steps_;
  next_us_ += config_.step_interval_us;
  if (deadline_reached(now_us, next_us_)) next_us_ = now_us + config_.step_interval_us;  // fell behind: no burst
  if (elapsed >= config_.duration_us) running_ = false;
  out.elapsed_us = elapsed;
  out.word = word;
  out.millihz = ad9834::output_millihz(word, dds_.mclk_hz());
  return true;
}

BusStatus FrequencySweep::play(uint32_t word) {
  const uint8_t idle = static_cast<uint8_t>(1u - dds_.selected_frequency());
  const BusStatus s = dds_.set_frequency_word(idle, word);
  if (s != BusStatus::Ok) return s;
  return dds_.select(idle, dds_.selected_phase());
}

}  // namespace ff
