#pragma once
// A microsecond clock the test moves by hand (wraps like micros()).
#include <cstdint>

#include "frictionfield/bus/clock.hpp"

namespace ff::emulated {

class ManualClock final : public MonotonicClock {
 public:
  explicit ManualClock(uint32_t start_us = 0) : now_(start_us) {}
  uint32_t now_us() const override { return now_; }
  void set(uint32_t t_us) { now_ = t_us; }
  void advance(uint32_t dt_us) { now_ += dt_us; }

 private:
  uint32_t now_;
};

}  // namespace ff::emulated
