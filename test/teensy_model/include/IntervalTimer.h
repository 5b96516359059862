#pragma once
// teensy3/IntervalTimer.h: a PIT channel calling `function` every `microseconds`, at `priority` (lower = more urgent).
#include <cstdint>

class IntervalTimer {
 public:
  bool begin(void (*function)(), uint32_t microseconds);
  void priority(uint8_t n);
  void end();
};
