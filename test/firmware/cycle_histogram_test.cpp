// The tick's cycle statistics and their handover to the main loop. Expected
// values are counted by hand in the comments. The interleaving test runs a
// tick (add()) before every word the loop's read() takes, as the interrupt
// may land between any two instructions of the loop on the one-core MK66,
// and accepts only the whole state before or after that tick.
#include "firmware/app/cycle_histogram.hpp"

#include <gtest/gtest.h>

#include <initializer_list>

namespace ff::firmware {
namespace {

CycleStats read_after(std::initializer_list<uint32_t> cycles) {
  CycleHistogram h;
  for (uint32_t c : cycles) h.add(c);
  return h.read();
}

void expect_stats(const CycleStats& s, uint32_t count, uint32_t mean, uint32_t max, uint32_t p99) {
  EXPECT_EQ(s.count, count);
  EXPECT_EQ(s.mean, mean);
  EXPECT_EQ(s.max, max);
  EXPECT_EQ(s.p99, p99);
}

bool operator==(const CycleStats& a, const CycleStats& b) {
  return a.count == b.count && a.mean == b.mean && a.max == b.max && a.p99 == b.p99;
}

TEST(CycleHistogram, NothingMeasuredReadsZero) { expect_stats(CycleHistogram().read(), 0, 0, 0, 0); }

TEST(CycleHistogram, MeanMaxAndPercentileOfHandCountedTicks) {
  CycleHistogram h;
  for (int i = 0; i < 99; ++i) h.add(1000);
  h.add(5000);
  // Sum 99 * 1000 + 5000 = 104,000 over 100: mean 1040. The 99th percentile
  // is the 99th value (ceil(100 * 0.99)): 1000, in bin 7 (896..1023), upper edge 1024.
  expect_stats(h.read(), 100, 1040, 5000, 1024);
}

TEST(CycleHistogram, APercentileInTheLastBinIsTheMax) {
  // 20,000 is past the last bin's start (127 * 128 = 16,256); ceil(2 * 0.99) = 2nd value.
  expect_stats(read_after({100, 20000}), 2, 10050, 20000, 20000);
}

TEST(CycleHistogram, TheMeanSinceBootDoesNotWrapAt32Bits) {
  // 3 * (2^32 - 1) needs 34 bits; the mean is 2^32 - 1 itself.
  expect_stats(read_after({0xFFFFFFFFu, 0xFFFFFFFFu, 0xFFFFFFFFu}), 3, 0xFFFFFFFFu, 0xFFFFFFFFu, 0xFFFFFFFFu);
}

// A tick that fires before the loop's read takes word number `fire_at`.
struct TickDuringRead {
  CycleHistogram* histogram;
  uint32_t cycles;
  int fire_at;
  int words = 0;
  bool fired = false;
  static void before_word(void* self) {
    auto& t = *static_cast<TickDuringRead*>(self);
    if (t.words++ == t.fire_at) {
      t.histogram->add(t.cycles);
      t.fired = true;
    }
  }
};

// For every word the read takes, a histogram in state `before` gets one more
// tick of `cycles` right before that word; the read must give `after` whole.
// Returns how many words a read takes.
int interrupt_at_every_word(std::initializer_list<uint32_t> before, uint32_t cycles, const CycleStats& after) {
  int fire_at = 0;
  for (;; ++fire_at) {
    CycleHistogram h;
    for (uint32_t c : before) h.add(c);
    TickDuringRead tick{&h, cycles, fire_at};
    const CycleStats s = h.read(&TickDuringRead::before_word, &tick);
    if (!tick.fired) break;  // past the last word: every position was tried
    EXPECT_TRUE(s == after) << "tick before word " << fire_at << ": count " << s.count << " mean " << s.mean
                            << " max " << s.max << " p99 " << s.p99;
  }
  return fire_at;
}

TEST(CycleHistogram, ATickDuringTheReadOfTheSumGivesTheNewStateWhole) {
  // Before: 100 + 4,294,967,040 = 4,294,967,140 (< 2^32). The tick adds 2^32 - 1:
  // 8,589,934,435 = 2^32 + 4,294,967,139, so both halves of the sum change.
  // Mean 8,589,934,435 / 3 = 2,863,311,478 (remainder 1); max 2^32 - 1; the
  // 99th percentile is the 3rd value (ceil(2.97)), in the last bin: the max.
  // A torn read mixes count, halves and max (e.g. count 2 with the new sum: 4,294,967,217).
  const CycleStats after{3, 2863311478u, 0xFFFFFFFFu, 0xFFFFFFFFu};
  EXPECT_GE(interrupt_at_every_word({100, 0xFFFFFF00u}, 0xFFFFFFFFu, after), 6);
}

TEST(CycleHistogram, ATickDuringTheWalkOverTheBinsGivesTheNewStateWhole) {
  // Before: one tick of 1000 (bin 7). The tick adds 200 (bin 1): count 2, mean 600,
  // max 1000; the 99th percentile is the 2nd value (ceil(1.98)): bin 7, edge 1024.
  // A read that took count 1 and then saw bin 1 filled would stop there: 256.
  const CycleStats after{2, 600, 1000, 1024};
  EXPECT_GE(interrupt_at_every_word({1000}, 200, after), 6);
}

}  // namespace
}  // namespace ff::firmware
