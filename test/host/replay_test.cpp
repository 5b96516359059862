// The replay's timing is docs/spec.md#tick-timing's: ticks at t0 + k * 500 us, samples at or
// before a tick delivered before it.
#include "frictionfield/host/replay.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iterator>
#include <memory>
#include <vector>

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
  ASSERT_EQ(seen.size(), 4u);
  EXPECT_EQ(seen[0], (std::pair<uint64_t, float>{1000, 10.0f}));
  EXPECT_EQ(seen[1], (std::pair<uint64_t, float>{1500, 10.0f}));  // 1600 is not due yet
  // Both 1600 and 2000 are due; a tick takes one report, the oldest, and the
  // replay ticks on until the mailbox is empty.
  EXPECT_EQ(seen[2], (std::pair<uint64_t, float>{2000, 20.0f}));
  EXPECT_EQ(seen[3], (std::pair<uint64_t, float>{2500, 30.0f}));
  EXPECT_EQ(s.samples, 3u);
  EXPECT_EQ(s.ticks, 4u);
  EXPECT_FLOAT_EQ(s.amplitude_max, 0.5f);
}

TEST(Replay, StopsWhereTheTickTimeWouldWrapPast2To64) {
  // Rows that bypass the reader's 2^53 bound: t0 + k * 500 us wraps after one
  // tick, and the replay's end test (a tick at or after the last report)
  // never held again: it ticked on for ever (found by fuzz/trace_csv).
  auto p = std::make_unique<HapticPipeline>();
  const std::vector<TraceRow> rows = {{UINT64_MAX - 5, 100, 0, false}};
  const ReplaySummary s = replay(rows, *p, nullptr, 600);
  EXPECT_EQ(s.ticks, 1u);
}

TEST(Replay, ExtraTicksLetLiftOffPlayOut) {
  auto p = std::make_unique<HapticPipeline>();
  const std::vector<TraceRow> rows = {{0, 10, 10, true}, {5000, 10, 10, true}, {10000, 0, 0, false}};
  TickOutput last;
  replay(rows, *p, [&](uint64_t, const TickOutput& o) { last = o; }, 100);
  EXPECT_FALSE(last.present);
  EXPECT_EQ(last.dac, 0);
}

// The rows replayed as a stream, a gap over 600 s ending the replay; `read`
// counts the rows taken from the source.
ReplaySummary replay_with_gap_limit(const std::vector<TraceRow>& rows, size_t& read) {
  read = 0;
  const RowSource source = [&](TraceRow& r) { return read < rows.size() ? (r = rows[read++], true) : false; };
  auto p = std::make_unique<HapticPipeline>();
  ReplayOptions options;
  options.max_gap_us = 600'000'000;
  return replay(source, *p, nullptr, options);
}

TEST(Replay, AnImplausibleJumpEndsTheReplayAtTheLastPlausibleReport) {
  // 2 s of reports, then one stamp 2^31 us ahead: ticking through the gap
  // would write 4.3 million idle ticks.
  std::vector<TraceRow> rows;
  for (uint64_t t = 0; t <= 2000000; t += 5000) rows.push_back({t, 400, 240, true});
  rows.push_back({2000000 + (1ull << 31), 400, 240, true});
  size_t read = 0;
  const ReplaySummary s = replay_with_gap_limit(rows, read);
  EXPECT_EQ(s.ticks, 2000000u / kTickPeriodUs + 1);  // ticks 0 .. 2 s
  EXPECT_TRUE(s.time_jump);
  EXPECT_EQ(s.time_jump_from_us, 2000000u);
  EXPECT_EQ(s.rows_after_time_jump, 1u);
  EXPECT_EQ(s.samples, rows.size() - 1);
}

