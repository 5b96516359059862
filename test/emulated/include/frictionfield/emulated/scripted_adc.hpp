#pragma once
// An ADC whose every conversion is scripted per channel: a list of values
// read in turn (the last one repeats), and failures on chosen reads.
#include <cstddef>
#include <cstdint>
#include <set>
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
  // The read with this 0-based index (over all channels) fails with BusError.
  void fail_read(uint32_t index) { failing_.insert(index); }
  uint32_t reads() const { return reads_; }

  uint8_t channel_count() const override { return static_cast<uint8_t>(scripts_.size()); }
  uint8_t resolution_bits() const override { return bits_; }

 private:
  BusStatus do_read(uint8_t channel, uint16_t& value) override;

  uint8_t bits_;
  std::vector<std::vector<uint16_t>> scripts_;
  std::vector<size_t> next_;
  std::set<uint32_t> failing_;
  uint32_t reads_ = 0;
};

}  // namespace ff::emulated
