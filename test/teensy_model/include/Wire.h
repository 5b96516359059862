#pragma once
// Wire library (WireKinetis.h): the master calls the binding makes.
#include <cstddef>
#include <cstdint>

class TwoWire {
 public:
  void begin();
  void setClock(uint32_t frequency);
  void beginTransmission(uint8_t address);
  size_t write(const uint8_t* data, size_t quantity);
  uint8_t endTransmission(uint8_t send_stop);
  uint8_t requestFrom(uint8_t address, uint8_t quantity);
  int read();
};
extern TwoWire Wire;
