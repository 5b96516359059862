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

// Member by member: a plain assignment copies 13 bytes, which GCC for the
// Cortex-M4 (-mno-unaligned-access) turns into a call of memcpy in flash.
inline void copy_sample(SensorSample& to, const SensorSample& from) {
  to.t_us = from.t_us;
  to.x = from.x;
  to.y = from.y;
  to.touch = from.touch;
}

}  // namespace ff
