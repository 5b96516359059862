#pragma once
// A multi-channel ADC read one conversion at a time (the load-cell inputs).
#include <cstdint>

#include "frictionfield/bus/bus_status.hpp"

namespace ff {

class Adc {
 public:
  BusStatus read(uint8_t channel, uint16_t& value) {
    if (channel >= channel_count()) return BusStatus::InvalidArgument;
    return do_read(channel, value);
  }
  virtual uint8_t channel_count() const = 0;
  virtual uint8_t resolution_bits() const = 0;

 protected:
  ~Adc() = default;

 private:
  virtual BusStatus do_read(uint8_t channel, uint16_t& value) = 0;
};

}  // namespace ff