TEST(Replay, StreamingGivesTheSameTicksAsTheWholeTraceAcrossItsWindows) {
  // More rows than the look-ahead window, with backwards and far-ahead stamps
  // scattered through: the arrival rule must not depend on where a window ends.
  std::vector<TraceRow> rows;
  uint64_t t = 1000;
  for (int i = 0; i < 10000; ++i) {
    t += 5000;
    uint64_t stamp = t;
    if (i % 977 == 500) stamp = t + 50000;   // far ahead: arrives with the next row
    if (i % 1313 == 700) stamp = t - 12000;  // behind: the tracker drops it
    rows.push_back({stamp, 100.0f + static_cast<float>(i % 600), 240.0f, true});
  }
  auto a = std::make_unique<HapticPipeline>();
  auto b = std::make_unique<HapticPipeline>();
  std::vector<uint32_t> whole, streamed;
  replay(rows, *a, [&](uint64_t, const TickOutput& o) { whole.push_back(o.dac); }, 10);
  // Independent expectation for the tick count: t0 .. the last stamp, then 10.
  EXPECT_EQ(whole.size(), (rows.back().t_us - rows.front().t_us + kTickPeriodUs - 1) / kTickPeriodUs + 1 + 10);
  size_t next = 0;
  const RowSource source = [&](TraceRow& r) { return next < rows.size() ? (r = rows[next++], true) : false; };
  ReplayOptions options;
  options.extra_ticks = 10;
  replay(source, *b, [&](uint64_t, const TickOutput& o) { streamed.push_back(o.dac); }, options);
  EXPECT_EQ(whole, streamed);
}

// The summary worked out again from the ticks the sink saw.
ReplaySummary expect_summary_of_its_ticks(const std::vector<TraceRow>& rows, HapticPipeline& pipeline,
                                          uint64_t extra_ticks) {
  uint64_t ticks = 0, with_finger = 0;
  float lo = 1.0f, hi = 0.0f;
  double sum = 0.0;
  const ReplaySummary s = replay(
      rows, pipeline,
      [&](uint64_t, const TickOutput& o) {
        ++ticks;
        with_finger += o.present ? 1 : 0;
        lo = std::min(lo, o.amplitude);
        hi = std::max(hi, o.amplitude);
        sum += static_cast<double>(o.amplitude);
      },
      extra_ticks);
  EXPECT_GT(ticks, 0u);
  EXPECT_EQ(s.ticks, ticks);
  EXPECT_EQ(s.ticks_with_finger, with_finger);
  EXPECT_EQ(s.amplitude_min, lo);
  EXPECT_EQ(s.amplitude_max, hi);
  EXPECT_FLOAT_EQ(s.amplitude_mean, static_cast<float>(sum / static_cast<double>(ticks)));
  for (int f = 0; f < static_cast<int>(Fault::kCount); ++f)
    EXPECT_EQ(s.faults[Fault(f)], pipeline.faults()[Fault(f)]) << to_string(Fault(f));
  return s;
}

TEST(Replay, TheSummaryIsWhatItsTicksShow) {
  {
    // The finger down throughout on a flat field (0.5 at every tick: the
    // smallest amplitude is not the lowest possible one), and one report off
    // the screen, which the tracker drops and counts.
    auto p = std::make_unique<HapticPipeline>();
    Condition c;
    c.scene = scenes::neutral();
    ASSERT_EQ(p->set_condition(c), PrepareStatus::Ok);
    std::vector<TraceRow> rows;
    for (uint64_t t = 0; t <= 200000; t += 5000)
      rows.push_back({t, 100.0f + static_cast<float>(t) * 1e-3f, 240.0f, true});
    rows[10].x = 5000.0f;
    expect_summary_of_its_ticks(rows, *p, 0);
    EXPECT_EQ(p->faults()[Fault::OffScreen], 1u);
  }
  {
    // A stroke over the heightmap, then the finger lifts and ticks play out:
    // amplitudes that vary, and ticks without a finger.
    auto p = std::make_unique<HapticPipeline>();
    Condition c;
    c.scene = scenes::heightmap(Target::Top);
    ASSERT_EQ(p->set_condition(c), PrepareStatus::Ok);
    std::vector<TraceRow> rows;
    for (uint64_t t = 0; t <= 400000; t += 5000)
      rows.push_back({t, 100.0f + static_cast<float>(t) * 1.5e-3f, 200.0f, true});
    rows.push_back({405000, 0.0f, 0.0f, false});
    const ReplaySummary s = expect_summary_of_its_ticks(rows, *p, 400);
    EXPECT_LT(s.amplitude_min, s.amplitude_max);
    EXPECT_GT(s.ticks_with_finger, 0u);
    EXPECT_LT(s.ticks_with_finger, s.ticks);
  }
}

