// The replay's timing is docs/spec.md#tick-timing's: ticks at t0 + k * 500 us, samples at or
// before a tick delivered before it.
#include "frictionfield/host/replay.hpp"

#include <gtest/gtest.h>

#include <memory>

#include "frictionfield/core/scenes.hpp"

namespace ff::host {
namespace {

TEST(Replay, TicksFromTheFirstSampleAndDeliversSamplesOnTime) {
  auto p = std::make_unique<HapticPipeline>();
  Condition c;
  c.scene = scenes::neutral();
  ASSERT_EQ(p->set_condition(c), PrepareStatus::Ok);
  // Samples at 1000, 1600 (between ticks 1500 and 2000) and 2000 (exactly on a tick).
  const std::vector<TraceRow> rows = {{1000, 10, 10, true}, {1600, 20, 10, true}, {2000, 30, 10, true}};
  std::vector<std::pair<uint64_t, float>> seen;
  const ReplaySummary s = replay(rows, *p, [&](uint64_t t, const TickOutput& o) { seen.push_back({t, o.position.x}); });
  ASSERT_EQ(seen.size(), 3u);
  EXPECT_EQ(seen[0], (std::pair<uint64_t, float>{1000, 10.0f}));
  EXPECT_EQ(seen[1], (std::pair<uint64_t, float>{1500, 10.0f}));  // 1600 is not due yet
  EXPECT_EQ(seen[2], (std::pair<uint64_t, float>{2000, 30.0f}));  // both 1600 and 2000 are
  EXPECT_EQ(s.samples, 3u);
  EXPECT_EQ(s.ticks, 3u);
  EXPECT_FLOAT_EQ(s.amplitude_max, 0.5f);
}

TEST(Replay, ExtraTicksLetLiftOffPlayOut) {
  auto p = std::make_unique<HapticPipeline>();
  const std::vector<TraceRow> rows = {{0, 10, 10, true}, {5000, 10, 10, true}, {10000, 0, 0, false}};
  TickOutput last;
  replay(rows, *p, [&](uint64_t, const TickOutput& o) { last = o; }, 100);
  EXPECT_FALSE(last.present);
  EXPECT_EQ(last.dac, 0);
}

}  // namespace
}  // namespace ff::host
