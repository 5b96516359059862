#pragma once
// A data-ready input line (the zForce's DR pin): its level, and the time of
// its last rising edge as latched by the interrupt. The edge time is what a
// sensor sample is stamped with: the moment the sensor had the data, not the
// moment the main loop got round to reading it.
#include <atomic>
#include <cstdint>

namespace ff {

class DataReadyInput {
 public:
  // True while the device has data waiting.
  virtual bool asserted() const = 0;
  // The newest rising edge not taken yet: its time and how many edges there
  // were since the last take (more than one: an edge was overwritten).
  // Returns false if there was none.
  virtual bool take_edge(uint32_t& t_us, uint32_t& edges) = 0;

 protected:
  ~DataReadyInput() = default;
};

// The interrupt-to-main-loop latch behind a real DR pin: the ISR calls
// on_edge(micros()), the main loop calls take(). Lock-free, one writer (the
// ISR) and one reader; the reader retries if an edge lands mid-read.
class EdgeLatch {
 public:
  void on_edge(uint32_t t_us) {
    time_.store(t_us, std::memory_order_relaxed);
    count_.fetch_add(1, std::memory_order_release);
  }

  bool take(uint32_t& t_us, uint32_t& edges) {
    for (int attempt = 0; attempt < 3; ++attempt) {
      const uint32_t before = count_.load(std::memory_order_acquire);
      const uint32_t t = time_.load(std::memory_order_relaxed);
      if (count_.load(std::memory_order_acquire) != before) continue;  // an edge landed meanwhile
      if (before == taken_) return false;
      edges = before - taken_;
      taken_ = before;
      t_us = t;
      return true;
    }
    return false;  // edges arriving faster than we read: try again next loop
  }

 private:
  std::atomic<uint32_t> time_{0};
  std::atomic<uint32_t> count_{0};
  uint32_t taken_ = 0;  // reader side only
};

}  // namespace ff
