#pragma once
// The monotonic microsecond clock (micros() on the Teensy). It is 32 bits and
// wraps every 71.6 min; compare times only through the differences below.
#include <cstdint>

namespace ff {

class MonotonicClock {
 public:
  virtual uint32_t now_us() const = 0;

 protected:
  ~MonotonicClock() = default;
};

// Time from `since` to `now`, correct across one wrap.
constexpr uint32_t elapsed_since(uint32_t now, uint32_t since) { return now - since; }

// True once `now` is at or after `deadline`, for deadlines less than 2^31 us
// (35 min) away, across the wrap.
constexpr bool deadline_reached(uint32_t now, uint32_t deadline) {
  return static_cast<int32_t>(now - deadline) >= 0;
}

}  // namespace ff
