// ffctl verify against a model device: a native pipeline ticking every 500 us
// whose reports reach the mailbox some time after their timestamp (the I2C
// read after the data-ready edge), as on the Teensy.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "device_client.hpp"
#include "frictionfield/core/scenes.hpp"

namespace ff::ffctl {
namespace {

Condition heightmap_top() {
  Condition c;
  c.scene = scenes::heightmap(Target::Top);
  c.amplitude.strength = 0.66f;
  return c;
}

// 200 Hz reports of a finger that draws a wave from x = 100 to 700 over
// 1.5 s, lifts for 0.4 s, and comes back for another 0.5 s.
std::vector<SensorSample> finger_reports() {
  std::vector<SensorSample> out;
  for (uint32_t t = 20000; t <= 1520000; t += 5000) {
    const float s = static_cast<float>(t - 20000) * 1e-6f;
    out.push_back({t, 100.0f + 400.0f * s, 240.0f - 100.0f * std::sin(3.0f * s), true});
  }
  out.push_back({1525000, 0.0f, 0.0f, false});
  for (uint32_t t = 1920000; t <= 2420000; t += 5000) {
    const float s = static_cast<float>(t - 1920000) * 1e-6f;
    out.push_back({t, 650.0f - 300.0f * s, 100.0f + 200.0f * s, true});
  }
  return out;
}

// The device: ticks at 500 us; a report is posted `latency_us` after its
// stamp and taken by the first tick at or after that. Ticks before
// `record_from_us`, and reports posted before it, are not in the recording.
Recording model_device(const Condition& c, uint32_t latency_us, uint32_t record_from_us = 0,
                       uint32_t end_us = 2600000) {
  const std::vector<SensorSample> reports = finger_reports();
  auto pipeline = std::make_unique<HapticPipeline>();
  EXPECT_EQ(pipeline->set_condition(c), PrepareStatus::Ok);
  Recording r;
  size_t next = 0;
  for (uint32_t t = 500; t <= end_us; t += 500) {
    while (next < reports.size() && reports[next].t_us + latency_us <= t) {
      const SensorSample& s = reports[next++];
      pipeline->post_sample(s);
      if (s.t_us + latency_us >= record_from_us) r.samples.push_back({{s.t_us, s.x, s.y, s.touch}, true, t});
    }
    const TickOutput out = pipeline->tick(t);
    if (t >= record_from_us) r.ticks.push_back({t, out.amplitude, out.dac, out.present});
  }
  return r;
}

TEST(Verify, ReportsGoToTheTickThatTookThemOnTheDevice) {
  // A read latency of 700 us: every report reaches the device one or two
  // ticks after the tick its timestamp precedes.
  const Recording r = model_device(heightmap_top(), 700);
  const VerifyResult v = verify(r, heightmap_top());
  ASSERT_TRUE(v.prepared);
  EXPECT_TRUE(v.exact_alignment);
  EXPECT_TRUE(v.synchronised);
  EXPECT_EQ(v.warm_up, 0u);
  EXPECT_EQ(v.compared, r.ticks.size());
  EXPECT_EQ(v.beyond_one_code, 0u);
  EXPECT_EQ(v.max_dac_difference, 0);

  // Without the taken times, reports go by timestamp, a tick early: the
  // rendering parts while the finger moves. This is why they are worth streaming.
  Recording by_time = r;
  for (DeviceSample& s : by_time.samples) s.taken_known = false;
  const VerifyResult u = verify(by_time, heightmap_top());
  EXPECT_FALSE(u.exact_alignment);
  EXPECT_GT(u.beyond_one_code, 100u);
  EXPECT_GT(u.max_dac_difference, 1);
}

TEST(Verify, WithoutLatencyTimestampsAreEnough) {
  Recording r = model_device(heightmap_top(), 0);
  for (DeviceSample& s : r.samples) s.taken_known = false;
  const VerifyResult v = verify(r, heightmap_top());
  EXPECT_EQ(v.compared, r.ticks.size());
  EXPECT_EQ(v.beyond_one_code, 0u);
}

TEST(Verify, ARecordingStartedMidStrokeIsComparedFromTheFirstLiftOff) {
  // The stream starts at 0.5 s with the finger down: the device's filters
  // hold 0.5 s of history the recording lacks.
  const Recording r = model_device(heightmap_top(), 700, 500200);
  const VerifyResult v = verify(r, heightmap_top());
  EXPECT_TRUE(v.synchronised);
  // Until the lift-off: last touch report at 1.52 s, touch = 0 at 1.525 s, 20 ms timeout.
  EXPECT_GT(v.warm_up, 2000u);
  EXPECT_LT(v.warm_up, 2200u);
  EXPECT_EQ(v.warm_up + v.compared, r.ticks.size());
  EXPECT_EQ(v.beyond_one_code, 0u);
}

TEST(Verify, AFingerThatNeverLiftsIsComparedFromTheStart) {
  const Recording r = model_device(heightmap_top(), 700, 500200, 1400000);
  const VerifyResult v = verify(r, heightmap_top());
  EXPECT_FALSE(v.synchronised);
  EXPECT_EQ(v.warm_up, 0u);
  EXPECT_EQ(v.compared, r.ticks.size());
  EXPECT_GT(v.beyond_one_code, 0u);  // the device's head start shows
}

TEST(Verify, TicksLostFromTheStreamAreCountedAndComparisonResumesAfterALiftOff) {
  Recording r = model_device(heightmap_top(), 700);
  // 10 ticks lost at 1.0 s (mid-stroke): the reports they took still reach
  // the native side, at the next tick there is.
  const auto at = std::find_if(r.ticks.begin(), r.ticks.end(), [](const DeviceTick& t) { return t.t_us == 1000000; });
  ASSERT_NE(at, r.ticks.end());
  r.ticks.erase(at, at + 10);
  const VerifyResult v = verify(r, heightmap_top());
  EXPECT_EQ(v.missing_ticks, 10u);
  EXPECT_GT(v.warm_up, 1000u);  // from 1.0 s to the lift-off at ~1.545 s
  EXPECT_LT(v.warm_up, 1100u);
  EXPECT_EQ(v.beyond_one_code, 0u);
  EXPECT_EQ(v.compared + v.warm_up, r.ticks.size());
}

TEST(Verify, DifferencesAreReportedWhereTheyAre) {
  Recording r = model_device(heightmap_top(), 700);
  // The device rendered 40 ticks wrongly from 0.8 s, and lost the finger for one tick at 2.0 s.
  size_t first = 0;
  while (r.ticks[first].t_us != 800000) ++first;
  for (size_t i = first; i < first + 40; ++i) r.ticks[i].dac = static_cast<uint16_t>(r.ticks[i].dac ^ 0x200);
  r.ticks[first + 20].dac = static_cast<uint16_t>(r.ticks[first + 20].dac ^ 0x600);  // the worst: 1024 codes
  size_t late = first;
  while (r.ticks[late].t_us != 2000000) ++late;
  ASSERT_TRUE(r.ticks[late].present);
  r.ticks[late].present = false;
  const VerifyResult v = verify(r, heightmap_top());
  EXPECT_EQ(v.beyond_one_code, 41u);
  EXPECT_EQ(v.presence_mismatches, 1u);
  ASSERT_EQ(v.run_count, 2u);
  ASSERT_EQ(v.runs.size(), 2u);
  EXPECT_EQ(v.runs[0].first_t_us, 800000u);
  EXPECT_EQ(v.runs[0].last_t_us, 800000u + 39 * 500);
  EXPECT_EQ(v.runs[0].ticks, 40u);
  EXPECT_EQ(v.runs[0].max_dac_difference, 1024);
  EXPECT_EQ(v.runs[0].worst.t_us, 810000u);
  EXPECT_EQ(v.runs[0].first.t_us, 800000u);
  EXPECT_EQ(v.runs[0].first.device_dac, r.ticks[first].dac);
  EXPECT_EQ(std::abs(static_cast<int>(v.runs[0].first.native_dac) - static_cast<int>(r.ticks[first].dac)), 0x200);
  EXPECT_EQ(v.runs[1].first_t_us, 2000000u);
  EXPECT_TRUE(v.runs[1].worst.native_present);
  EXPECT_FALSE(v.runs[1].worst.device_present);
  EXPECT_EQ(v.max_dac_difference, 1024);
}

TEST(Verify, AnotherConditionIsCaught) {
  const Recording r = model_device(heightmap_top(), 700);
  Condition other = heightmap_top();
  other.amplitude.strength = 1.0f;
  EXPECT_GT(verify(r, other).beyond_one_code, 500u);
  EXPECT_FALSE(verify(r, Condition{}).beyond_one_code == 0);  // neutral
}

}  // namespace
}  // namespace ff::ffctl

