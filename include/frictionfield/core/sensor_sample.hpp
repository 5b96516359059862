#pragma once
#include <cstdint>

namespace ff {

// One finger report from the touch sensor, in screen pixels.
// t_us is the 32-bit microsecond clock (micros()): it wraps every 71.6 min,
// so only differences of nearby timestamps are meaningful.
struct SensorSample {
  uint32_t t_us = 0;
  float x = 0.0f;
  float y = 0.0f;
  bool touch = false;  // false: no finger (x, y ignored)
};

}  // namespace ff
