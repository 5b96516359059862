#include "firmware/app/cycle_histogram.hpp"

namespace ff::firmware {

uint32_t CycleHistogram::percentile_permille(uint32_t permille) const {
  const uint32_t n = count();
  if (n == 0) return 0;
  // The smallest bin whose cumulative count reaches ceil(n * p / 1000).
  const uint64_t need = (static_cast<uint64_t>(n) * permille + 999) / 1000;
  uint64_t seen = 0;
  for (uint32_t b = 0; b < kBins; ++b) {
    seen += bins_[b].load(std::memory_order_relaxed);
    if (seen >= need && need > 0) return b == kBins - 1 ? max() : (b + 1) * kBinCycles;
  }
  return max();
}

}  // namespace ff::firmware