namespace ff::ffctl {
namespace {

TEST(Verify, CoverageSaysHowMuchWasComparedAndAMinimumFailsTheRest) {
  // Recorded from 0.1 s, the finger down until 1.525 s: nothing before the
  // lift can be compared (the device's filters hold reports the recording
  // lacks), so at most (2.6 - 1.525) / 0.0005 + 1 = 2151 of the 5001 ticks.
  const Recording r = model_device(heightmap_top(), 700, 100000);
  const VerifyResult v = verify(r, heightmap_top());
  ASSERT_EQ(v.recorded, 5001u);
  EXPECT_EQ(v.compared + v.warm_up, v.recorded);
  EXPECT_EQ(v.beyond_one_code, 0u);
  EXPECT_LE(v.compared, 2151u);
  EXPECT_GT(v.compared, 1500u);  // the tracker lets go within ~0.3 s of the lift
  EXPECT_NEAR(v.coverage(), static_cast<double>(v.compared) / 5001.0, 1e-12);
  EXPECT_FALSE(verify_passed(v, kDefaultMinCoverage));  // agreement on 43 % proves little
  EXPECT_TRUE(verify_passed(v, 0.25));                  // unless asked otherwise
  // A full recording passes the default; one tampered tick fails any minimum.
  Recording full = model_device(heightmap_top(), 700);
  EXPECT_TRUE(verify_passed(verify(full, heightmap_top()), kDefaultMinCoverage));
  full.ticks[3000].dac = static_cast<uint16_t>(full.ticks[3000].dac ^ 0x100);
  EXPECT_FALSE(verify_passed(verify(full, heightmap_top()), 0.0));
  // Nothing compared never passes.
  EXPECT_FALSE(verify_passed(VerifyResult{}, 0.0));
}

}  // namespace
}  // namespace ff::ffctl
