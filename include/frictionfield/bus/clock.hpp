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

// Signed time from `earlier` to `later` for stamps less than 2^31 us (35 min)
// apart, across the wrap: negative when `later` is in fact earlier.
constexpr int32_t signed_elapsed(uint32_t later, uint32_t earlier) {
  return static_cast<int32_t>(later - earlier);
}

// True once `now` is at or after `deadline`, for deadlines less than 2^31 us
// (35 min) away, across the wrap.
constexpr bool deadline_reached(uint32_t now, uint32_t deadline) {
  return signed_elapsed(now, deadline) >= 0;
}

}  // namespace ff
