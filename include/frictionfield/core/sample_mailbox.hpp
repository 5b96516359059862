#pragma once
// Single-producer single-consumer ring of sensor samples: the main loop (or
// the replay) posts, the 2 kHz tick takes. Lock-free, no allocation.
#include <atomic>
#include <cstdint>

#include "frictionfield/core/sensor_sample.hpp"

namespace ff {

class SampleMailbox {
 public:
  static constexpr uint32_t kCapacity = 8;  // power of two

  bool post(const SensorSample& s) {
    const uint32_t head = head_.load(std::memory_order_relaxed);
    const uint32_t tail = tail_.load(std::memory_order_acquire);
    if (head - tail >= kCapacity) return false;
    slots_[head & (kCapacity - 1)] = s;
    head_.store(head + 1, std::memory_order_release);
    return true;
  }

  // Monotonic counts (they wrap at 2^32): the index the next post gets, and how many the tick took.
  uint32_t posted() const { return head_.load(std::memory_order_acquire); }
  uint32_t taken() const { return tail_.load(std::memory_order_acquire); }

  bool take(SensorSample& out) {
    const uint32_t tail = tail_.load(std::memory_order_relaxed);
    const uint32_t head = head_.load(std::memory_order_acquire);
    if (head == tail) return false;
    copy_sample(out, slots_[tail & (kCapacity - 1)]);
    tail_.store(tail + 1, std::memory_order_release);
    return true;
  }

 private:
  SensorSample slots_[kCapacity];
  std::atomic<uint32_t> head_{0};
  std::atomic<uint32_t> tail_{0};
};

}  // namespace ff
