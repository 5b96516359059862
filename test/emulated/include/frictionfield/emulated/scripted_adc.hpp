#pragma once
// An ADC whose every conversion is scripted per channel: a list of values
// read in turn (the last one repeats). Failures are injected as in every
// test double here: fail_next(count, status).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "frictionfield/bus/adc.hpp"

namespace ff::emulated {

class ScriptedAdc final : public Adc {
 public:
  explicit ScriptedAdc(uint8_t channels = 4, uint8_t bits = 13) : bits_(bits), scripts_(channels), next_(channels, 0) {}

  void set(uint8_t channel, uint16_t value) { script(channel, {value}); }
  void script(uint8_t channel, std::vector<uint16_t> values) {
    scripts_.at(channel) = std::move(values);
    next_.at(channel) = 0;
  }
  // The next `count` reads (any channel) fail with `status`.
  void fail_next(uint32_t count, BusStatus status = BusStatus::BusError) {
    fail_count_ = count;
    fail_status_ = status;
  }
  uint32_t reads() const { return reads_; }

  uint8_t channel_count() const override { return static_cast<uint8_t>(scripts_.size()); }
  uint8_t resolution_bits() const override { return bits_; }

 private:
  BusStatus do_read(uint8_t channel, uint16_t& value) override;

  uint8_t bits_;
  std::vector<std::vector<uint16_t>> scripts_;
  std::vector<size_t> next_;
  uint32_t fail_count_ = 0;
  BusStatus fail_status_ = BusStatus::Ok;
  uint32_t reads_ = 0;
};

}  // namespace ff::emulated