TEST(Replay, AJumpKeepsItsStampAndCountsEveryRowAfterIt) {
  // More rows after the jump than the arrival window holds: they are counted
  // from the rest of the source, not only from the window.
  std::vector<TraceRow> rows;
  for (uint64_t t = 0; t <= 100000; t += 5000) rows.push_back({t, 400, 240, true});
  const uint64_t jump_to = 100000 + 3'600'000'000ull;
  for (uint64_t i = 0; i < 10000; ++i) rows.push_back({jump_to + i * 5000, 400, 240, true});
  size_t read = 0;
  const ReplaySummary s = replay_with_gap_limit(rows, read);
  EXPECT_TRUE(s.time_jump);
  EXPECT_EQ(s.time_jump_from_us, 100000u);
  EXPECT_EQ(s.time_jump_to_us, jump_to);
  EXPECT_EQ(s.rows_after_time_jump, 10000u);
  EXPECT_EQ(s.samples, 21u);
  EXPECT_EQ(read, rows.size());  // the whole source read
}

// ff-replay's "rejected" line: the faults that drop a sample, one each, and
// no more than the samples read (the list here is fault_counters.hpp's
// comments read by hand: the kinds that say "dropped" or lose the sample).
TEST(Replay, AFirstRowStampedFarAheadDoesNotSkipTheRowsBehindIt) {
  // The first stamp is 100 s ahead (a clock glitch); the 20 reports behind it
  // span 1 ms .. 96 ms. Ticking from that stamp made every other row due at the
  // first tick, and all but 8 overflowed the mailbox: 0.1 s of output.
  std::vector<TraceRow> rows = {{100'000'000, 400, 240, true}};
  for (uint64_t t = 1000; t <= 96000; t += 5000) rows.push_back({t, 400, 240, true});
  auto p = std::make_unique<HapticPipeline>();
  const ReplaySummary s = replay(rows, *p, nullptr);
  // Ticks from the second row's arrival (1 ms), the glitch arriving with it, to 96 ms.
  EXPECT_EQ(s.ticks, (96000u - 1000u) / kTickPeriodUs + 1);
  EXPECT_EQ(s.faults[Fault::MailboxOverflow], 0u);
  EXPECT_EQ(s.samples, rows.size());
  EXPECT_EQ(s.rejected_samples(), 1u);  // the glitch alone
}

// Rows replayed as ff-replay streams them, a clock stepping back more than
// 20 ms (twice in a row) ending the replay.
ReplaySummary replay_ending_at_a_step_back(const std::vector<TraceRow>& rows) {
  size_t next = 0;
  const RowSource source = [&](TraceRow& r) { return next < rows.size() ? (r = rows[next++], true) : false; };
  auto p = std::make_unique<HapticPipeline>();
  ReplayOptions options;
  options.max_step_back_us = kClockStepBackUs;
  return replay(source, *p, nullptr, options);
}

