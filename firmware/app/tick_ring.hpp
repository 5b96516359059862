#pragma once
// Single-producer (tick) single-consumer (loop) ring of rendered ticks for
// streaming to the host (ffctl record). Full: the record is dropped and counted.
#include <atomic>
#include <cstdint>

#include "frictionfield/protocol/messages.hpp"

namespace ff::firmware {

class TickRing {
 public:
  static constexpr uint32_t kCapacity = 256;  // 128 ms of ticks: the loop drains every few ms

  bool push(const protocol::TickRecord& r) {
    const uint32_t head = head_.load(std::memory_order_relaxed);
    if (head - tail_.load(std::memory_order_acquire) >= kCapacity) return false;
    slots_[head % kCapacity] = r;
    head_.store(head + 1, std::memory_order_release);
    return true;
  }
  bool pop(protocol::TickRecord& r) {
    const uint32_t tail = tail_.load(std::memory_order_relaxed);
    if (tail == head_.load(std::memory_order_acquire)) return false;
    r = slots_[tail % kCapacity];
    tail_.store(tail + 1, std::memory_order_release);
    return true;
  }
  uint32_t size() const { return head_.load(std::memory_order_acquire) - tail_.load(std::memory_order_acquire); }

 private:
  protocol::TickRecord slots_[kCapacity];
  std::atomic<uint32_t> head_{0};
  std::atomic<uint32_t> tail_{0};
};

}  // namespace ff::firmware
