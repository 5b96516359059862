// The zForce driver: the configuration exchange byte for byte (replayed),
// then against the emulated sensor: samples in pixels at the DR edge time,
// one finger tracked, every fault counted and dropped without losing sync.
#include "frictionfield/drivers/zforce_sensor.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "frictionfield/emulated/replay_mocks.hpp"
#include "zforce_rig.hpp"

namespace ff {
namespace {

using emulated::expect_read;
using emulated::expect_write;
using emulated::I2cTransaction;
using emulated::MockI2cInitiator;
using emulated::ZforceModel;
using test::ZforceRig;
using Fault = ZforceModel::Fault;

// DR as the protocol defines it: up exactly while the sensor has a message,
// i.e. while the next expected transaction is a read.
class ScriptDr final : public DataReadyInput {
 public:
  ScriptDr(const std::vector<I2cTransaction>& script, const MockI2cInitiator& bus) : script_(script), bus_(bus) {}
  bool asserted() const override {
    return bus_.used() < gate && bus_.used() < script_.size() && script_[bus_.used()].write.empty();
  }
  bool take_edge(uint32_t& t_us, uint32_t& edges) override {
    if (!asserted() || bus_.used() == last_) return false;
    last_ = bus_.used();
    t_us = edge_us;
    edges = 1;
    return true;
  }
  uint32_t edge_us = 0;
  size_t gate = SIZE_MAX;  // DR stays low from this transaction on (the sensor has nothing yet)

