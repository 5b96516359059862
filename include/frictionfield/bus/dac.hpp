#pragma once
// A 12-bit DAC output (the Teensy's DAC0 driving the AD9834's FSADJUST).
// Written from the 2 kHz tick: virtual, one indirect call per tick.
#include <cstdint>

#include "frictionfield/bus/bus_status.hpp"

namespace ff {

class Dac12 {
 public:
  static constexpr uint16_t kMaxCode = 4095;

  BusStatus write(uint16_t code) {
    if (code > kMaxCode) return BusStatus::InvalidArgument;
    return do_write(code);
  }

 protected:
  ~Dac12() = default;

 private:
  virtual BusStatus do_write(uint16_t code) = 0;
};

}  // namespace ff
