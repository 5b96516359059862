// The firmware's main loop and 2 kHz tick against emulated devices and a
// scripted host: scene switches over UDP mid-trace, malformed packets, a
// stalled loop, lift-off; what the mouse, the DAC and the telemetry saw.
#include "firmware/app/firmware_app.hpp"

#include <gtest/gtest.h>

#include <deque>
#include <memory>
#include <vector>

#include "frictionfield/emulated/ad9834_model.hpp"
#include "frictionfield/emulated/i2c_bus.hpp"
#include "frictionfield/emulated/recording_dac.hpp"
#include "frictionfield/emulated/scripted_adc.hpp"
#include "frictionfield/emulated/zforce_model.hpp"

namespace ff::firmware {
namespace {

using protocol::Message;
using protocol::MessageType;

class FakeBoard final : public Board {
 public:
  void mouse_move_to(int x, int y) override { mouse.push_back({x, y}); }
  bool udp_receive(uint8_t* buffer, size_t capacity, size_t& size) override {
    if (udp_in.empty() || udp_in.front().size() > capacity) return false;
    size = udp_in.front().size();
    std::copy(udp_in.front().begin(), udp_in.front().end(), buffer);
    udp_in.pop_front();
    return true;
  }
  void udp_send(const uint8_t* data, size_t size) override {
    Message m;
    if (protocol::decode(data, size, m) == protocol::DecodeStatus::Ok) udp_out.push_back(m);
    else ++undecodable;
  }
  bool hid_receive(uint8_t*) override { return false; }
  void hid_send(const uint8_t* report) override {
    if (hid.push(report)) {
      Message m;
      if (protocol::decode(hid.frame(), hid.size(), m) == protocol::DecodeStatus::Ok) hid_out.push_back(m);
    }
  }
  uint32_t cycles() override { return cycle_counter += 900; }  // a fixed cost per call
  void reboot_to_bootloader() override {
    ++reboots;
    dac_at_reboot = dac ? dac->last() : -1;
  }

  void send(const Message& m) {
    std::vector<uint8_t> f(protocol::kMaxFrame);
    f.resize(protocol::encode(m, f.data(), f.size()));
    udp_in.push_back(f);
  }
  size_t count(MessageType t) const {
    size_t n = 0;
    for (const Message& m : udp_out) n += m.type == t ? 1 : 0;
    return n;
  }

  struct Point { int x, y; };
  std::vector<Point> mouse;
  std::deque<std::vector<uint8_t>> udp_in;
  std::vector<Message> udp_out, hid_out;
  protocol::HidReassembler hid;
  uint32_t cycle_counter = 0;
  int undecodable = 0, reboots = 0, dac_at_reboot = -1;
  const emulated::RecordingDac* dac = nullptr;
};

// The device: every peripheral emulated, the app as on the Teensy.
struct Device {
  emulated::Ad9834Model dds;
  emulated::ZforceModel zforce_model;
  emulated::EmulatedI2cBus i2c;
  emulated::RecordingDac dac;
  emulated::ScriptedAdc adc;
  FakeBoard board;
  std::unique_ptr<HapticPipeline> pipeline = std::make_unique<HapticPipeline>();
  std::unique_ptr<FirmwareApp> app;

  Device() {
    const ZforceConfig config;
    i2c.attach(config.address, zforce_model);
    zforce_model.set_calibration(config.calibration);
    for (uint8_t ch = 0; ch < 4; ++ch) adc.set(ch, 100);
    board.dac = &dac;
    app = std::make_unique<FirmwareApp>(Peripherals{dds, 0, i2c, zforce_model, dac, adc}, board, *pipeline);
    app->begin(0);
    // Sensor start-up: the loop configures the zForce over I2C.
    for (uint32_t t = 0; t < 1000000 && app->sensor().state() != ZforceState::Running; t += 1000) {
      zforce_model.advance_to(t);
      app->loop(t);
    }
  }

