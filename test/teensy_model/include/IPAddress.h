#pragma once
// teensy3/IPAddress.h, the parts the binding uses: four octets, first octet lowest in the uint32_t.
#include <cstdint>

class IPAddress {
 public:
  IPAddress() = default;
  IPAddress(uint8_t a, uint8_t b, uint8_t c, uint8_t d) : bytes_{a, b, c, d} {}
  IPAddress(uint32_t address) {  // NOLINT: as Teensyduino's
    for (int i = 0; i < 4; ++i) bytes_[i] = static_cast<uint8_t>(address >> (8 * i));
  }
  operator uint32_t() const {  // NOLINT: as Teensyduino's
    return static_cast<uint32_t>(bytes_[0]) | static_cast<uint32_t>(bytes_[1]) << 8 |
           static_cast<uint32_t>(bytes_[2]) << 16 | static_cast<uint32_t>(bytes_[3]) << 24;
  }
  uint8_t operator[](int i) const { return bytes_[i]; }

 private:
  uint8_t bytes_[4] = {0, 0, 0, 0};
};
