#pragma once
// SPI initiator that shifts 16-bit words, MSB first, with the clock mode and
// chip select given per transfer (several devices may share the bus).
// Virtual for the reasons given in i2c.hpp.
#include <cstddef>
#include <cstdint>

#include "frictionfield/bus/bus_status.hpp"

namespace ff {

// CPOL = clock idle level, CPHA = sampling edge (0: first edge, 1: second).
enum class SpiMode : uint8_t { Mode0 = 0, Mode1 = 1, Mode2 = 2, Mode3 = 3 };
constexpr bool spi_cpol(SpiMode m) { return (static_cast<uint8_t>(m) & 2u) != 0; }
constexpr bool spi_cpha(SpiMode m) { return (static_cast<uint8_t>(m) & 1u) != 0; }

struct SpiConfig {
  SpiMode mode = SpiMode::Mode0;
  uint32_t max_clock_hz = 1000000;
};

class SpiBus16 {
 public:
  // Asserts `chip_select`, shifts out `count` words (each MSB first) and
  // releases chip select after the last word. count >= 1.
  BusStatus write(const SpiConfig& config, uint8_t chip_select, const uint16_t* words, size_t count) {
    if (words == nullptr || count == 0 || config.max_clock_hz == 0) return BusStatus::InvalidArgument;
    return do_write(config, chip_select, words, count);
  }

 protected:
  ~SpiBus16() = default;

 private:
  virtual BusStatus do_write(const SpiConfig& config, uint8_t chip_select, const uint16_t* words,
                             size_t count) = 0;
};

}  // namespace ff