  // Main loop every 100 us, tick every 500 us, from `from` to `to`.
  void run(uint32_t from, uint32_t to, bool loop_alive = true) {
    for (uint32_t t = from; t < to; t += 100) {
      zforce_model.advance_to(t);
      if (loop_alive) app->loop(t);
      if (t % 500 == 0) app->tick(t);
    }
  }
};

// A finger along the middle path (y = 240) from x = 100 at 300 px/s, 200 Hz,
// from 1 s to 3 s, then lifted.
std::vector<SensorSample> stroke() {
  std::vector<SensorSample> s;
  for (uint32_t t = 1000000; t <= 3000000; t += 5000) {
    s.push_back({t, 100.0f + 300.0f * static_cast<float>(t - 1000000) * 1e-6f, 240.0f, true});
  }
  s.push_back({3005000, 0.0f, 0.0f, false});
  return s;
}

Message condition(protocol::ConditionKind kind, float strength = 1.0f) {
  Message m;
  m.type = MessageType::SetCondition;
  m.sequence = 5;
  m.condition.kind = kind;
  m.condition.target = Target::Middle;
  m.condition.strength = strength;
  return m;
}

TEST(FirmwareApp, BootsWithTheCarrierAtTheResonanceAndThePlateResting) {
  Device d;
  EXPECT_EQ(d.app->sensor().state(), ZforceState::Running);
  EXPECT_TRUE(d.dds.output_on());
  EXPECT_EQ(d.dds.output_word(), 124912u);  // 34.9 kHz
  d.run(1000000, 1010000);
  EXPECT_EQ(d.dac.last(), 0);  // no finger, no scene: idle amplitude 0
}

TEST(FirmwareApp, RunsATrialScenesSwitchOverUdpMalformedPacketsAreRefused) {
  Device d;
  d.zforce_model.load_trace(stroke());
  d.board.send(condition(protocol::ConditionKind::Heightmap));
  d.run(1000000, 1500000);
  ASSERT_GE(d.board.count(MessageType::Ack), 1u);
  EXPECT_EQ(d.board.udp_out.front().sequence, 5);
  const uint16_t heightmap_code = d.dac.last();
  EXPECT_GT(heightmap_code, 2048);  // moving right towards the middle target: assisted

  // Frictionmap mid-trace: the finger is on the path, so the next ticks render A = 1.
  d.board.send(condition(protocol::ConditionKind::Frictionmap));
  d.run(1500000, 1500600);
  EXPECT_EQ(d.dac.last(), 4095);
  EXPECT_EQ(d.app->counters().conditions_set, 2u);

  // Garbage and a bad CRC: counted, answered with Error, the scene stays.
  d.board.udp_in.push_back({1, 2, 3});
  std::vector<uint8_t> bad(protocol::kMaxFrame);
  bad.resize(protocol::encode(condition(protocol::ConditionKind::Neutral), bad.data(), bad.size()));
  bad[9] ^= 0xFF;
  d.board.udp_in.push_back(bad);
  d.run(1500600, 1600000);
  EXPECT_EQ(d.app->counters().protocol_errors, 2u);
  EXPECT_EQ(d.board.count(MessageType::Error), 2u);
  EXPECT_EQ(d.dac.last(), 4095);

  // A scene the core refuses (NaN weight): Ack refused, the scene stays.
  Message general = condition(protocol::ConditionKind::General);
  general.condition.scene.rendering = Rendering::Directional;
  general.condition.scene.add(FieldElement::vortex({400, 240}, NAN));
  d.board.send(general);
  d.run(1600000, 1700000);
  EXPECT_EQ(d.app->counters().conditions_refused, 1u);
  const Message* last_ack = nullptr;
  for (const Message& m : d.board.udp_out) if (m.type == MessageType::Ack) last_ack = &m;
  ASSERT_NE(last_ack, nullptr);
  EXPECT_EQ(last_ack->ack.status, protocol::AckStatus::Refused);
  EXPECT_EQ(last_ack->ack.detail, static_cast<uint8_t>(PrepareStatus::InvalidParameter));
  EXPECT_EQ(d.dac.last(), 4095);

  // Lift-off at 3.005 s: idle (0) after the 20 ms lift-off timeout.
  d.run(1700000, 3100000);
  EXPECT_EQ(d.dac.last(), 0);

  // Mouse every 3 ms while the finger was down, at the filtered position.
  EXPECT_GT(d.board.mouse.size(), 600u);
  EXPECT_LT(d.board.mouse.size(), 700u);
  EXPECT_NEAR(d.board.mouse.back().y, 240, 2);
  // Force telemetry every 30 ms over UDP: 1.0 .. 3.1 s / 30 ms = 70, +-1 for phase.
  EXPECT_NEAR(static_cast<double>(d.board.count(MessageType::Force)), 2100000.0 / 30000.0, 1.0);
}

TEST(FirmwareApp, StalledLoopRestsThePlateUntilItRecovers) {
  Device d;
  d.zforce_model.load_trace(stroke());
  d.board.send(condition(protocol::ConditionKind::Frictionmap));
  d.run(1000000, 1200000);
  EXPECT_EQ(d.dac.last(), 4095);
  d.run(1200000, 1240000, false);  // 40 ms without the loop: still inside the watchdog
  EXPECT_EQ(d.app->counters().watchdog_trips, 0u);
  d.run(1240000, 1300000, false);  // past 50 ms: idle
  EXPECT_EQ(d.dac.last(), 0);
  EXPECT_EQ(d.app->counters().watchdog_trips, 1u);
  d.run(1300000, 1400000);  // the loop is back: rendering again
  EXPECT_EQ(d.dac.last(), 4095);
}

TEST(FirmwareApp, StatusStreamingCarrierAndReboot) {
  Device d;
  d.zforce_model.load_trace(stroke());
  d.board.send(condition(protocol::ConditionKind::Heightmap, 0.66f));
  Message start;
  start.type = MessageType::StartStream;
  start.stream.tick_decimation = 2;
  d.board.send(start);
  d.run(1000000, 1100000);
  Message stop;
  stop.type = MessageType::StopStream;
  d.board.send(stop);
  Message q;
  q.type = MessageType::QueryStatus;
  d.board.send(q);
  Message carrier;
  carrier.type = MessageType::SetCarrier;
  carrier.carrier.frequency_hz = 35200.0f;
  d.board.send(carrier);
  d.run(1100000, 1101000);

  // Streaming: every 2nd tick of 100 ms = 100 records, and the sensor's reports.
  size_t ticks = 0, samples = 0;
  for (const Message& m : d.board.hid_out) {
    if (m.type == MessageType::Ticks) ticks += m.ticks.count;
    if (m.type == MessageType::Samples) samples += m.samples.count;
  }
  EXPECT_NEAR(static_cast<double>(ticks), 100.0, 2.0);
  EXPECT_NEAR(static_cast<double>(samples), 20.0, 1.0);

  const Message* status = nullptr;
  for (const Message& m : d.board.udp_out) if (m.type == MessageType::Status) status = &m;
  ASSERT_NE(status, nullptr);
  EXPECT_EQ(status->status.firmware_version, kFirmwareVersion);
  EXPECT_EQ(status->status.kind, protocol::ConditionKind::Heightmap);
  EXPECT_FLOAT_EQ(status->status.strength, 0.66f);
  EXPECT_EQ(status->status.tick_cycles_mean, 900u);  // the fake counter's cost per tick
  EXPECT_TRUE(status->status.finger_present);
  EXPECT_EQ(status->status.faults[Fault::TouchDown], 1u);

  EXPECT_NEAR(d.dds.output_hz(), 35200.0, 0.3);  // switched to the other register, glitch-free
  EXPECT_EQ(d.dds.total_faults(), 0u);

  Message reboot;
  reboot.type = MessageType::RebootToBootloader;
  d.board.send(reboot);
  d.run(1101000, 1102000);
  EXPECT_EQ(d.board.reboots, 1);
  EXPECT_EQ(d.board.dac_at_reboot, 0);  // the plate rests before the reboot
}

}  // namespace
}  // namespace ff::firmware
