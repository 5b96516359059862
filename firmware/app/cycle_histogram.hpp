#pragma once
// Cycle statistics written by the tick interrupt, read by the main loop:
// count, mean and max since boot, and a 99th percentile from 128-cycle bins
// (the tick's budget is 90,000 cycles; a healthy tick costs a few thousand).
//
// Handover without tearing: add() (the tick, the only writer) makes the
// sequence odd, writes, and makes it even again; read() (the loop) takes the
// sequence, reads every word it needs, and starts again if the sequence moved.
// On the one-core Cortex-M4 the tick preempts the loop but never the other
// way round, so read() never sees an odd sequence and retries only when a
// tick landed inside it: at most once in practice (a read takes a few hundred
// cycles, ticks come every 90,000). Every word is a 32-bit atomic (a plain
// LDR/STR on the M4); the 64-bit sum is two of them, whole only under the
// sequence. Written for a preempting interrupt, it is also a correct seqlock
// for two threads.
#include <atomic>
#include <cstdint>

namespace ff::firmware {

struct CycleStats {
  uint32_t count = 0;  // measurements (wraps after 24 days of ticks)
  uint32_t mean = 0;   // since boot
  uint32_t max = 0;
  uint32_t p99 = 0;    // upper edge of the bin holding the 99th percentile; the max if that is the last bin
};

class CycleHistogram {
 public:
  static constexpr uint32_t kBinCycles = 128;
  static constexpr uint32_t kBins = 128;  // up to 16,384 cycles; above: the last bin
  static constexpr uint32_t kPercentilePermille = 990;

  void add(uint32_t cycles);  // the tick only
  CycleStats read() const { return read(nullptr, nullptr); }
  // The same, calling `between(context)` before each word it reads: a test
  // runs add() there, as a tick that interrupts the loop at that instruction.
  CycleStats read(void (*between)(void*), void* context) const;

 private:
  static void bump(std::atomic<uint32_t>& word, uint32_t by) {  // the writer's own read-modify-write
    word.store(word.load(std::memory_order_relaxed) + by, std::memory_order_relaxed);
  }

  std::atomic<uint32_t> sequence_{0};  // odd while add() writes
  std::atomic<uint32_t> count_{0};
  std::atomic<uint32_t> sum_low_{0};
  std::atomic<uint32_t> sum_high_{0};
  std::atomic<uint32_t> max_{0};
  std::atomic<uint32_t> bins_[kBins] = {};
};

}  // namespace ff::firmware
