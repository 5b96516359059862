#include "firmware/app/cycle_histogram.hpp"

namespace ff::firmware {

void CycleHistogram::add(uint32_t cycles) {
  const uint32_t sequence = sequence_.load(std::memory_order_relaxed);
  sequence_.store(sequence + 1, std::memory_order_relaxed);
  std::atomic_thread_fence(std::memory_order_release);  // odd before any word changes
  const uint32_t bin = cycles / kBinCycles < kBins - 1 ? cycles / kBinCycles : kBins - 1;
  bump(bins_[bin], 1);
  if (cycles > max_.load(std::memory_order_relaxed)) max_.store(cycles, std::memory_order_relaxed);
  const uint32_t low = sum_low_.load(std::memory_order_relaxed);
  sum_low_.store(low + cycles, std::memory_order_relaxed);
  if (low + cycles < low) bump(sum_high_, 1);  // carry
  bump(count_, 1);
  sequence_.store(sequence + 2, std::memory_order_release);  // even after every word
}

CycleStats CycleHistogram::read(void (*between)(void*), void* context) const {
  const auto word = [&](const std::atomic<uint32_t>& w, std::memory_order order) {
    if (between != nullptr) between(context);
    return w.load(order);
  };
  for (;;) {
    const uint32_t before = word(sequence_, std::memory_order_acquire);
    if (before & 1u) continue;  // a writer on another thread is mid-add (never on the M4)
    CycleStats s;
    s.count = word(count_, std::memory_order_relaxed);
    const uint64_t sum = word(sum_low_, std::memory_order_relaxed) |
                         static_cast<uint64_t>(word(sum_high_, std::memory_order_relaxed)) << 32;
    s.max = word(max_, std::memory_order_relaxed);
    s.mean = s.count == 0 ? 0u : static_cast<uint32_t>(sum / s.count);
    if (s.count > 0) {
      // The smallest bin whose cumulative count reaches ceil(count * p / 1000).
      const uint64_t need = (static_cast<uint64_t>(s.count) * kPercentilePermille + 999) / 1000;
      uint64_t seen = 0;
      s.p99 = s.max;
      for (uint32_t b = 0; b < kBins - 1; ++b) {
        seen += word(bins_[b], std::memory_order_relaxed);
        if (seen >= need) {
          s.p99 = (b + 1) * kBinCycles;
          break;
        }
      }
    }
    std::atomic_thread_fence(std::memory_order_acquire);  // every word read before the sequence again
    if (word(sequence_, std::memory_order_relaxed) == before) return s;
  }
}

}  // namespace ff::firmware
