#pragma once
// Interrupt cost statistics written by the tick, read by the main loop:
// mean, max and a 99th percentile from 128-cycle bins (the tick's budget is
// 90,000 cycles; a healthy tick costs a few thousand). Only the tick writes;
// the loop reads each word once (a percentile read mid-update is off by one
// tick, never torn: the counters are 32-bit atomics, and no 64-bit sum exists).
#include <atomic>
#include <cstdint>

namespace ff::firmware {

class CycleHistogram {
 public:
  static constexpr uint32_t kBinCycles = 128;
  static constexpr uint32_t kBins = 128;  // up to 16,384 cycles; above: the last bin

  void add(uint32_t cycles) {  // tick only
    const uint32_t bin = cycles / kBinCycles < kBins - 1 ? cycles / kBinCycles : kBins - 1;
    bins_[bin].store(bins_[bin].load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
    if (cycles > max_.load(std::memory_order_relaxed)) max_.store(cycles, std::memory_order_relaxed);
    // The mean over windows of 2^16 ticks (33 s): a 32-bit sum that cannot wrap, published whole.
    window_sum_ += cycles < 0xFFFFu ? cycles : 0xFFFFu;
    if (++window_count_ == kWindow) {
      mean_.store(window_sum_ / kWindow, std::memory_order_relaxed);
      window_sum_ = 0;
      window_count_ = 0;
    }
    count_.store(count_.load(std::memory_order_relaxed) + 1, std::memory_order_release);
  }

  uint32_t count() const { return count_.load(std::memory_order_acquire); }
  uint32_t max() const { return max_.load(std::memory_order_relaxed); }
  // Mean of the last whole window; before the first one, the mean so far (read between two ticks).
  uint32_t mean() const {
    const uint32_t m = mean_.load(std::memory_order_relaxed);
    if (m != 0 || count() >= kWindow) return m;
    const uint32_t n = window_count_;
    return n == 0 ? 0u : window_sum_ / n;
  }
  // Upper edge of the bin that holds the p-th permille (990 = 99th percentile); the max if that is the last bin.
  uint32_t percentile_permille(uint32_t permille) const;

 private:
  std::atomic<uint32_t> bins_[kBins] = {};
  std::atomic<uint32_t> max_{0};
  static constexpr uint32_t kWindow = 65536;
  std::atomic<uint32_t> mean_{0};
  std::atomic<uint32_t> count_{0};
  uint32_t window_sum_ = 0;    // tick only (the early mean() reads it between ticks)
  uint32_t window_count_ = 0;
};

}  // namespace ff::firmware