TEST(Replay, AClockSteppingBackEndsTheReplayWhereverItFallsInTheStream) {
  // Two logs joined: `first` rows at 200 Hz from 1 s, then the clock restarts
  // at 0.2 s. Each row ahead of the restart looked like a glitch to the one
  // after it, so all of them arrived with the restart at once and flooded the
  // mailbox. Now the first log replays on its own clock and the replay ends
  // at its last row. The restart is put around the streaming window's edge
  // (4096 rows handed out, 64 looked ahead), where the run in view may be short, and near the start.
  for (const size_t first : {9, 100, 4090, 4100, 4104, 4105, 4150, 4160, 4170}) {
    std::vector<TraceRow> rows;
    for (size_t i = 0; i < first; ++i) rows.push_back({1'000'000 + 5000 * i, 400, 240, true});
    for (size_t i = 0; i < 300; ++i) rows.push_back({200'000 + 5000 * i, 400, 240, true});
    const ReplaySummary s = replay_ending_at_a_step_back(rows);
    const uint64_t last = 1'000'000 + 5000 * (first - 1);
    EXPECT_TRUE(s.time_jump) << first;
    EXPECT_EQ(s.time_jump_from_us, last) << first;
    EXPECT_EQ(s.time_jump_to_us, 200'000u) << first;
    EXPECT_EQ(s.rows_after_time_jump, 300u) << first;
    EXPECT_EQ(s.samples, first) << first;
    EXPECT_EQ(s.ticks, (last - 1'000'000) / kTickPeriodUs + 1) << first;
    EXPECT_EQ(s.faults[Fault::MailboxOverflow], 0u) << first;
  }
}

TEST(Replay, AnEndNamesTheLinesOfTheLastReportAndOfTheRowThatEndedIt) {
  // Rows numbered as a file's lines (header on line 1). A log of 12 rows, its
  // last two out of order, then a restarted clock: the last report delivered
  // is the one with the latest arrival (line 12), not the last read.
  const auto numbered = [](std::vector<TraceRow> rows) {
    for (size_t i = 0; i < rows.size(); ++i) rows[i].line = i + 2;
    return rows;
  };
  std::vector<TraceRow> log;
  for (uint64_t i = 0; i < 12; ++i) log.push_back({1'000'000 + 5000 * i, 400, 240, true});
  std::swap(log[10].t_us, log[11].t_us);
  log.push_back({200'000, 400, 240, true});
  log.push_back({205'000, 400, 240, true});
  const ReplaySummary back = replay_ending_at_a_step_back(numbered(log));
  ASSERT_TRUE(back.time_jump);
  EXPECT_EQ(back.time_jump_from_us, 1'055'000u);
  EXPECT_EQ(back.time_jump_from_line, 12u);
  EXPECT_EQ(back.time_jump_to_us, 200'000u);
  EXPECT_EQ(back.time_jump_to_line, 14u);

  const std::vector<TraceRow> gap = numbered({{0, 400, 240, true}, {5000, 400, 240, true}, {1'000'000'000, 400, 240, true}});
  size_t read = 0;
  const ReplaySummary ahead = replay_with_gap_limit(gap, read);
  ASSERT_TRUE(ahead.time_jump);
  EXPECT_EQ(ahead.time_jump_from_line, 3u);
  EXPECT_EQ(ahead.time_jump_to_line, 4u);
}

TEST(Replay, UpToEightStampsFarAheadInARowAreGlitchesNotAClockStep) {
  // 8 rows in a row stamped 100 s ahead arrive with the row after them; a
  // ninth makes them a clock that stepped back, and the replay ends.
  for (const size_t ahead : {size_t{1}, size_t{8}, size_t{9}}) {
    std::vector<TraceRow> rows;
    for (uint64_t i = 0; i < 200; ++i) rows.push_back({1'000'000 + 5000 * i, 400, 240, true});
    for (size_t i = 0; i < ahead; ++i) rows[100 + i].t_us += 100'000'000;
    const ReplaySummary s = replay_ending_at_a_step_back(rows);
    if (ahead <= 8) {
      EXPECT_FALSE(s.time_jump) << ahead;
      EXPECT_EQ(s.samples, 200u) << ahead;
      EXPECT_EQ(s.ticks, 199u * 5000u / kTickPeriodUs + 1) << ahead;
    } else {
      EXPECT_TRUE(s.time_jump);
      EXPECT_EQ(s.time_jump_from_us, rows[108].t_us);
      EXPECT_EQ(s.time_jump_to_us, rows[109].t_us);
      EXPECT_EQ(s.rows_after_time_jump, 91u);
    }
  }
}

TEST(Replay, OneRowFarBehindIsASampleTheTrackerDropsNotAClockStep) {
  // In the middle, and as the last row, with no row after it to make a step.
  for (const size_t behind : {size_t{100}, size_t{199}}) {
    std::vector<TraceRow> rows;
    for (uint64_t i = 0; i < 200; ++i) rows.push_back({1'000'000 + 5000 * i, 400, 240, true});
    rows[behind].t_us = 200'000;
    const ReplaySummary s = replay_ending_at_a_step_back(rows);
    EXPECT_FALSE(s.time_jump) << behind;
    EXPECT_EQ(s.samples, 200u) << behind;
    EXPECT_EQ(s.rejected_samples(), 1u) << behind;
  }
}

TEST(Replay, ARowWithItsTakenTimeGoesToTheTickThatTookItWhateverItsStamp) {
  // Stamps 1000, 1200, 1400 would all be taken by the ticks from 1000 on; the
  // device took them at 1700, 2201 and 2699 (its ticks are micros() in an
  // interrupt, a microsecond off the grid).
  std::vector<TraceRow> rows = {{1000, 10, 10, true}, {1200, 20, 10, true}, {1400, 30, 10, true}};
  rows[0].taken_us = 1700;
  rows[1].taken_us = 2201;
  rows[2].taken_us = 2699;
  auto p = std::make_unique<HapticPipeline>();
  std::vector<std::pair<uint64_t, uint32_t>> seen;  // tick time, reports taken by then
  replay(rows, *p, [&](uint64_t t, const TickOutput&) { seen.push_back({t, p->samples_taken()}); });
  ASSERT_EQ(seen.size(), 3u);
  EXPECT_EQ(seen[0], (std::pair<uint64_t, uint32_t>{1700, 1}));
  EXPECT_EQ(seen[1], (std::pair<uint64_t, uint32_t>{2200, 2}));
  EXPECT_EQ(seen[2], (std::pair<uint64_t, uint32_t>{2700, 3}));
}

TEST(Replay, ARecordingWithTakenTimesReplaysToTheDevicesTicks) {
  // A model device, independent of the replay: ticks every 500 us, each at
  // micros() a microsecond or so off the grid; a 200 Hz report of a moving
  // finger reaches the mailbox 700 us after its stamp (the I2C read) and is
  // taken by the next tick. The trace keeps each report's stamp and the time
  // of the tick that took it, as ffctl record writes them.
  Condition c;
  c.scene = scenes::heightmap(Target::Top);
  c.amplitude.strength = 0.66f;
  auto device = std::make_unique<HapticPipeline>();
  ASSERT_EQ(device->set_condition(c), PrepareStatus::Ok);
  std::vector<TraceRow> rows;
  std::vector<std::pair<uint64_t, uint16_t>> device_ticks;
  uint64_t next_stamp = 10'000;
  for (uint64_t k = 0; k < 4000; ++k) {
    const uint64_t tick = 250 + 500 * k + (k % 3) - 1;  // 249, 750, 1251, 1749, ...
    while (next_stamp + 700 <= tick && next_stamp < 1'800'000) {
      const float s = static_cast<float>(next_stamp) * 1e-6f;
      TraceRow r{next_stamp, 100.0f + 300.0f * s, 240.0f - 120.0f * std::sin(4.0f * s), s < 1.2f};
      r.taken_us = static_cast<int64_t>(tick);
      device->post_sample({static_cast<uint32_t>(r.t_us), r.x, r.y, r.touch});
      rows.push_back(r);
      next_stamp += 5000;
    }
    if (!rows.empty()) device_ticks.push_back({tick, device->tick(static_cast<uint32_t>(tick)).dac});
  }
  auto p = std::make_unique<HapticPipeline>();
  ASSERT_EQ(p->set_condition(c), PrepareStatus::Ok);
  std::vector<uint16_t> replayed;
  replay(rows, *p, [&](uint64_t, const TickOutput& o) { replayed.push_back(o.dac); });
  ASSERT_GE(replayed.size(), 3000u);
  size_t beyond_one_code = 0, moving = 0;
  for (size_t i = 0; i < replayed.size() && i < device_ticks.size(); ++i) {
    beyond_one_code += std::abs(int{replayed[i]} - int{device_ticks[i].second}) > 1;
    moving += device_ticks[i].second != 0;
  }
  EXPECT_GT(moving, 1000u);
  EXPECT_EQ(beyond_one_code, 0u);
}

TEST(ReplaySummary, RejectedSamplesAreTheFaultsThatDropOne) {
  const Fault dropping[] = {Fault::NonFiniteCoordinate, Fault::OffScreen,       Fault::NonIncreasingTime,
                            Fault::JumpRejected,        Fault::MailboxOverflow, Fault::SampleTimeImplausible};
  for (int k = 0; k < static_cast<int>(Fault::kCount); ++k) {
    const Fault f = static_cast<Fault>(k);
    ReplaySummary summary;
    summary.samples = 100;
    for (int i = 0; i < 3; ++i) summary.faults.add(f);
    const bool drops = std::find(std::begin(dropping), std::end(dropping), f) != std::end(dropping);
    EXPECT_EQ(summary.rejected_samples(), drops ? 3u : 0u) << to_string(f);
  }
  ReplaySummary summary;
  summary.samples = 4;
  for (const Fault f : dropping) summary.faults.add(f);
  EXPECT_EQ(summary.rejected_samples(), 4u);  // six faults, four samples
  summary.samples = 7;
  EXPECT_EQ(summary.rejected_samples(), 6u);
}

}  // namespace
}  // namespace ff::host