 private:
  const std::vector<I2cTransaction>& script_;
  const MockI2cInitiator& bus_;
  size_t last_ = SIZE_MAX;
};

// Frames of the byte-for-byte exchange below, for scripts that vary it.
const std::vector<uint8_t> kBootHead = {0xEE, 0x0F};
const std::vector<uint8_t> kBoot = {0xF0, 0x0D, 0x40, 0x02, 0x00, 0x00, 0x63, 0x07, 0x80, 0x01, 0x00, 0x81, 0x02, 0x07, 0x80};
// The boot-complete notification whole, as the emulated sensor schedules raw frames.
std::vector<uint8_t> boot_frame() {
  std::vector<uint8_t> f = kBootHead;
  f.insert(f.end(), kBoot.begin(), kBoot.end());
  return f;
}
const std::vector<uint8_t> kAskTouchFormat = {0xEE, 0x08, 0xEE, 0x06, 0x40, 0x02, 0x02, 0x00, 0x66, 0x00};
const std::vector<uint8_t> kTouchFormatHead = {0xEE, 0x0E};
const std::vector<uint8_t> kTouchFormat = {0xEF, 0x0C, 0x40, 0x02, 0x02, 0x00, 0x66, 0x06, 0x41, 0x04, 0x01, 0xF6, 0x18, 0x04};
const std::vector<uint8_t> kAskResolution = {0xEE, 0x10, 0xEE, 0x0E, 0x40, 0x02, 0x02, 0x00, 0x69, 0x08, 0x80, 0x02,
                                             0x0C, 0x80, 0x81, 0x02, 0x07, 0x80};
const std::vector<uint8_t> kResolutionHead = {0xEE, 0x10};
const std::vector<uint8_t> kResolution = {0xEF, 0x0E, 0x40, 0x02, 0x02, 0x00, 0x69, 0x08, 0x80, 0x02, 0x0C, 0x80, 0x81,
                                          0x02, 0x07, 0x80};
const std::vector<uint8_t> kAskFrequency = {0xEE, 0x0F, 0xEE, 0x0D, 0x40, 0x02, 0x00, 0x00, 0x68, 0x07, 0x80, 0x02,
                                            0x00, 0xC8, 0x82, 0x01, 0x32};

// The driver on a replayed script from begin(0), polled every millisecond
// until the script is used up (or 2 s pass); the script must outlive it.
struct ScriptRun {
  MockI2cInitiator bus;
  ScriptDr dr;
  ZforceSensor sensor;
  uint32_t done_us = 0;  // when the last transaction had happened
  explicit ScriptRun(const std::vector<I2cTransaction>& script) : bus(script), dr(script, bus), sensor(bus, dr) {
    sensor.begin(0);
    SensorSample s;
    for (;; done_us += 1000) {
      sensor.poll(done_us, s);
      if (bus.used() >= script.size() || done_us >= 2000000) break;
    }
    std::string why;
    EXPECT_TRUE(bus.finished(&why)) << why;
  }
};

TEST(ZforceSensor, EachStepHasItsOwnThreeAttempts) {
  // touchFormat answered at its second attempt, resolution at its third.
  const std::vector<I2cTransaction> script = {
      expect_read(0x50, kBootHead),         expect_read(0x50, kBoot),
      expect_write(0x50, kAskTouchFormat),  expect_write(0x50, kAskTouchFormat),
      expect_read(0x50, kTouchFormatHead),  expect_read(0x50, kTouchFormat),
      expect_write(0x50, kAskResolution),   expect_write(0x50, kAskResolution),
      expect_write(0x50, kAskResolution),   expect_read(0x50, kResolutionHead),
      expect_read(0x50, kResolution),       expect_write(0x50, kAskFrequency),
  };
  const ScriptRun run(script);
  EXPECT_EQ(run.sensor.state(), ZforceState::Configuring);
  EXPECT_EQ(run.sensor.count(ZforceCount::ConfigRetry), 3u);
}

TEST(ZforceSensor, ARebootGrantsTheFirstStepItsThreeAttemptsAgain) {
  // Two unanswered requests, a reboot, then the first request answered at its
  // second attempt: the attempts before the reboot do not count.
  const std::vector<I2cTransaction> script = {
      expect_read(0x50, kBootHead),        expect_read(0x50, kBoot),
      expect_write(0x50, kAskTouchFormat), expect_write(0x50, kAskTouchFormat),
      expect_read(0x50, kBootHead),        expect_read(0x50, kBoot),
      expect_write(0x50, kAskTouchFormat), expect_write(0x50, kAskTouchFormat),
      expect_read(0x50, kTouchFormatHead), expect_read(0x50, kTouchFormat),
      expect_write(0x50, kAskResolution),
  };
  const ScriptRun run(script);
  EXPECT_EQ(run.sensor.state(), ZforceState::Configuring);
  EXPECT_EQ(run.sensor.count(ZforceCount::ConfigRetry), 2u);
}

TEST(ZforceSensor, ABootNotificationWhileAwaitingAnAnswerAsksAgainAtOnce) {
  const std::vector<I2cTransaction> script = {
      expect_read(0x50, kBootHead),        expect_read(0x50, kBoot),
      expect_write(0x50, kAskTouchFormat),  // unanswered: the sensor rebooted instead
      expect_read(0x50, kBootHead),        expect_read(0x50, kBoot),
      expect_write(0x50, kAskTouchFormat),
  };
  const ScriptRun run(script);
  EXPECT_LT(run.done_us, 10000u);  // not after the 100 ms answer timeout
  EXPECT_EQ(run.sensor.count(ZforceCount::ConfigRetry), 0u);
}

TEST(ZforceSensor, ConfigurationExchangeAndFirstTouchByteForByte) {
  const std::vector<I2cTransaction> script = {
      // Boot complete.
      expect_read(0x50, kBootHead),
      expect_read(0x50, kBoot),
      // touchFormat -> the default 9-byte descriptor.
      expect_write(0x50, kAskTouchFormat),
      expect_read(0x50, kTouchFormatHead),
      expect_read(0x50, kTouchFormat),
      // resolution 3200 x 1920.
      expect_write(0x50, kAskResolution),
      expect_read(0x50, kResolutionHead),
      expect_read(0x50, kResolution),
      // frequency 200 Hz finger, 50 Hz idle, to the platform.
      expect_write(0x50, kAskFrequency),
      expect_read(0x50, {0xEE, 0x0F}),
      expect_read(0x50, {0xEF, 0x0D, 0x40, 0x02, 0x00, 0x00, 0x68, 0x07, 0x80, 0x02, 0x00, 0xC8, 0x82, 0x01, 0x32}),
      // two reported touches.
      expect_write(0x50, {0xEE, 0x0B, 0xEE, 0x09, 0x40, 0x02, 0x02, 0x00, 0x73, 0x03, 0x86, 0x01, 0x02}),
      expect_read(0x50, {0xEE, 0x0B}),
      expect_read(0x50, {0xEF, 0x09, 0x40, 0x02, 0x02, 0x00, 0x73, 0x03, 0x86, 0x01, 0x02}),
      // detection mode.
      expect_write(0x50, {0xEE, 0x17, 0xEE, 0x15, 0x40, 0x02, 0x02, 0x00, 0x67, 0x0F, 0x80, 0x01, 0xFF, 0x81, 0x01,
                          0x00, 0x82, 0x01, 0x00, 0x83, 0x01, 0x00, 0x84, 0x01, 0x00}),
      expect_read(0x50, {0xEE, 0x17}),
      expect_read(0x50, {0xEF, 0x15, 0x40, 0x02, 0x02, 0x00, 0x67, 0x0F, 0x80, 0x01, 0xFF, 0x81, 0x01, 0x00, 0x82,
                         0x01, 0x00, 0x83, 0x01, 0x00, 0x84, 0x01, 0x00}),
      // enable.
      expect_write(0x50, {0xEE, 0x0B, 0xEE, 0x09, 0x40, 0x02, 0x02, 0x00, 0x65, 0x03, 0x81, 0x01, 0x00}),
      expect_read(0x50, {0xEE, 0x0B}),
      expect_read(0x50, {0xEF, 0x09, 0x40, 0x02, 0x02, 0x00, 0x65, 0x03, 0x81, 0x01, 0x00}),
      // A touch: id 0 down at (400, 960) sensor units.
      expect_read(0x50, {0xEE, 0x16}),
      expect_read(0x50, {0xF0, 0x14, 0x40, 0x02, 0x02, 0x00, 0xA0, 0x0B, 0x42, 0x09, 0x00, 0x00, 0x01, 0x90, 0x03,
                         0xC0, 0x00, 0x30, 0x64, 0x58, 0x01, 0x20}),
  };
  MockI2cInitiator bus(script);
  ScriptDr dr(script, bus);
  dr.gate = script.size() - 2;  // the touch comes later
  ZforceSensor sensor(bus, dr);
  sensor.begin(0);
  SensorSample s;
  uint32_t t = 0;
  for (; t < 7000 && sensor.state() != ZforceState::Running; t += 1000) EXPECT_FALSE(sensor.poll(t, s));
  ASSERT_EQ(sensor.state(), ZforceState::Running);
  dr.gate = SIZE_MAX;
  dr.edge_us = 123456;
  ASSERT_TRUE(sensor.poll(130000, s));
  EXPECT_EQ(s.t_us, 123456u);  // the DR edge, not the poll time
  EXPECT_EQ(s.x, 100.0f);      // 400 * 0.25
  EXPECT_EQ(s.y, 240.0f);      // 960 * 0.25
  EXPECT_TRUE(s.touch);
  std::string why;
  EXPECT_TRUE(bus.finished(&why)) << why;
  EXPECT_EQ(sensor.errors(), 0u);
}

// DR up for a few polls because messages queued behind an answer is no lost
// attempt: the next request waits for them, within the answer timeout.
TEST(ZforceSensor, MessagesQueuedBehindAnAnswerDelayTheNextRequestWithoutARetry) {
  const std::vector<uint8_t> answer_head = {0xEE, 0x0E};
  const std::vector<uint8_t> answer = {0xEF, 0x0C, 0x40, 0x02, 0x02, 0x00, 0x66, 0x06, 0x41, 0x04, 0x01, 0xF6, 0x18, 0x04};
  std::vector<I2cTransaction> script = {
      expect_read(0x50, {0xEE, 0x0F}),
      expect_read(0x50, {0xF0, 0x0D, 0x40, 0x02, 0x00, 0x00, 0x63, 0x07, 0x80, 0x01, 0x00, 0x81, 0x02, 0x07, 0x80}),
      expect_write(0x50, {0xEE, 0x08, 0xEE, 0x06, 0x40, 0x02, 0x02, 0x00, 0x66, 0x00}),
  };
  for (int i = 0; i < 5; ++i) {  // the answer, then four copies: five frames, one more than a poll reads
    script.push_back(expect_read(0x50, answer_head));
    script.push_back(expect_read(0x50, answer));
  }
  script.push_back(expect_write(0x50, {0xEE, 0x10, 0xEE, 0x0E, 0x40, 0x02, 0x02, 0x00, 0x69, 0x08, 0x80, 0x02, 0x0C,
                                       0x80, 0x81, 0x02, 0x07, 0x80}));
  const ScriptRun run(script);
  EXPECT_EQ(run.done_us, 2000u);  // the third poll sends
  EXPECT_EQ(run.sensor.count(ZforceCount::UnexpectedResponse), 4u);
  EXPECT_EQ(run.sensor.count(ZforceCount::ConfigRetry), 0u);
}

TEST(ZforceSensor, ConfiguresTheEmulatedSensor) {
  ZforceRig rig;
  EXPECT_LT(rig.configure(), 20000u);
  EXPECT_EQ(rig.sensor.state(), ZforceState::Running);
  EXPECT_TRUE(rig.model.enabled());
  EXPECT_TRUE(rig.model.detection_mode());
  EXPECT_EQ(rig.model.resolution_x(), 3200);
  EXPECT_EQ(rig.model.resolution_y(), 1920);
  EXPECT_EQ(rig.model.finger_frequency(), 200);
  EXPECT_EQ(rig.model.idle_frequency(), 50);
  EXPECT_EQ(rig.model.reported_touches(), 2);
  EXPECT_EQ(rig.model.requests_rejected(), 0u) << rig.model.last_rejection();
  EXPECT_EQ(rig.sensor.count(ZforceCount::FramesRead), 7u);  // boot complete + six answers
  EXPECT_EQ(rig.sensor.errors(), 0u);
}

// 40 reports, 5 ms apart with a little jitter, on the 0.25 px grid.
std::vector<SensorSample> stroke(uint32_t t0, int n = 40, float x0 = 100.0f) {
  std::vector<SensorSample> t;
  for (int i = 0; i < n; ++i) {
    t.push_back({t0 + static_cast<uint32_t>(i) * 5000u + static_cast<uint32_t>((i * 37) % 7) * 100u,
                 x0 + 2.25f * static_cast<float>(i), 240.0f - 0.5f * static_cast<float>(i), true});
  }
  return t;
}

void expect_samples(const std::vector<SensorSample>& got, const std::vector<SensorSample>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (size_t i = 0; i < want.size(); ++i) {
    EXPECT_EQ(got[i].t_us, want[i].t_us) << i;
    EXPECT_EQ(got[i].touch, want[i].touch) << i;
    if (want[i].touch) {
      EXPECT_EQ(got[i].x, want[i].x) << i;
      EXPECT_EQ(got[i].y, want[i].y) << i;
    }
  }
}

TEST(ZforceSensor, ReportsATraceInPixelsAtTheDrEdgeTimes) {
  ZforceRig rig;
  rig.configure();
  std::vector<SensorSample> trace = stroke(100000);
  const SensorSample last = trace.back();
  trace.push_back({last.t_us + 5000, 0.0f, 0.0f, false});
  rig.model.load_trace(trace);
  // Polled every 1.7 ms, out of step with the sensor.
  const std::vector<SensorSample> got = rig.run(100000, last.t_us + 20000, 1700);
  std::vector<SensorSample> want = trace;
  want.back().x = last.x;
  want.back().y = last.y;
  expect_samples(got, want);
  EXPECT_FALSE(rig.sensor.finger_present());
  EXPECT_EQ(rig.sensor.count(ZforceCount::Samples), trace.size());
  EXPECT_EQ(rig.sensor.errors(), 0u);
}

TEST(ZforceSensor, FingerPresentFollowsDownAndUp) {
  ZforceRig rig;
  rig.configure();
  rig.model.load_trace({{100000, 50.0f, 50.0f, true}, {105000, 50.0f, 50.0f, false}});
  rig.run(100000, 102000);
  EXPECT_TRUE(rig.sensor.finger_present());
  rig.run(102500, 106000);
  EXPECT_FALSE(rig.sensor.finger_present());
}

class SecondFingerTest : public ::testing::TestWithParam<bool> {};

TEST_P(SecondFingerTest, IsIgnoredWhereverItIsListed) {
  ZforceRig rig;
  rig.configure();
  const std::vector<SensorSample> trace = stroke(100000);
  ZforceModel::SecondFinger second;
  second.from_us = trace[10].t_us;
  second.to_us = trace[25].t_us;
  second.listed_first = GetParam();
  rig.model.load_trace(trace, &second);
  const std::vector<SensorSample> got = rig.run(100000, trace.back().t_us + 1000);
  expect_samples(got, trace);
  EXPECT_EQ(rig.sensor.count(ZforceCount::OtherFingerIgnored), 16u);  // its down and 15 moves
  EXPECT_EQ(rig.sensor.errors(), 0u);
}

INSTANTIATE_TEST_SUITE_P(ListedAfterOrFirst, SecondFingerTest, ::testing::Values(false, true));

TEST(ZforceSensor, ASecondFingerLeftBehindIsNotAdopted) {
  ZforceRig rig;
  rig.configure();
  std::vector<SensorSample> trace = stroke(100000, 10);
  const uint32_t lift = trace.back().t_us + 5000;
  trace.push_back({lift, 0.0f, 0.0f, false});
  for (int i = 1; i <= 5; ++i) trace.push_back({lift + 5000u * i, 0.0f, 0.0f, false});  // second finger alone
  const std::vector<SensorSample> again = stroke(lift + 100000, 5, 300.0f);
  trace.insert(trace.end(), again.begin(), again.end());
  ZforceModel::SecondFinger second;
  second.from_us = trace[5].t_us;
  second.to_us = lift + 25000;
  rig.model.load_trace(trace, &second);
  const std::vector<SensorSample> got = rig.run(100000, again.back().t_us + 1000);
  ASSERT_EQ(got.size(), 10u + 1u + 5u);  // first stroke, its lift, the new stroke: nothing from the other finger
  EXPECT_FALSE(got[10].touch);
  EXPECT_EQ(got[11].x, 300.0f);
  EXPECT_EQ(rig.sensor.count(ZforceCount::ResumedWithoutDown), 0u);
}

// A touch notification at `t_us`: fingers `ids` with their events (0 down,
// 1 move, 2 up), all at (800, 960) sensor units.
void touches(ZforceModel& model, uint32_t t_us, std::vector<uint8_t> ids, std::vector<uint8_t> events) {
  const std::vector<uint32_t> xs(ids.size(), 800), ys(ids.size(), 960);
  model.schedule_raw(t_us, model.touch_frame(ids.data(), events.data(), xs.data(), ys.data(),
                                             static_cast<int>(ids.size()), t_us));
}

TEST(ZforceSensor, AnIgnoredFingerThatLiftedIsIgnoredNoMore) {
  // Finger 1 comes while finger 0 is tracked (ignored), lifts, and later moves
  // again after a lost down, when no finger is tracked: it is taken up.
  ZforceRig rig;
  rig.configure();
  touches(rig.model, 100000, {0}, {0});        // 0 down: tracked
  touches(rig.model, 105000, {0, 1}, {1, 0});  // 1 down: ignored
  touches(rig.model, 110000, {0, 1}, {1, 2});  // 1 up
  touches(rig.model, 115000, {0}, {2});        // 0 up: nothing tracked
  touches(rig.model, 120000, {1}, {1});        // 1 moves, its down lost
  const std::vector<SensorSample> got = rig.run(100000, 125000);
  ASSERT_EQ(got.size(), 5u);  // 0's down, move, move, up; then 1
  EXPECT_FALSE(got[3].touch);
  EXPECT_TRUE(got[4].touch);
  EXPECT_EQ(got[4].t_us, 120000u);
  EXPECT_EQ(rig.sensor.count(ZforceCount::OtherFingerIgnored), 1u);
  EXPECT_EQ(rig.sensor.count(ZforceCount::ResumedWithoutDown), 1u);
}

// Finger 1's up is lost while finger 0 is tracked; it comes down again and is
// tracked, lifts, and moves once more after a lost down: taken up again.
TEST(ZforceSensor, AFingerOnceIgnoredIsForgivenWhenItIsTracked) {
  ZforceRig rig;
  rig.configure();
  touches(rig.model, 100000, {0}, {0});        // 0 down: tracked
  touches(rig.model, 105000, {0, 1}, {1, 0});  // 1 down: ignored
  touches(rig.model, 110000, {0}, {2});        // 0 up; 1's up lost
  touches(rig.model, 115000, {1}, {0});        // 1 down: tracked
  touches(rig.model, 120000, {1}, {2});        // 1 up
  touches(rig.model, 125000, {1}, {1});        // 1 moves, its down lost
  const std::vector<SensorSample> got = rig.run(100000, 130000);
  ASSERT_EQ(got.size(), 6u);  // 0: down, move, up; 1: down, up, move
  EXPECT_TRUE(got[5].touch);
  EXPECT_EQ(got[5].t_us, 125000u);
  EXPECT_EQ(rig.sensor.count(ZforceCount::ResumedWithoutDown), 1u);
}

// The tracked finger and an ignored one both go silent (their ups lost): once
// the tracked one is forgotten, the other is no longer ignored either.
TEST(ZforceSensor, ForgettingASilentFingerForgivesTheIgnoredOnes) {
  ZforceRig rig;
  rig.configure();
  touches(rig.model, 100000, {0}, {0});        // 0 down: tracked
  touches(rig.model, 105000, {0, 1}, {1, 0});  // 1 down: ignored; then silence, both ups lost
  touches(rig.model, 400000, {1}, {1});        // 1 moves, 295 ms later (over the 200 ms track timeout)
  const std::vector<SensorSample> got = rig.run(100000, 405000);
  ASSERT_EQ(got.size(), 3u);
  EXPECT_EQ(got[2].t_us, 400000u);
  EXPECT_EQ(rig.sensor.count(ZforceCount::TrackLost), 1u);
  EXPECT_EQ(rig.sensor.count(ZforceCount::ResumedWithoutDown), 1u);
}

// The firmware polls with one now_us per loop pass; a DR edge that rises
// after the pass read the clock stamps its frame a little after now_us. The
// next poll of that pass must not take the tracked finger's newest report for
// one 2^32 us old: finger 0 (x = 200) stays tracked when finger 1 (x = 600)
// is later listed first.
TEST(ZforceSensor, AnEdgeNewerThanTheLoopsClockIsNoSilence) {
  ZforceRig rig;
  rig.configure();
  uint32_t x[2], y[2];
  rig.model.to_sensor(200.0f, 100.0f, x[0], y[0]);
  rig.model.to_sensor(600.0f, 100.0f, x[1], y[1]);
  auto frame = [&](uint32_t t_us, std::vector<uint8_t> ids, std::vector<uint8_t> events) {
    std::vector<uint32_t> xs, ys;
    for (uint8_t id : ids) {
      xs.push_back(x[id]);
      ys.push_back(y[id]);
    }
    rig.model.schedule_raw(t_us, rig.model.touch_frame(ids.data(), events.data(), xs.data(), ys.data(),
                                                       static_cast<int>(ids.size()), t_us));
  };
  frame(100000, {0}, {0});        // 0 down: tracked
  frame(105000, {0, 1}, {1, 0});  // 1 down: ignored
  frame(110002, {0, 1}, {1, 1});  // rises 2 us after the pass at 110000 read the clock
  frame(115000, {1, 0}, {1, 1});  // 1 listed first
  frame(120000, {1, 0}, {1, 1});
  std::vector<SensorSample> got;
  for (uint32_t t = 100000; t <= 125000; t += 500) {
    rig.model.advance_to(t + 2);  // the sensor runs on while the pass polls with the time it read
    SensorSample s;
    while (rig.sensor.poll(t, s)) got.push_back(s);
  }
  ASSERT_EQ(got.size(), 5u);
  EXPECT_EQ(got[2].t_us, 110002u);
  for (const SensorSample& s : got) {
    EXPECT_TRUE(s.touch);
    EXPECT_EQ(s.x, 200.0f) << s.t_us;
  }
  EXPECT_EQ(rig.sensor.count(ZforceCount::TrackLost), 0u);
  EXPECT_EQ(rig.sensor.count(ZforceCount::ResumedWithoutDown), 0u);
}

TEST(ZforceSensor, TheFirstFingerDownIsTheOneTracked) {
  // The other finger lands first (a frame with it alone), then the one the
  // trace follows: the first stays tracked, as the thesis' sensor would have it.
  ZforceRig rig;
  rig.configure();
  std::vector<SensorSample> trace = stroke(100000, 10);
  trace.insert(trace.begin(), {95000, 0.0f, 0.0f, false});
  ZforceModel::SecondFinger second;
  second.from_us = 95000;
  second.to_us = 200000;
  second.x = 400.0f;
  second.y = 100.0f;
  rig.model.load_trace(trace, &second);
  const std::vector<SensorSample> got = rig.run(95000, 160000);
  ASSERT_EQ(got.size(), 11u);
  for (const SensorSample& s : got) {
    EXPECT_EQ(s.x, 400.0f);
    EXPECT_EQ(s.y, 100.0f);
  }
}

struct FaultCase {
  Fault fault;
  ZforceCount counter;
};

class CorruptFrameTest : public ::testing::TestWithParam<FaultCase> {};

TEST_P(CorruptFrameTest, IsCountedOnceAndTheRestStaysInSync) {
  ZforceRig rig;
  rig.configure();
  const std::vector<SensorSample> trace = stroke(100000);
  rig.model.load_trace(trace);
  ASSERT_TRUE(rig.model.corrupt_frame_at(trace[17].t_us, GetParam().fault));
  const std::vector<SensorSample> got = rig.run(100000, trace.back().t_us + 1000);
  std::vector<SensorSample> want = trace;
  want.erase(want.begin() + 17);
  expect_samples(got, want);
  EXPECT_EQ(rig.sensor.count(GetParam().counter), 1u);
  EXPECT_EQ(rig.sensor.errors(), 1u);
  EXPECT_EQ(rig.model.frames_pending(), 0u);
}

INSTANTIATE_TEST_SUITE_P(
    EveryFault, CorruptFrameTest,
    ::testing::Values(FaultCase{Fault::BadHeader, ZforceCount::WrongHeader},
                      FaultCase{Fault::Truncated, ZforceCount::Truncated},
                      FaultCase{Fault::CutShort, ZforceCount::MalformedTag},
                      FaultCase{Fault::LengthOverMax, ZforceCount::LengthOverMax},
                      FaultCase{Fault::UnknownTag, ZforceCount::UnknownTag},
                      FaultCase{Fault::MalformedLength, ZforceCount::MalformedTag},
                      FaultCase{Fault::ImpossibleEvent, ZforceCount::ImpossibleValue},
                      FaultCase{Fault::OutOfRange, ZforceCount::ImpossibleValue}));

TEST(ZforceSensor, ResyncBytesAreExactlyTheRestOfTheBadFrame) {
  ZforceRig rig;
  rig.configure();
  const std::vector<SensorSample> trace = stroke(100000, 5);
  rig.model.load_trace(trace);
  rig.model.corrupt_frame_at(trace[2].t_us, Fault::BadHeader);
  rig.model.inject(trace[3].t_us + 1000, Fault::LengthOverMax);
  rig.run(100000, trace.back().t_us + 1000);
  // The bad frame is 25 bytes (2-byte timestamp) less its 2-byte header; then the 200 announced.
  EXPECT_EQ(rig.sensor.count(ZforceCount::ResyncBytes), 23u + 200u);
}

TEST(ZforceSensor, InjectedGarbageBetweenReportsChangesNothing) {
  ZforceRig rig;
  rig.configure();
  const std::vector<SensorSample> trace = stroke(100000);
  rig.model.load_trace(trace);
  const Fault faults[] = {Fault::BadHeader,   Fault::Truncated,       Fault::CutShort,        Fault::LengthOverMax,
                          Fault::UnknownTag,  Fault::MalformedLength, Fault::ImpossibleEvent, Fault::OutOfRange};
  int i = 2;
  for (Fault f : faults) {
    rig.model.inject(trace[i].t_us + 2500, f);
    i += 4;
  }
  expect_samples(rig.run(100000, trace.back().t_us + 1000), trace);
  EXPECT_EQ(rig.sensor.errors(), 8u);
  EXPECT_EQ(rig.sensor.count(ZforceCount::MalformedTag), 2u);
  EXPECT_EQ(rig.sensor.count(ZforceCount::ImpossibleValue), 2u);
}

TEST(ZforceSensor, ABadFrameJustBeforeAGoodOneDoesNotSwallowIt) {
  // Both are waiting when the main loop comes round: the drain of the bad one
  // must stop at the good one's DR edge, and keep that edge's time for it.
  ZforceRig rig;
  rig.configure();
  const std::vector<SensorSample> trace = stroke(100000, 10);
  rig.model.load_trace(trace);
  ASSERT_EQ(trace[4].t_us, 120100u);  // stroke()'s jitter: between the loop passes at 120 and 125 ms
  rig.model.inject(trace[4].t_us - 50, Fault::BadHeader);
  std::vector<SensorSample> got;
  for (uint32_t t = 100000; t <= trace.back().t_us + 5000; t += 5000) {  // a slow loop: both due at once
    rig.model.advance_to(t);
    SensorSample s;
    while (rig.sensor.poll(t + 300, s)) got.push_back(s);  // the loop reads 300 us after the sensor's time
  }
  ASSERT_EQ(got.size(), trace.size());
  EXPECT_EQ(got[4].x, trace[4].x);
  // DR rose for it when the drain emptied the bad one, at the sensor's 125 ms: not the poll's 125.3 ms.
  EXPECT_EQ(got[4].t_us, 125000u);
  for (size_t i = 0; i < got.size(); ++i) {  // the kept edge is used once
    if (i != 4) {
      EXPECT_EQ(got[i].t_us, trace[i].t_us) << i;
    }
  }
  EXPECT_EQ(rig.sensor.count(ZforceCount::WrongHeader), 1u);
}

TEST(ZforceSensor, ABusErrorLosesOneReport) {
  ZforceRig rig;
  rig.configure();
  const std::vector<SensorSample> trace = stroke(100000, 10);
  rig.model.load_trace(trace);
  std::vector<SensorSample> got = rig.run(100000, trace[3].t_us + 500);
  rig.bus.fail_next(1, BusStatus::Timeout);
  const std::vector<SensorSample> rest = rig.run(trace[4].t_us + 100, trace.back().t_us + 1000);
  got.insert(got.end(), rest.begin(), rest.end());
  std::vector<SensorSample> want = trace;
  want.erase(want.begin() + 4);
  expect_samples(got, want);
  EXPECT_EQ(rig.sensor.count(ZforceCount::BusError), 1u);
}

TEST(ZforceSensor, ABusErrorWhileDrainingIsCountedToo) {
  ZforceRig rig;
  rig.configure();
  const std::vector<SensorSample> trace = stroke(100000, 10);
  rig.model.load_trace(trace);
  std::vector<SensorSample> got = rig.run(100000, trace[3].t_us + 500);
  rig.bus.fail_next(2, BusStatus::Timeout);  // the header read, then the drain's first byte
  const std::vector<SensorSample> rest = rig.run(trace[4].t_us + 100, trace.back().t_us + 1000);
  got.insert(got.end(), rest.begin(), rest.end());
  // The drain stops at its failed read; neither failed read took a byte, so
  // the next poll reads the report whole (its DR edge was taken: the poll's time).
  ASSERT_EQ(got.size(), trace.size());
  EXPECT_EQ(got[4].x, trace[4].x);
  EXPECT_EQ(rig.sensor.count(ZforceCount::BusError), 2u);
  EXPECT_EQ(rig.sensor.count(ZforceCount::ResyncBytes), 0u);
}

TEST(ZforceSensor, AFailedPayloadReadIsCountedAndTheRestDrained) {
  const std::vector<I2cTransaction> script = {
      expect_read(0x50, {0xEE, 0x0F}),                                    // a good header
      expect_read(0x50, std::vector<uint8_t>(15, 0), BusStatus::Timeout),  // its payload lost
      expect_read(0x50, {0x40}),                                          // drained while DR stays up
  };
  MockI2cInitiator bus(script);
  struct OneMessageDr final : DataReadyInput {  // up for the three reads, one rising edge
    const MockI2cInitiator& bus;
    bool edge = true;
    explicit OneMessageDr(const MockI2cInitiator& b) : bus(b) {}
    bool asserted() const override { return bus.used() < 3; }
    bool take_edge(uint32_t& t_us, uint32_t& edges) override {
      t_us = 500;
      edges = 1;
      return std::exchange(edge, false);
    }
  } dr(bus);
  ZforceSensor sensor(bus, dr);
  sensor.begin(0);
  SensorSample s;
  EXPECT_FALSE(sensor.poll(1000, s));
  std::string why;
  EXPECT_TRUE(bus.finished(&why)) << why;
  EXPECT_EQ(sensor.count(ZforceCount::BusError), 1u);
  EXPECT_EQ(sensor.count(ZforceCount::ResyncBytes), 1u);
  EXPECT_EQ(sensor.count(ZforceCount::FramesRead), 0u);
}

TEST(ZforceSensor, AFailedReadWhileSkippingAnOverlongFrameIsCounted) {
  const std::vector<I2cTransaction> script = {
      expect_read(0x50, {0xEE, 200}),                                      // 200 bytes announced: over 128
      expect_read(0x50, std::vector<uint8_t>(128, 0), BusStatus::Timeout),  // skipping them fails at once
  };
  MockI2cInitiator bus(script);
  ScriptDr dr(script, bus);
  dr.gate = 2;
  ZforceSensor sensor(bus, dr);
  sensor.begin(0);
  SensorSample s;
  EXPECT_FALSE(sensor.poll(1000, s));
  std::string why;
  EXPECT_TRUE(bus.finished(&why)) << why;
  EXPECT_EQ(sensor.count(ZforceCount::LengthOverMax), 1u);
  EXPECT_EQ(sensor.count(ZforceCount::BusError), 1u);
  EXPECT_EQ(sensor.count(ZforceCount::ResyncBytes), 0u);  // nothing skipped: the rest is left to DR
}

TEST(ZforceSensor, ALostDownIsRecoveredFromTheMoves) {
  ZforceRig rig;
  rig.configure();
  const std::vector<SensorSample> trace = stroke(100000, 10);
  rig.model.load_trace(trace);
  rig.model.corrupt_frame_at(trace[0].t_us, Fault::BadHeader);
  const std::vector<SensorSample> got = rig.run(100000, trace.back().t_us + 1000);
  expect_samples(got, std::vector<SensorSample>(trace.begin() + 1, trace.end()));
  EXPECT_EQ(rig.sensor.count(ZforceCount::ResumedWithoutDown), 1u);
}

TEST(ZforceSensor, ASilentFingerIsForgottenAndTheNextOneTracked) {
  ZforceRig rig;
  rig.configure();
  std::vector<SensorSample> trace = stroke(100000, 5);  // no up: its frame was lost
  rig.model.load_trace(trace);
  rig.run(100000, 130000);
  EXPECT_TRUE(rig.sensor.finger_present());
  rig.run(130500, 350000);
  EXPECT_FALSE(rig.sensor.finger_present());
  EXPECT_EQ(rig.sensor.count(ZforceCount::TrackLost), 1u);
}

TEST(ZforceSensor, GhostReportsOfTheTrackedFingerGiveNoSample) {
  ZforceRig rig;
  rig.configure();
  rig.model.load_trace(stroke(100000, 2));
  const uint8_t id = 0, ghost = 4;
  const uint32_t x = 800, y = 800;
  rig.model.schedule_raw(107500, rig.model.touch_frame(&id, &ghost, &x, &y, 1, 107500));
  const std::vector<SensorSample> got = rig.run(100000, 110000);
  EXPECT_EQ(got.size(), 2u);
  EXPECT_EQ(rig.sensor.count(ZforceCount::GhostOrInvalid), 1u);
}

TEST(ZforceSensor, LearnsTheSensorsTouchFormat) {
  ZforceModel::Options o;
  o.format.fields = 0xFF;  // id, event, x and y in three bytes each, nothing else
  ZforceRig rig(ZforceConfig(), o);
  rig.configure();
  EXPECT_EQ(rig.sensor.format().bytes(), 8);
  const std::vector<SensorSample> trace = stroke(100000, 10);
  rig.model.load_trace(trace);
  expect_samples(rig.run(100000, trace.back().t_us + 1000), trace);
  EXPECT_EQ(rig.sensor.errors(), 0u);
}

TEST(ZforceSensor, TakesEitherTimestampLayoutAndCountsWhichItSaw) {
  for (const bool inside : {false, true}) {
    ZforceModel::Options o;
    o.timestamp_inside = inside;
    ZforceRig rig(ZforceConfig(), o);
    rig.configure();
    const std::vector<SensorSample> trace = stroke(100000, 10);
    rig.model.load_trace(trace);
    expect_samples(rig.run(100000, trace.back().t_us + 1000), trace);
    EXPECT_EQ(rig.sensor.errors(), 0u);
    EXPECT_EQ(rig.sensor.count(ZforceCount::TimestampInside), inside ? trace.size() : 0u);
    EXPECT_EQ(rig.sensor.count(ZforceCount::TimestampBeside), inside ? 0u : trace.size());
  }
}

TEST(ZforceSensor, RetriesThenGivesUpOnASilentSensor) {
  ZforceModel::Options o;
  o.answer_requests = false;
  ZforceRig rig(ZforceConfig(), o);
  rig.configure();
  EXPECT_EQ(rig.sensor.state(), ZforceState::Failed);
  EXPECT_EQ(rig.sensor.count(ZforceCount::ConfigRetry), 2u);
  EXPECT_EQ(rig.model.requests(), 3u);
  rig.configure(3000000);  // begun again, as the firmware does: three attempts again
  EXPECT_EQ(rig.sensor.state(), ZforceState::Failed);
  EXPECT_EQ(rig.sensor.count(ZforceCount::ConfigRetry), 4u);
  EXPECT_EQ(rig.model.requests(), 6u);
}

// A sensor that holds DR while no read reaches it (a wedged sensor, a
// shorted line, SDA stuck): nothing can be sent, since DR says a message
// waits. Each request held back that long counts as an unanswered attempt,
// so the driver fails as it would for a silent sensor, and the firmware
// restarts it, instead of configuring for ever.
TEST(ZforceSensor, GivesUpWhenDrStaysUpAndNoReadGetsThrough) {
  struct StuckDr final : DataReadyInput {
    bool asserted() const override { return true; }
    bool take_edge(uint32_t&, uint32_t&) override { return false; }
  } dr;
  struct DeadBus final : I2cInitiator {
    int writes = 0;
    BusStatus do_write_read(uint8_t, const uint8_t*, size_t tx_len, uint8_t*, size_t, uint32_t) override {
      if (tx_len > 0) ++writes;
      return BusStatus::Timeout;
    }
  } bus;
  const ZforceConfig config;  // boot wait 300 ms, then 3 attempts of 100 ms each
  ZforceSensor sensor(bus, dr, config);
  sensor.begin(0);
  SensorSample s;
  uint32_t failed_at = 0;
  for (uint32_t t = 0; t <= 2000000 && failed_at == 0; t += 1000) {
    EXPECT_FALSE(sensor.poll(t, s));
    if (sensor.state() == ZforceState::Failed) failed_at = t;
  }
  EXPECT_EQ(failed_at, config.boot_wait_us + 3 * config.response_timeout_us);
  EXPECT_EQ(sensor.count(ZforceCount::ConfigRetry), 2u);
  EXPECT_GT(sensor.count(ZforceCount::BusError), 0u);
  EXPECT_EQ(bus.writes, 0);
}

TEST(ZforceSensor, ConfiguresAgainAfterTheSensorReboots) {
  ZforceRig rig;
  rig.configure();
  ASSERT_EQ(rig.model.requests(), 6u);
  rig.model.schedule_raw(50000, boot_frame());
  rig.run(50000, 80000, 1000);
  EXPECT_EQ(rig.sensor.count(ZforceCount::SensorRebooted), 1u);
  EXPECT_EQ(rig.sensor.state(), ZforceState::Running);
  EXPECT_EQ(rig.model.requests(), 12u);
}

TEST(ZforceSensor, ARebootForgetsTheTrackedFinger) {
  // The sensor restarts mid-stroke: its numbering starts afresh, so the
  // finger's next move is one whose down was lost, not the old track.
  ZforceRig rig;
  rig.configure();
  const std::vector<SensorSample> trace = stroke(100000, 10);
  rig.model.load_trace(trace);
  rig.model.schedule_raw(trace[4].t_us + 1000, boot_frame());
  const std::vector<SensorSample> got = rig.run(100000, trace.back().t_us + 1000);
  EXPECT_EQ(got.size(), trace.size());
  EXPECT_EQ(rig.sensor.count(ZforceCount::SensorRebooted), 1u);
  EXPECT_EQ(rig.sensor.count(ZforceCount::ResumedWithoutDown), 1u);
}

TEST(ZforceSensor, MessagesQueuedBehindARebootDelayTheFirstRequestWithoutARetry) {
  ZforceRig rig;
  rig.configure();
  ASSERT_EQ(rig.model.requests(), 6u);
  for (int i = 0; i < 6; ++i) {  // six boot notifications at once: more than a poll reads
    rig.model.schedule_raw(500000, boot_frame());
  }
  rig.run(500000, 530000, 1000);  // long after the last answer's deadline
  EXPECT_EQ(rig.sensor.count(ZforceCount::ConfigRetry), 0u);
  EXPECT_EQ(rig.sensor.state(), ZforceState::Running);
  EXPECT_EQ(rig.model.requests(), 12u);
}

TEST(ZforceSensor, BeginningAgainMidwayConfiguresFromTheFirstStep) {
  // As the firmware does after a failure: begin() again, whichever step the
  // configuration had reached, sends all six requests again.
  ZforceRig rig;
  rig.sensor.begin(0);
  uint32_t t = 0;
  while (rig.model.requests() < 4 && t < 2000000) {  // three steps answered, the fourth asked
    t += 1000;
    rig.model.advance_to(t);
    SensorSample s;
    while (rig.sensor.poll(t, s)) {
    }
  }
  ASSERT_EQ(rig.model.requests(), 4u);
  rig.configure(t + 1000);
  EXPECT_EQ(rig.sensor.state(), ZforceState::Running);
  EXPECT_EQ(rig.model.requests(), 4u + 6u);
  EXPECT_EQ(rig.sensor.count(ZforceCount::ConfigRetry), 0u);  // the unanswered fourth is forgotten, not retried
}

TEST(ZforceSensor, BeginningAgainForgetsTheFinger) {
  // A restart in the middle of a stroke: the driver knows no finger after it,
  // so the finger's next move is taken up as one whose down was lost.
  ZforceRig rig;
  rig.configure();
  rig.model.load_trace(stroke(100000, 200));  // 1 s
  rig.run(100000, 200000);
  ASSERT_TRUE(rig.sensor.finger_present());
  const uint32_t running = rig.configure(200500);
  ASSERT_EQ(rig.sensor.state(), ZforceState::Running);
  const std::vector<SensorSample> after = rig.run(running + 500, 1100000);
  ASSERT_FALSE(after.empty());
  EXPECT_EQ(rig.sensor.count(ZforceCount::ResumedWithoutDown), 1u);
}

TEST(ZforceSensor, BeginningAgainForgetsWhichFingersWereIgnored) {
  // A second finger lands while the first is tracked and is ignored; it stays
  // when the first lifts, still ignored. After a restart the driver knows of
  // no finger: the second's next move is taken up.
  ZforceRig rig;
  rig.configure();
  std::vector<SensorSample> trace = stroke(100000, 40);  // to 0.3 s
  trace.push_back({305000, 0.0f, 0.0f, false});
  for (uint32_t t = 310000; t <= 1200000; t += 5000) trace.push_back({t, 0.0f, 0.0f, false});  // the second alone
  ZforceModel::SecondFinger second;
  second.from_us = 150000;
  second.to_us = 1200000;
  rig.model.load_trace(trace, &second);
  EXPECT_EQ(rig.run(100000, 400000).size(), 41u);  // the first finger's reports and its lift: nothing else
  const uint32_t running = rig.configure(400500);
  ASSERT_EQ(rig.sensor.state(), ZforceState::Running);
  const std::vector<SensorSample> after = rig.run(running + 500, 1100000);
  ASSERT_FALSE(after.empty());
  EXPECT_EQ(after.back().x, 400.0f);
  EXPECT_EQ(after.back().y, 100.0f);
}

TEST(ZforceSensor, BeginningAgainForgetsAnEdgeKeptFromADrain) {
  // Four wrong headers in one poll: each drain meets the next message's DR
  // edge and keeps it, and the poll ends with the fourth's edge kept. Then the
  // sensor is reset and begin() called: that message is gone, so the next
  // message is dated by its own edge, not by the kept one.
  const ZforceModel model;
  const uint8_t id = 0, down = 0;
  const uint32_t x = 800, y = 800;
  const std::vector<uint8_t> touch = model.touch_frame(&id, &down, &x, &y, 1, 0);
  std::vector<I2cTransaction> script(4, expect_read(0x50, {0x00, 0x05}));
  script.push_back(expect_read(0x50, {touch[0], touch[1]}));
  script.push_back(expect_read(0x50, std::vector<uint8_t>(touch.begin() + 2, touch.end())));
  MockI2cInitiator bus(script);
  struct EdgeListDr final : DataReadyInput {
    bool up = true;
    std::vector<uint32_t> edges = {100, 200, 300, 400, 500};
    size_t next = 0;
    bool asserted() const override { return up; }
    bool take_edge(uint32_t& t_us, uint32_t& n) override {
      if (!up || next == edges.size()) return false;
      t_us = edges[next++];
      n = 1;
      return true;
    }
  } dr;
  ZforceSensor sensor(bus, dr);
  sensor.begin(0);
  SensorSample s;
  EXPECT_FALSE(sensor.poll(1000, s));
  ASSERT_EQ(sensor.count(ZforceCount::WrongHeader), 4u);
  ASSERT_EQ(dr.next, 5u);  // the fifth edge taken by the fourth drain, kept
  dr.up = false;           // the reset: the fifth message is gone
  sensor.begin(2000);
  EXPECT_FALSE(sensor.poll(2500, s));
  dr.up = true;  // the next message, with its own edge
  dr.edges.push_back(3000);
  ASSERT_TRUE(sensor.poll(3500, s));
  EXPECT_EQ(s.t_us, 3000u);
  std::string why;
  EXPECT_TRUE(bus.finished(&why)) << why;
}

TEST(ZforceSensor, AConfigOfZeroesIsMadeUsable) {
  ZforceConfig c;
  c.resolution_x = 0;
  c.resolution_y = 0;
  c.max_attempts = 0;
  c.calibration = ScreenCalibration{};
  ZforceRig rig(c);
  EXPECT_EQ(rig.sensor.config().resolution_x, 1u);
  EXPECT_EQ(rig.sensor.config().resolution_y, 1u);
  EXPECT_EQ(rig.sensor.config().max_attempts, 1u);
  EXPECT_TRUE(rig.sensor.config().calibration.valid());
}

TEST(ZforceSensor, CalibrationFlipsSwapsAndOffsetsByHand) {
  // The sensor reports (400, 400) units for a finger at (100, 100) px.
  const std::vector<SensorSample> at{{100000, 100.0f, 100.0f, true}};
  const ScreenCalibration plain = ScreenCalibration::fit(3200, 1920);
  auto sample_with = [&](const ScreenCalibration& c) {
    ZforceConfig cfg;
    cfg.calibration = c;
    ZforceRig rig(cfg, ZforceModel::Options(), &plain);
    rig.configure();
    rig.model.load_trace(at);
    const std::vector<SensorSample> got = rig.run(100000, 101000);
    EXPECT_EQ(got.size(), 1u);
    return got.empty() ? SensorSample{} : got[0];
  };
  ScreenCalibration c = plain;
  c.flip_x = true;
  c.flip_y = true;
  SensorSample s = sample_with(c);
  EXPECT_EQ(s.x, 700.0f);  // 0.25 * (3200 - 400)
  EXPECT_EQ(s.y, 380.0f);  // 0.25 * (1920 - 400)
  c = plain;
  c.offset_x = 10.0f;
  c.offset_y = -4.0f;
  c.scale_x = 0.2f;
  s = sample_with(c);
  EXPECT_FLOAT_EQ(s.x, 90.0f);  // 10 + 0.2 * 400
  EXPECT_EQ(s.y, 96.0f);        // -4 + 0.25 * 400
  c = ScreenCalibration::fit(1920, 3200);  // sensor mounted along the side
  c.swap_xy = true;
  s = sample_with(c);
  EXPECT_FLOAT_EQ(s.x, 400.0f * 800.0f / 1920.0f);
  EXPECT_FLOAT_EQ(s.y, 400.0f * 480.0f / 3200.0f);
}

TEST(ScreenCalibration, FitValidityAndRepair) {
  const ScreenCalibration c = ScreenCalibration::fit(3200, 1920);
  EXPECT_EQ(c.scale_x, 0.25f);
  EXPECT_EQ(c.scale_y, 0.25f);
  EXPECT_TRUE(c.valid());
  ScreenCalibration bad = c;
  bad.scale_x = std::numeric_limits<float>::quiet_NaN();
  EXPECT_FALSE(bad.valid());
  ZforceConfig cfg;
  cfg.calibration = bad;
  ZforceRig rig(cfg, ZforceModel::Options(), &c);
  rig.configure();
  rig.model.load_trace({{100000, 100.0f, 100.0f, true}});
  const std::vector<SensorSample> got = rig.run(100000, 101000);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].x, 100.0f);  // replaced by the fit to the resolution
}

TEST(ZforceCount, HasNames) {
  EXPECT_STREQ(to_string(ZforceCount::OtherFingerIgnored), "other finger ignored");
  EXPECT_STREQ(to_string(ZforceCount::TrackLost), "track lost");
}

}  // namespace
}  // namespace ff
