// The 2 kHz tick end to end: scenes switch atomically, idle without a finger,
// only what the scene needs is computed, and the replay-output identity (docs/spec.md#replay-output) holds.
#include "frictionfield/core/haptic_pipeline.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <memory>
#include <vector>

#include "frictionfield/core/min_jerk.hpp"
#include "frictionfield/core/scenes.hpp"
#include "support/random.hpp"

namespace ff {
namespace {

Condition condition(const SceneDefinition& s, float strength = 1.0f) {
  Condition c;
  c.scene = s;
  c.amplitude.strength = strength;
  return c;
}

// A finger moving right along y = 240 at 300 px/s, 200 Hz samples.
void stroke(HapticPipeline& p, uint32_t from_us, int ticks, std::vector<TickOutput>* out = nullptr) {
  for (int k = 0; k < ticks; ++k) {
    const uint32_t now = from_us + static_cast<uint32_t>(k) * kTickPeriodUs;
    if (now % 5000 == 0) p.post_sample({now, 100.0f + 300.0f * static_cast<float>(now) * 1e-6f, 240.0f, true});
    const TickOutput t = p.tick(now);
    if (out) out->push_back(t);
  }
}

TEST(HapticPipeline, BootsIdleWithThePlateResting) {
  auto p = std::make_unique<HapticPipeline>();
  const TickOutput t = p->tick(0);
  EXPECT_FALSE(t.present);
  EXPECT_EQ(t.amplitude, 0.0f);
  EXPECT_EQ(t.dac, 0);
}

// Before any condition a default slot is the boot condition, prepared by
// nothing: the neutral scene at full strength, A = 0.5, code
// round(0.5 * 4095) = 2048, no tracking; the plate rests without a finger.
TEST(HapticPipeline, BeforeAnyConditionAFingerFeelsTheNeutralScene) {
  auto p = std::make_unique<HapticPipeline>();
  EXPECT_EQ(p->plan().needs(), Needs::Nothing);
  std::vector<TickOutput> out;
  stroke(*p, 0, 100, &out);
  ASSERT_TRUE(out.back().present);
  EXPECT_EQ(out.back().amplitude, 0.5f);
  EXPECT_EQ(out.back().dac, 2048);
  EXPECT_EQ(out.back().direction.x, 0.0f);
  EXPECT_EQ(out.back().direction.y, 0.0f);
  EXPECT_EQ(p->amplitude_map().idle_code(), 0);
}

TEST(HapticPipeline, OutputObeysTheSpecIdentity) {
  // amplitude = 0.5 - s (vx, vy) . G_norm and dac = calibration(amplitude).
  auto p = std::make_unique<HapticPipeline>();
  ASSERT_EQ(p->set_condition(condition(scenes::heightmap(Target::Top), 0.66f)), PrepareStatus::Ok);
  std::vector<TickOutput> out;
  stroke(*p, 0, 400, &out);
  const TickOutput& t = out.back();
  ASSERT_TRUE(t.present);
  EXPECT_NEAR(static_cast<double>(length(t.direction)), 1.0, 1e-5);
  const Vec2 g = p->plan().normalized_gradient(t.position);
  EXPECT_NEAR(static_cast<double>(t.amplitude), 0.5 - 0.66 * static_cast<double>(dot(t.direction, g)), 1e-6);
  EXPECT_EQ(t.dac, static_cast<uint16_t>(static_cast<double>(t.amplitude) * 4095.0 + 0.5));
}

// The 2 kHz interrupt can fire at any instruction of the main loop, also
// while set_condition() prepares. The pipeline's clock hook is called inside
// set_condition() (before and after preparation, before the swap): it stands
// in for the interrupt and runs a tick there.
struct InterruptDuringPreparation {
  static HapticPipeline* pipeline;
  static uint32_t now_us;
  static std::vector<TickOutput> ticks;
  static std::vector<Needs> rendered_needs;
  static uint32_t micros() {
    now_us += kTickPeriodUs;
    pipeline->post_sample({now_us, 400.0f, 240.0f, true});
    ticks.push_back(pipeline->tick(now_us));
    rendered_needs.push_back(pipeline->plan().needs());
    return now_us;
  }
};
HapticPipeline* InterruptDuringPreparation::pipeline = nullptr;
uint32_t InterruptDuringPreparation::now_us = 0;
std::vector<TickOutput> InterruptDuringPreparation::ticks;
std::vector<Needs> InterruptDuringPreparation::rendered_needs;

TEST(HapticPipeline, TickDuringPreparationRendersTheOldSceneWhole) {
  using I = InterruptDuringPreparation;
  auto p = std::make_unique<HapticPipeline>();
  I::pipeline = p.get();
  // Old scene: the frictionmap at half strength. A finger on the middle path
  // (|u| = 0) gives A = 1, so A_s = 0.5 + 0.5 (1 - 0.5) = 0.75, code
  // round(0.75 * 4095) = 3071.
  ASSERT_EQ(p->set_condition(condition(scenes::frictionmap(Target::Middle), 0.5f)), PrepareStatus::Ok);
  for (int k = 0; k < 40; ++k) I::micros();  // the finger settles on the path
  ASSERT_TRUE(I::ticks.back().present);
  ASSERT_EQ(I::ticks.back().dac, 3071);
  I::ticks.clear();
  I::rendered_needs.clear();
  // New scene: constant 0.25 at full strength, code round(0.25 * 4095) = 1024.
  SceneDefinition next = scenes::neutral();
  next.constant = 0.25f;
  p->set_clock(&I::micros);
  ASSERT_EQ(p->set_condition(condition(next)), PrepareStatus::Ok);
  p->set_clock(nullptr);
  ASSERT_GE(I::ticks.size(), 2u);  // before and after preparation
  for (size_t k = 0; k < I::ticks.size(); ++k) {
    EXPECT_EQ(I::rendered_needs[k], Needs::Position) << k;  // the slot being rendered was not written
    EXPECT_FLOAT_EQ(I::ticks[k].amplitude, 0.75f) << k;    // the old scene, whole
    EXPECT_EQ(I::ticks[k].dac, 3071) << k;
  }
  const TickOutput after = p->tick(I::now_us + kTickPeriodUs);  // the first tick after the swap
  EXPECT_EQ(p->plan().needs(), Needs::Nothing);
  EXPECT_FLOAT_EQ(after.amplitude, 0.25f);
  EXPECT_EQ(after.dac, 1024);
}

TEST(HapticPipeline, NeutralNeedsNoTrackingAndRendersHalf) {
  auto p = std::make_unique<HapticPipeline>();
  ASSERT_EQ(p->set_condition(condition(scenes::neutral())), PrepareStatus::Ok);
  std::vector<TickOutput> out;
  stroke(*p, 0, 100, &out);
  EXPECT_EQ(out.back().amplitude, 0.5f);
  EXPECT_EQ(out.back().dac, 2048);
  EXPECT_EQ(out.back().direction.x, 0.0f);
  // Reported position is the last sample's: 100 + 300 * 0.045.
  EXPECT_FLOAT_EQ(out.back().position.x, 113.5f);
}

TEST(HapticPipeline, SwitchesScenesBetweenTicksAndRefusesBadOnes) {
  auto p = std::make_unique<HapticPipeline>();
  ASSERT_EQ(p->set_condition(condition(scenes::frictionmap(Target::Middle))), PrepareStatus::Ok);
  std::vector<TickOutput> out;
  stroke(*p, 0, 200, &out);
  EXPECT_FLOAT_EQ(out.back().amplitude, 1.0f);  // on the path
  SceneDefinition bad = scenes::heightmap(Target::Top);
  bad.elements[0].weight = NAN;
  EXPECT_EQ(p->set_condition(condition(bad)), PrepareStatus::InvalidParameter);
  out.clear();
  stroke(*p, 100000, 1, &out);
  EXPECT_FLOAT_EQ(out.back().amplitude, 1.0f);  // still the frictionmap
  ASSERT_EQ(p->set_condition(condition(scenes::neutral())), PrepareStatus::Ok);
  out.clear();
  stroke(*p, 100500, 1, &out);
  EXPECT_FLOAT_EQ(out.back().amplitude, 0.5f);  // the very next tick
}

TEST(HapticPipeline, SwitchingToADirectionalSceneRestartsTheFilterCleanly) {
  auto p = std::make_unique<HapticPipeline>();
  ASSERT_EQ(p->set_condition(condition(scenes::neutral())), PrepareStatus::Ok);
  stroke(*p, 0, 200);
  ASSERT_EQ(p->set_condition(condition(scenes::heightmap(Target::Middle))), PrepareStatus::Ok);
  std::vector<TickOutput> out;
  stroke(*p, 100000, 400, &out);
  for (const TickOutput& t : out) {
    EXPECT_TRUE(std::isfinite(t.amplitude));
    EXPECT_LE(length(t.direction), 1.0f + 1e-6f);
  }
  EXPECT_GT(out.back().amplitude, 0.5f);  // moving right towards the middle target: assisted
}

TEST(HapticPipeline, MailboxOverflowIsCounted) {
  auto p = std::make_unique<HapticPipeline>();
  for (uint32_t i = 0; i < SampleMailbox::kCapacity + 3; ++i) p->post_sample({i * 10u, 100, 100, true});
  EXPECT_EQ(p->faults()[Fault::MailboxOverflow], 3u);
  p->tick(1000);
  EXPECT_TRUE(p->post_sample({2000, 100, 100, true}));
}

TEST(HapticPipeline, ABurstOfReportsIsTakenOnePerTickInOrder) {
  // Bounded work per tick: three reports waiting at one tick are taken by
  // that tick and the next two, oldest first. The neutral scene renders the
  // last taken report's position, so each tick shows which one it took.
  auto p = std::make_unique<HapticPipeline>();
  const float xs[] = {100.0f, 101.0f, 102.5f};
  for (uint32_t i = 0; i < 3; ++i) ASSERT_TRUE(p->post_sample({1000 + i * 100u, xs[i], 240.0f, true}));
  for (uint32_t k = 0; k < 3; ++k) {
    const TickOutput t = p->tick(1500 + k * kTickPeriodUs);
    EXPECT_EQ(p->samples_taken(), k + 1);
    ASSERT_TRUE(t.present);
    EXPECT_EQ(t.position.x, xs[k]);
  }
  const TickOutput idle = p->tick(1500 + 3 * kTickPeriodUs);  // nothing left: the last report stays
  EXPECT_EQ(p->samples_taken(), 3u);
  EXPECT_EQ(idle.position.x, xs[2]);
  EXPECT_EQ(p->faults().total(), 1u);  // the touch-down; no report was dropped
  EXPECT_EQ(p->faults()[Fault::TouchDown], 1u);
}

TEST(HapticPipeline, BadStrengthIsCountedAndRepaired) {
  auto p = std::make_unique<HapticPipeline>();
  ASSERT_EQ(p->set_condition(condition(scenes::heightmap(Target::Top), NAN)), PrepareStatus::Ok);
  EXPECT_EQ(p->faults()[Fault::BadStrength], 1u);
  std::vector<TickOutput> out;
  stroke(*p, 0, 200, &out);
  EXPECT_FLOAT_EQ(out.back().amplitude, 0.5f);
}

SensorProfile measured() { return {1.5f, 0.5f, 250.0f, 0.25f, 180.0f, 400.0f, 3000u, 9.5f}; }

// The fade's noise is derived in the loop with the configuration, the tick
// only takes it over: the pipeline renders a noisy stroke with the same
// direction, tick for tick, as a tracker built from the profile directly.
TEST(HapticPipeline, AProfilesTrackerFadesAsOneBuiltFromIt) {
  auto p = std::make_unique<HapticPipeline>();
  ASSERT_EQ(p->set_condition(condition(scenes::heightmap(Target::Top))), PrepareStatus::Ok);
  ASSERT_TRUE(p->set_sensor_profile(measured()));
  Tracker alone(TrackerConfig::recommended(measured()));
  support::Random rng(3, support::Stream::Noise);
  int differ = 0, shown = 0;
  for (uint32_t k = 0; k < 2000; ++k) {
    const uint32_t now = k * kTickPeriodUs;
    if (k % 10 == 0) {  // 200 Hz: 0.3 s at rest, a 300 px stroke in 0.4 s, at rest again
      const double t = static_cast<double>(now) * 1e-6;
      const SensorSample s{now, static_cast<float>(100.0 + 300.0 * min_jerk((t - 0.3) / 0.4) + 1.5 * rng.gaussian()),
                           static_cast<float>(240.0 + 1.5 * rng.gaussian()), true};
      ASSERT_TRUE(p->post_sample(s));
      alone.on_sample(s);
    }
    const TickOutput out = p->tick(now);
    const TrackState& expected = alone.on_tick(now);
    if (out.direction.x != expected.direction.x || out.direction.y != expected.direction.y) ++differ;
    if (length(expected.direction) > 0.0f && length(expected.direction) < 1.0f) ++shown;  // partly faded
  }
  EXPECT_EQ(differ, 0);
  EXPECT_GT(shown, 20);  // the fade's noise decided something
}

TEST(HapticPipeline, ASensorProfileReachesTheTrackerAtTheStartOfTheNextTick) {
  auto p = std::make_unique<HapticPipeline>();
  EXPECT_EQ(p->tracker().config().sensor, SensorProfile{});  // start-up: the default profile
  stroke(*p, 0, 100);  // a finger is tracked
  ASSERT_TRUE(p->tracker().state().present);
  ASSERT_EQ(p->faults()[Fault::TouchDown], 1u);

  ASSERT_TRUE(p->set_sensor_profile(measured()));
  // Handed over, not applied: the loop never touches the tick's tracker.
  EXPECT_EQ(p->tracker_config().sensor, measured());
  EXPECT_EQ(p->tracker().config().sensor, SensorProfile{});
  EXPECT_TRUE(p->tracker().state().present);

  // The next tick takes a report: configured first, so that report is the
  // new tracker's first (a touch-down) and the finger is tracked at once.
  const uint32_t next = 100 * kTickPeriodUs;
  ASSERT_EQ(next % 5000, 0u);
  std::vector<TickOutput> out;
  stroke(*p, next, 1, &out);
  EXPECT_EQ(p->tracker().config().sensor, measured());
  EXPECT_TRUE(out[0].present);
  EXPECT_EQ(p->faults()[Fault::TouchDown], 2u);
  // Configured once: later ticks keep the finger (no further touch-down).
  stroke(*p, next + kTickPeriodUs, 40, &out);
  EXPECT_TRUE(out.back().present);
  EXPECT_EQ(p->faults()[Fault::TouchDown], 2u);
}

TEST(HapticPipeline, WithoutAReportAtTheChangeTheFingerIsFoundAgainAtTheNext) {
  auto p = std::make_unique<HapticPipeline>();
  stroke(*p, 0, 100);
  ASSERT_TRUE(p->set_sensor_profile(measured()));
  // Ticks 50.0 .. 54.5 ms: no report until 55 ms. The new tracker has none yet: idle.
  std::vector<TickOutput> out;
  stroke(*p, 100 * kTickPeriodUs + kTickPeriodUs, 9, &out);
  for (const TickOutput& t : out) {
    EXPECT_FALSE(t.present) << &t - out.data();
    EXPECT_EQ(t.dac, 0);  // the plate rests
  }
  stroke(*p, 110 * kTickPeriodUs, 1, &out);  // 55 ms: the next report
  EXPECT_TRUE(out.back().present);
}

// A new profile reconfigures the tracker, but the clock runs on: the first
// report after the change is judged by the tick clock like any other. One
// stamped 1 s ahead is dropped; taken as the new touch-down, it would make
// every report for the next second look older and freeze the finger.
TEST(HapticPipeline, TheFirstReportAfterAProfileChangeIsJudgedByTheTickClock) {
  auto p = std::make_unique<HapticPipeline>();  // the neutral scene: the output is at the last report
  // At rest at x = 100 until 50 ms, then right at 0.625 px/ms to rest at 700 from 1010 ms.
  auto x_at = [](uint32_t t_us) {
    if (t_us <= 50000) return 100.0f;
    if (t_us >= 1010000) return 700.0f;
    return 100.0f + 0.000625f * static_cast<float>(t_us - 50000);
  };
  TickOutput out;
  for (uint32_t now = 0; now <= 1030000; now += kTickPeriodUs) {
    if (now == 50000) {
      ASSERT_TRUE(p->set_sensor_profile(measured()));
      ASSERT_TRUE(p->post_sample({now + 1000000, 100.0f, 240.0f, true}));  // in place of the 50 ms report
    } else if (now % 5000 == 0) {
      ASSERT_TRUE(p->post_sample({now, x_at(now), 240.0f, true}));
    }
    out = p->tick(now);
  }
  EXPECT_EQ(p->tracker().config().sensor, measured());
  EXPECT_EQ(p->faults()[Fault::SampleTimeImplausible], 1u);
  EXPECT_EQ(p->faults()[Fault::NonIncreasingTime], 0u);
  ASSERT_TRUE(out.present);
  EXPECT_EQ(out.position.x, 700.0f);
}

TEST(HapticPipeline, TheLoopWritesTheSlotTheTickIsNotReading) {
  auto p = std::make_unique<HapticPipeline>();
  SensorProfile a = measured(), b = measured();
  b.white_noise_px = 2.0f;
  ASSERT_TRUE(p->set_sensor_profile(a));
  const TrackerConfig* named = &p->tracker_config();  // what a tick would read now
  ASSERT_TRUE(p->set_sensor_profile(b));
  // A tick landing anywhere inside that call read `named`: it still holds a, whole.
  EXPECT_EQ(named->sensor, a);
  EXPECT_NE(&p->tracker_config(), named);
  // Two profiles between ticks: the tick takes the last.
  p->tick(0);
  EXPECT_EQ(p->tracker().config().sensor, b);
}

TEST(HapticPipeline, AnInvalidSensorProfileIsRefusedCountedAndChangesNothing) {
  // Each one value past SensorProfileLimits (by hand from the header), the rest the default.
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  std::vector<SensorProfile> bad;
  auto with = [&](auto set) {
    SensorProfile s;
    set(s);
    bad.push_back(s);
  };
  with([&](SensorProfile& s) { s.white_noise_px = nan; });
  with([&](SensorProfile& s) { s.white_noise_px = -1.0f; });
  with([&](SensorProfile& s) { s.white_noise_px = 0.0f; });           // white noise must be above 0
  with([&](SensorProfile& s) { s.white_noise_px = 50.5f; });          // max 50 px
  with([&](SensorProfile& s) { s.correlated_noise_px = -0.1f; });
  with([&](SensorProfile& s) { s.correlated_noise_px = 2.0f; });      // a wander with tau 0
  with([&](SensorProfile& s) { s.correlation_time_ms = 10001.0f; });  // max 10 s
  with([&](SensorProfile& s) { s.tremor_px = inf; });
  with([&](SensorProfile& s) { s.report_rate_hz = 9.9f; });           // min 10 Hz
  with([&](SensorProfile& s) { s.report_rate_hz = 5001.0f; });        // max 5 kHz
  with([&](SensorProfile& s) { s.jitter_us = -1.0f; });
  with([&](SensorProfile& s) { s.jitter_us = 50001.0f; });            // max 50 ms
  with([&](SensorProfile& s) { s.latency_us = 50001u; });             // max 50 ms

  auto p = std::make_unique<HapticPipeline>();
  ASSERT_TRUE(p->set_sensor_profile(measured()));
  stroke(*p, 0, 100);
  ASSERT_TRUE(p->tracker().state().present);
  uint32_t expected = 0;
  for (const SensorProfile& s : bad) {
    EXPECT_FALSE(p->set_sensor_profile(s)) << &s - bad.data();
    EXPECT_EQ(p->faults()[Fault::BadSensorProfile], ++expected);
    EXPECT_EQ(p->tracker_config().sensor, measured());
  }
  std::vector<TickOutput> out;
  stroke(*p, 100 * kTickPeriodUs, 20, &out);
  EXPECT_EQ(p->tracker().config().sensor, measured());
  for (const TickOutput& t : out) EXPECT_TRUE(t.present) << &t - out.data();  // never reset: the finger stays
  EXPECT_EQ(p->faults()[Fault::TouchDown], 1u);

  // The edges themselves are in range.
  SensorProfile edge;
  edge.white_noise_px = 50.0f;
  edge.correlated_noise_px = 50.0f;
  edge.correlation_time_ms = 10000.0f;
  edge.report_rate_hz = 10.0f;
  edge.jitter_us = 50000.0f;
  edge.latency_us = 50000u;
  EXPECT_TRUE(p->set_sensor_profile(edge));
  edge.report_rate_hz = 5000.0f;
  edge.correlated_noise_px = 0.0f;
  edge.correlation_time_ms = 0.0f;  // no wander needs no time
  EXPECT_TRUE(p->set_sensor_profile(edge));
  EXPECT_EQ(p->faults()[Fault::BadSensorProfile], expected);
}

}  // namespace
}  // namespace ff
