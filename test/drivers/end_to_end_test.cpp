// The native chain end to end: a finger trace goes into the emulated zForce,
// out of it as I2C frames and DR edges, through the driver into the 2 kHz
// pipeline, and out as DAC codes through FSADJUST, with the AD9834 carrier
// configured over SPI. The DAC codes must equal, tick for tick, those of the
// replay feeding the same reports straight into a second pipeline.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "frictionfield/core/haptic_pipeline.hpp"
#include "frictionfield/core/scenes.hpp"
#include "frictionfield/drivers/ad9834.hpp"
#include "frictionfield/drivers/fsadjust_amplitude.hpp"
#include "frictionfield/emulated/ad9834_model.hpp"
#include "frictionfield/emulated/recording_dac.hpp"
#include "frictionfield/host/replay.hpp"
#include "frictionfield/host/trace_csv.hpp"
#include "zforce_rig.hpp"

namespace ff {
namespace {

using emulated::ZforceModel;
using host::TraceRow;

constexpr uint64_t kExtraTicks = 200;  // let lift-off and timeouts play out

// What the sensor can report: positions on its 0.25 px grid inside the
// screen, and only the first no-finger row after a touch (the up event; the
// sensor is silent while nothing touches).
std::vector<TraceRow> as_sensor_reports(const std::vector<TraceRow>& raw) {
  std::vector<TraceRow> out;
  bool down = false;
  float x = 0.0f, y = 0.0f;
  for (const TraceRow& r : raw) {
    if (r.touch) {
      x = std::round(std::fmin(std::fmax(r.x, 0.0f), 800.0f) * 4.0f) / 4.0f;
      y = std::round(std::fmin(std::fmax(r.y, 0.0f), 480.0f) * 4.0f) / 4.0f;
      out.push_back({r.t_us, x, y, true});
      down = true;
    } else if (down) {
      out.push_back({r.t_us, x, y, false});
      down = false;
    }
  }
  return out;
}

std::vector<SensorSample> as_samples(const std::vector<TraceRow>& rows) {
  std::vector<SensorSample> s;
  for (const TraceRow& r : rows) s.push_back({static_cast<uint32_t>(r.t_us), r.x, r.y, r.touch});
  return s;
}

// Two strokes and a rest, 200 Hz with +-300 us jitter, on the sensor grid,
// with redundant no-finger rows the sensor would never send.
std::vector<TraceRow> synthetic_trace() {
  std::vector<TraceRow> rows;
  uint32_t lcg = 12345;
  auto jitter = [&lcg]() {
    lcg = lcg * 1664525u + 1013904223u;
    return static_cast<int64_t>((lcg >> 8) % 601) - 300;
  };
  auto q = [](double v) { return static_cast<float>(std::round(v * 4.0) / 4.0); };
  uint64_t t = 5000000;
  auto stroke = [&](double x0, double y0, double x1, double y1, int n) {
    for (int i = 0; i < n; ++i) {
      const double u = static_cast<double>(i) / (n - 1);
      const double s = u * u * (3.0 - 2.0 * u);
      rows.push_back({static_cast<uint64_t>(static_cast<int64_t>(t) + jitter()), q(x0 + (x1 - x0) * s),
                      q(y0 + (y1 - y0) * s + 40.0 * std::sin(3.14159265358979 * u)), true});
      t += 5000;
    }
  };
  stroke(120.0, 240.0, 680.0, 300.0, 300);  // 1.5 s to the right, bowed downwards
  for (int i = 0; i < 3; ++i, t += 5000) rows.push_back({t, 0.0f, 0.0f, false});
  t += 400000;
  stroke(650.0, 200.0, 150.0, 260.0, 240);  // back, 1.2 s
  for (int i = 0; i < 60; ++i, t += 5000) {  // rest with quarter-pixel noise
    rows.push_back({t, q(150.0 + 0.25 * ((i * 7) % 3 - 1)), q(260.0 + 0.25 * ((i * 5) % 3 - 1)), true});
  }
  rows.push_back({t, 0.0f, 0.0f, false});
  return rows;
}

struct Result {
  std::vector<uint16_t> dac;          // through the emulated chain
  std::vector<uint16_t> reference;    // the replay
  std::vector<SensorSample> posted;   // what the driver handed the pipeline
  uint32_t zforce_errors = 0;
  uint32_t other_finger = 0;
  uint32_t dds_words = 0;
  bool carrier_on = false;
  uint32_t carrier_word = 0;
  uint32_t carrier_faults = 0;
};

struct ChainSetup {
  SceneDefinition scene = scenes::heightmap(Target::Middle);
  DacCalibration calibration = DacCalibration::linear();
  const ZforceModel::SecondFinger* second = nullptr;
  std::vector<std::pair<uint32_t, ZforceModel::Fault>> garbage;  // frames of their own
};

Result run_chain(const std::vector<TraceRow>& raw, const ChainSetup& setup) {
  Result result;
  const std::vector<TraceRow> reports = as_sensor_reports(raw);
  Condition condition;
  condition.scene = setup.scene;
  condition.amplitude.calibration = setup.calibration;

  // The replay: reports straight into a pipeline.
  auto reference = std::make_unique<HapticPipeline>();
  EXPECT_EQ(reference->set_condition(condition), PrepareStatus::Ok);
  host::replay(reports, *reference, [&](uint64_t, const TickOutput& out) { result.reference.push_back(out.dac); },
               kExtraTicks);

  // The device: carrier over SPI, sensor over I2C + DR, amplitude through the DAC.
  emulated::Ad9834Model carrier_chip;
  Ad9834 carrier(carrier_chip, 0);
  emulated::RecordingDac dac;
  FsAdjustAmplitude amplitude(dac, setup.calibration);
  ZforceModel::Options options;
  options.boot_complete = false;  // the sensor booted long ago; the driver configures it after its boot wait
  test::ZforceRig rig(ZforceConfig(), options);
  auto pipeline = std::make_unique<HapticPipeline>();
  EXPECT_EQ(pipeline->set_condition(condition), PrepareStatus::Ok);

  const uint64_t t0 = reports.front().t_us;
  EXPECT_EQ(carrier.start(34900), BusStatus::Ok);
  EXPECT_EQ(amplitude.write_code(pipeline->amplitude_map().idle_code()), BusStatus::Ok);
  rig.configure(static_cast<uint32_t>(t0 - 1000000));
  EXPECT_EQ(rig.sensor.state(), ZforceState::Running);
  rig.model.load_trace(as_samples(raw), setup.second);
  for (const auto& g : setup.garbage) rig.model.inject(g.first, g.second);
  dac.clear();

  uint64_t t_last = t0;
  for (const TraceRow& r : reports) t_last = std::max(t_last, r.t_us);
  const uint64_t ticks = (t_last - t0 + kTickPeriodUs - 1) / kTickPeriodUs + kExtraTicks;
  for (uint64_t k = 0; k <= ticks; ++k) {
    const uint32_t now = static_cast<uint32_t>(t0 + k * kTickPeriodUs);
    rig.model.advance_to(now);
    SensorSample s;
    while (rig.sensor.poll(now, s)) {  // main loop
      pipeline->post_sample(s);
      result.posted.push_back(s);
    }
    const TickOutput out = pipeline->tick(now);  // interrupt
    amplitude.write_code(out.dac);
  }
  result.dac = dac.codes();
  result.zforce_errors = rig.sensor.errors();
  result.other_finger = rig.sensor.count(ZforceCount::OtherFingerIgnored);
  result.dds_words = carrier_chip.words_accepted();
  result.carrier_on = carrier_chip.output_on();
  result.carrier_word = carrier_chip.output_word();
  result.carrier_faults = carrier_chip.total_faults();

  EXPECT_EQ(result.posted.size(), reports.size());
  for (size_t i = 0; i < std::min(result.posted.size(), reports.size()); ++i) {
    EXPECT_EQ(result.posted[i].t_us, static_cast<uint32_t>(reports[i].t_us)) << i;
    EXPECT_EQ(result.posted[i].touch, reports[i].touch) << i;
    EXPECT_EQ(result.posted[i].x, reports[i].x) << i;
    EXPECT_EQ(result.posted[i].y, reports[i].y) << i;
  }
  return result;
}

void expect_same_codes(const Result& r) {
  ASSERT_EQ(r.dac.size(), r.reference.size());
  size_t first_difference = r.dac.size();
  for (size_t k = 0; k < r.dac.size() && first_difference == r.dac.size(); ++k) {
    if (r.dac[k] != r.reference[k]) first_difference = k;
  }
  EXPECT_EQ(first_difference, r.dac.size()) << "tick " << first_difference << ": " << r.dac[first_difference]
                                            << " vs " << r.reference[first_difference];
}

void expect_carrier(const Result& r) {
  EXPECT_TRUE(r.carrier_on);
  EXPECT_EQ(r.carrier_word, 124912u);  // 34.9 kHz, rounded to nearest
  EXPECT_EQ(r.dds_words, 8u);          // start-up only: the tick never touches the DDS
  EXPECT_EQ(r.carrier_faults, 0u);
}

TEST(EndToEnd, SyntheticStrokesMatchTheReplayTickForTick) {
  const Result r = run_chain(synthetic_trace(), ChainSetup());
  expect_same_codes(r);
  expect_carrier(r);
  EXPECT_EQ(r.zforce_errors, 0u);
  // The chain did render something: codes span most of the range.
  uint16_t lo = 4095, hi = 0;
  for (uint16_t c : r.dac) {
    lo = std::min(lo, c);
    hi = std::max(hi, c);
  }
  EXPECT_LT(lo, 1500);
  EXPECT_GT(hi, 2600);
  EXPECT_EQ(r.dac.back(), 0);  // lifted, idle: the plate rests
}

TEST(EndToEnd, DecreasingCalibrationMatchesToo) {
  ChainSetup s;
  s.calibration = DacCalibration::inverted();
  const Result r = run_chain(synthetic_trace(), s);
  expect_same_codes(r);
  EXPECT_EQ(r.dac.back(), 4095);  // lifted, idle: amplitude 0 is full volts on FSADJUST
}

TEST(EndToEnd, ASecondFingerAndGarbageFramesChangeNoCode) {
  const std::vector<TraceRow> raw = synthetic_trace();
  ZforceModel::SecondFinger second;
  second.from_us = static_cast<uint32_t>(raw[100].t_us);
  second.to_us = static_cast<uint32_t>(raw[400].t_us);
  second.x = 420.0f;
  second.y = 90.0f;
  second.listed_first = true;
  ChainSetup s;
  s.second = &second;
  const ZforceModel::Fault faults[] = {ZforceModel::Fault::BadHeader,       ZforceModel::Fault::Truncated,
                                       ZforceModel::Fault::CutShort,        ZforceModel::Fault::LengthOverMax,
                                       ZforceModel::Fault::UnknownTag,      ZforceModel::Fault::MalformedLength,
                                       ZforceModel::Fault::ImpossibleEvent, ZforceModel::Fault::OutOfRange};
  for (int i = 0; i < 8; ++i) s.garbage.push_back({static_cast<uint32_t>(raw[50 + 60 * i].t_us + 2500), faults[i]});
  const Result r = run_chain(raw, s);
  expect_same_codes(r);
  expect_carrier(r);
  EXPECT_EQ(r.zforce_errors, 8u);
  EXPECT_GT(r.other_finger, 250u);
}

class BundledTraceTest : public ::testing::TestWithParam<const char*> {};

TEST_P(BundledTraceTest, MatchesTheReplayTickForTick) {
  std::vector<TraceRow> rows;
  host::TraceError error;
  ASSERT_TRUE(host::read_sensor_trace_file(std::string(FF_TRACE_DIR) + "/" + GetParam(), rows, error))
      << error.to_string(GetParam());
  const Result r = run_chain(rows, ChainSetup());
  expect_same_codes(r);
  expect_carrier(r);
  EXPECT_EQ(r.zforce_errors, 0u);
}

INSTANTIATE_TEST_SUITE_P(Traces, BundledTraceTest,
                         ::testing::Values("gen_mixed_zforce_rests.csv", "gen_clock_wrap.csv", "gen_along_low.csv"));

}  // namespace
}  // namespace ff
