// The firmware's main loop and 2 kHz tick against the emulated devices and a
// scripted host, as on the Teensy: the loop every 100 us, the tick every
// 500 us (after the loop, as an interrupt would land), the USB host reading
// one report per millisecond. Checked: what the DAC, the mouse, the carrier
// and the host saw through scene switches over UDP mid-trace, malformed
// packets, a stalled loop, a stopped tick, lift-off, streaming with and
// without a reading host, a failed sensor.
#include "firmware/app/firmware_app.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <functional>
#include <memory>
#include <vector>

#include "frictionfield/emulated/ad9834_model.hpp"
#include "frictionfield/emulated/i2c_bus.hpp"
#include "frictionfield/emulated/manual_clock.hpp"
#include "frictionfield/emulated/recording_dac.hpp"
#include "frictionfield/emulated/scripted_adc.hpp"
#include "frictionfield/emulated/zforce_model.hpp"

namespace ff::firmware {
namespace {

using protocol::Message;
using protocol::MessageType;

std::vector<uint8_t> encode(const Message& m) {
  std::vector<uint8_t> f(protocol::kMaxFrame);
  f.resize(protocol::encode(m, f.data(), f.size()));
  return f;
}

// The Teensy side of the board, scripted: the experiment host on UDP, ffctl
// on the HID channel (a 6-report transmit queue, as Teensyduino's SEREMU
// keeps, drained by the host one report per millisecond).
class FakeBoard final : public Board {
 public:
  static constexpr size_t kTxQueue = 6;
  explicit FakeBoard(const uint32_t& now) : now_(now) {}

  struct Move { uint32_t t_us; int x, y; };
  bool mouse_move_to(int x, int y) override {
    if (mouse_queue_full) return false;  // the USB host stopped polling the mouse
    mouse.push_back({now_, x, y});
    return true;
  }
  bool udp_receive(uint8_t* buffer, size_t capacity, size_t& size, UdpEndpoint& from) override {
    if (udp_in.empty() || udp_in.front().size() > capacity) return false;
    from = {0x0101A8C0u, 50000};
    size = udp_in.front().size();
    std::copy(udp_in.front().begin(), udp_in.front().end(), buffer);
    udp_in.pop_front();
    return true;
  }
  bool udp_send(const UdpEndpoint& /*to*/, const uint8_t* data, size_t size) override {
    ++udp_attempts;
    if (udp_unanswered) return false;  // no ARP answer: the send timed out
    Message m;
    if (protocol::decode(data, size, m) == protocol::DecodeStatus::Ok) {
      udp_out.push_back(m);
      udp_out_us.push_back(now_);
    } else {
      ++undecodable;
    }
    return true;
  }
  bool hid_receive(uint8_t* report) override {
    if (hid_in.empty()) return false;
    std::copy(hid_in.front().begin(), hid_in.front().end(), report);
    hid_in.pop_front();
    return true;
  }
  void hid_send(const uint8_t* report) override {
    ASSERT_LT(queued, kTxQueue) << "sent beyond the room the board reported";
    ++queued;
    if (reassembler.push(report)) {
      Message m;
      if (protocol::decode(reassembler.frame(), reassembler.size(), m) == protocol::DecodeStatus::Ok) {
        hid_out.push_back(m);
        hid_out_us.push_back(now_);
      } else {
        ++undecodable;
      }
    }
  }
  size_t hid_tx_room() override { return kTxQueue - queued; }
  uint32_t cycles() override { return cycle_counter += 900; }  // a fixed cost per tick
  void watchdog_kick() override { kicks.push_back(now_); }
  void reboot_to_bootloader() override {
    ++reboots;
    dac_at_reboot = dac ? dac->last() : -1;
    if (while_rebooting) while_rebooting();  // the reset takes a moment: a tick may land
  }

  // The hosts.
  void send_udp(const Message& m) { udp_in.push_back(encode(m)); }
  void send_hid(const Message& m) {
    const std::vector<uint8_t> f = encode(m);
    uint8_t reports[protocol::kMaxHidReports][protocol::kHidReportBytes];
    const size_t n = protocol::split_into_reports(f.data(), f.size(), reports, protocol::kMaxHidReports);
    for (size_t i = 0; i < n; ++i) hid_in.emplace_back(reports[i], reports[i] + protocol::kHidReportBytes);
  }
  void host_reads_one_report() {
    if (queued > 0) --queued;
  }
  std::vector<Message> udp_of(MessageType t) const {
    std::vector<Message> out;
    for (const Message& m : udp_out) if (m.type == t) out.push_back(m);
    return out;
  }
  std::vector<Message> hid_of(MessageType t) const {
    std::vector<Message> out;
    for (const Message& m : hid_out) if (m.type == t) out.push_back(m);
    return out;
  }

  std::vector<Move> mouse;
  std::deque<std::vector<uint8_t>> udp_in, hid_in;
  std::vector<Message> udp_out, hid_out;
  std::vector<uint32_t> udp_out_us, hid_out_us, kicks;
  protocol::HidReassembler reassembler;
  size_t queued = 0;
  uint32_t cycle_counter = 0;
  int undecodable = 0, reboots = 0, dac_at_reboot = -1;
  bool udp_unanswered = false, mouse_queue_full = false;
  std::function<void()> while_rebooting;
  int udp_attempts = 0;
  const emulated::RecordingDac* dac = nullptr;

 private:
  const uint32_t& now_;
};

// The device: every peripheral emulated, the app as on the Teensy.
struct Device {
  uint32_t now = 0;
  emulated::ManualClock clock;
  emulated::Ad9834Model dds;
  emulated::ZforceModel zforce_model;
  emulated::EmulatedI2cBus i2c;
  emulated::RecordingDac dac{&clock};
  emulated::ScriptedAdc adc;
  FakeBoard board{now};
  std::unique_ptr<HapticPipeline> pipeline = std::make_unique<HapticPipeline>();
  std::unique_ptr<FirmwareApp> app;
  bool loop_alive = true;
  bool ticks_alive = true;
  bool host_reads = true;

  // unplugged: the zForce neither announces its boot nor acknowledges its address.
  // begin_us: when setup() calls begin() (after Ethernet.begin(), which may take seconds).
  explicit Device(bool sensor_unplugged = false, uint32_t begin_us = 0, bool timestamp_inside = false)
      : now(begin_us), zforce_model(model_options(sensor_unplugged, timestamp_inside)) {
    const ZforceConfig config;
    i2c.attach(config.address, zforce_model);
    zforce_model.set_calibration(config.calibration);
    if (sensor_unplugged) i2c.fail_next(UINT32_MAX, BusStatus::Nack);
    for (uint8_t ch = 0; ch < 4; ++ch) adc.set(ch, 100);
    board.dac = &dac;
    app = std::make_unique<FirmwareApp>(Peripherals{dds, 0, i2c, zforce_model, dac, adc}, board, *pipeline);
    clock.set(now);
    app->begin(now);
    if (!sensor_unplugged) {
      while (app->sensor().state() != ZforceState::Running && now < 1000000) step();  // configures the zForce
    }
  }

  void tick_at(uint32_t t) {
    clock.set(t);
    app->tick(t);
    app->note_interrupt_cycles(1000);  // as main.cpp's interrupt does, around the tick
  }
  void step() {
    now += 100;
    clock.set(now);
    zforce_model.advance_to(now);
    if (loop_alive) app->loop(now);  // may move `now` (a slow preparation)
    if (now % 500 == 0 && ticks_alive) tick_at(now);
    if (now % 1000 == 0 && host_reads) board.host_reads_one_report();
  }
  void run_until(uint32_t t) {
    while (now < t) step();
  }
  // The code on the DAC at time t (the last write at or before it).
  uint16_t dac_at(uint32_t t) const {
    uint16_t code = 0;
    for (const auto& w : dac.writes()) {
      if (w.t_us > t) break;
      code = w.code;
    }
    return code;
  }
  FirmwareCounters counters() const { return app->counters(); }
  static emulated::ZforceModel::Options model_options(bool unplugged, bool timestamp_inside) {
    emulated::ZforceModel::Options o;
    o.boot_complete = !unplugged;
    o.timestamp_inside = timestamp_inside;
    return o;
  }
};

// A finger along the middle path (y = 240) from x = 100 at 300 px/s, 200 Hz,
// from `from_us` for 2 s, then lifted.
std::vector<SensorSample> stroke(uint32_t from_us = 1000000) {
  std::vector<SensorSample> s;
  for (uint32_t t = from_us; t <= from_us + 2000000; t += 5000) {
    s.push_back({t, 100.0f + 300.0f * static_cast<float>(t - from_us) * 1e-6f, 240.0f, true});
  }
  s.push_back({from_us + 2005000, 0.0f, 0.0f, false});
  return s;
}

Message condition(protocol::ConditionKind kind, float strength = 1.0f, uint8_t sequence = 5) {
  Message m;
  m.type = MessageType::SetCondition;
  m.sequence = sequence;
  m.condition.kind = kind;
  m.condition.target = Target::Middle;
  m.condition.strength = strength;
  return m;
}

Message command(MessageType type, uint8_t sequence = 9) {
  Message m;
  m.type = type;
  m.sequence = sequence;
  return m;
}

// The Status over USB, asked at `t_us` and answered within 10 ms.
protocol::StatusMessage status_at(Device& d, uint32_t t_us) {
  d.run_until(t_us);
  d.board.send_hid(command(MessageType::QueryStatus, 77));
  d.run_until(t_us + 10000);
  const auto status = d.board.hid_of(MessageType::Status);
  EXPECT_FALSE(status.empty());
  return status.empty() ? protocol::StatusMessage() : status.back().status;
}

void expect_device_counts(const protocol::DeviceCounts& got, const protocol::DeviceCounts& want) {
  for (int i = 0; i < static_cast<int>(protocol::DeviceCount::kCount); ++i) {
    EXPECT_EQ(got.count[i], want.count[i]) << to_string(static_cast<protocol::DeviceCount>(i));
  }
}


// StartStream over USB, taken by the loop pass at `t_us` (the loop reads the
// sensor, then takes the command): the sensor's report count then.
uint32_t start_stream(Device& d, uint32_t t_us, uint8_t decimation) {
  d.run_until(t_us - 100);
  Message start = command(MessageType::StartStream);
  start.stream.tick_decimation = decimation;
  d.board.send_hid(start);
  d.run_until(t_us);
  return d.app->sensor().count(ZforceCount::Samples);
}

// StopStream over USB, taken by the loop pass at `t_us`: the sensor's report count then.
uint32_t stop_stream(Device& d, uint32_t t_us) {
  d.run_until(t_us - 100);
  d.board.send_hid(command(MessageType::StopStream));
  d.run_until(t_us);
  return d.app->sensor().count(ZforceCount::Samples);
}

// The tick records and reports the USB host got, in order.
std::vector<protocol::TickRecord> ticks_received(const Device& d) {
  std::vector<protocol::TickRecord> ticks;
  for (const Message& m : d.board.hid_of(MessageType::Ticks)) ticks.insert(ticks.end(), m.ticks.ticks, m.ticks.ticks + m.ticks.count);
  return ticks;
}
size_t samples_received(const Device& d) {
  size_t samples = 0;
  for (const Message& m : d.board.hid_of(MessageType::Samples)) samples += m.samples.count;
  return samples;
}

// Codes the thesis' scenes give on the middle path, moving right (v_hat = (1, 0)):
// frictionmap |u| = 0 <= 10: A = 1 -> 4095. Heightmap: grad Z_path = 0 on the
// path, grad Z_cone = (-1, 0), so G = (-0.5, 0); max|G| over the screen is
// (1 + 48^2/(1 + 48^2)) / 2 = 0.99978 (above the top target, where both
// slopes point up), G_norm = (-0.25005, 0), mu = 0.24995, A = 0.75005
// -> round(3071.5) = 3071 (3071.46 before rounding: no tie).
constexpr uint16_t kFrictionmapOnPath = 4095;
constexpr uint16_t kHeightmapOnPathMovingRight = 3071;

TEST(FirmwareApp, BootsWithThePlateRestingAndTheCarrierAtTheResonance) {
  Device d;
  EXPECT_EQ(d.app->sensor().state(), ZforceState::Running);
  ASSERT_FALSE(d.dac.writes().empty());
  EXPECT_EQ(d.dac.writes().front().t_us, 0u);  // in begin(), before the first tick
  EXPECT_EQ(d.dac.writes().front().code, 0);
  EXPECT_TRUE(d.dds.output_on());
  EXPECT_EQ(d.dds.output_word(), 124912u);  // round(34900 * 2^28 / 75 MHz) = round(124911.97)
  EXPECT_NEAR(static_cast<double>(d.app->carrier_hz()), 34900.0, 0.3);
  d.run_until(1010000);
  for (const auto& w : d.dac.writes()) EXPECT_EQ(w.code, 0) << "at " << w.t_us;  // no scene, no finger: idle
  EXPECT_EQ(d.counters().tick_stalls, 0u);
  EXPECT_EQ(d.counters().watchdog_trips, 0u);
}

TEST(FirmwareApp, TrialOverUdpSceneSwitchMidTraceMalformedPacketsLiftOff) {
  Device d;
  d.zforce_model.load_trace(stroke());
  d.run_until(999000);
  d.board.send_udp(condition(protocol::ConditionKind::Heightmap));
  d.run_until(1499900);
  EXPECT_EQ(d.dac_at(1499500), kHeightmapOnPathMovingRight);

  // Frictionmap at 1.5 s, mid-trace: handled by the loop at 1.5 s, rendered by the tick at 1.5 s.
  d.board.send_udp(condition(protocol::ConditionKind::Frictionmap, 1.0f, 6));
  d.run_until(1600000);
  EXPECT_EQ(d.dac_at(1499500), kHeightmapOnPathMovingRight);
  EXPECT_EQ(d.dac_at(1500000), kFrictionmapOnPath);
  const auto acks = d.board.udp_of(MessageType::Ack);
  ASSERT_EQ(acks.size(), 2u);
  EXPECT_EQ(acks[0].sequence, 5);
  EXPECT_EQ(acks[1].sequence, 6);
  EXPECT_EQ(acks[1].ack.command, MessageType::SetCondition);
  EXPECT_EQ(acks[1].ack.status, protocol::AckStatus::Ok);

  // Garbage, a bad CRC, a type the protocol does not know, a device-to-host
  // type: each counted and answered with its Error; the scene stays.
  d.board.udp_in.push_back({1, 2, 3});
  std::vector<uint8_t> bad_crc = encode(condition(protocol::ConditionKind::Neutral));
  bad_crc[9] ^= 0xFF;
  d.board.udp_in.push_back(bad_crc);
  std::vector<uint8_t> unknown = encode(command(MessageType::QueryStatus));
  unknown[3] = 0x42;
  const uint16_t crc = protocol::crc16_ccitt(unknown.data() + 2, unknown.size() - 4);
  unknown[unknown.size() - 2] = static_cast<uint8_t>(crc);
  unknown[unknown.size() - 1] = static_cast<uint8_t>(crc >> 8);
  d.board.udp_in.push_back(unknown);
  Message force = command(MessageType::Force);
  d.board.send_udp(force);
  d.run_until(1700000);
  const auto errors = d.board.udp_of(MessageType::Error);
  ASSERT_EQ(errors.size(), 4u);
  EXPECT_EQ(errors[0].error.code, protocol::ErrorCode::TooShort);
  EXPECT_EQ(errors[1].error.code, protocol::ErrorCode::BadCrc);
  EXPECT_EQ(errors[2].error.code, protocol::ErrorCode::UnknownType);
  EXPECT_EQ(errors[2].error.type, 0x42);
  EXPECT_EQ(errors[3].error.code, protocol::ErrorCode::UnknownType);
  EXPECT_EQ(errors[3].error.type, static_cast<uint8_t>(MessageType::Force));
  EXPECT_EQ(d.counters().protocol_errors, 4u);
  EXPECT_EQ(d.counters().conditions_set, 2u);
  for (uint32_t t = 1500000; t <= 1700000; t += 500) ASSERT_EQ(d.dac_at(t), kFrictionmapOnPath) << t;
  d.board.send_udp(command(MessageType::QueryStatus));  // the host can read the count
  d.run_until(1710000);
  ASSERT_FALSE(d.board.udp_of(MessageType::Status).empty());
  EXPECT_EQ(d.board.udp_of(MessageType::Status).back().status.protocol_errors, 4u);

  // A scene the core refuses (a 1 px float table: 1.5 MiB, over the 96 KiB
  // slot): Ack refused with the reason; the scene stays.
  Message general = condition(protocol::ConditionKind::General, 1.0f, 7);
  general.condition.scene.rendering = Rendering::Directional;
  general.condition.scene.evaluation = Evaluation::Table;
  general.condition.scene.table = {1.0f, TableStorage::Float32, TableSource::TabulatedGradient};
  general.condition.scene.add(FieldElement::vortex({400, 240}, 1.0f));
  d.board.send_udp(general);
  d.run_until(1800000);
  const Message last_ack = d.board.udp_of(MessageType::Ack).back();
  EXPECT_EQ(last_ack.sequence, 7);
  EXPECT_EQ(last_ack.ack.status, protocol::AckStatus::Refused);
  EXPECT_EQ(last_ack.ack.detail, static_cast<uint8_t>(PrepareStatus::TableTooLarge));
  EXPECT_EQ(d.counters().conditions_refused, 1u);
  EXPECT_EQ(d.dac_at(1800000), kFrictionmapOnPath);

  // Lift-off: touch = 0 at 3.005 s, idle from the tick 20 ms later (the tracker's timeout).
  d.run_until(3200000);
  EXPECT_EQ(d.dac_at(3000000), kFrictionmapOnPath);
  EXPECT_EQ(d.dac_at(3024500), kFrictionmapOnPath);
  for (uint32_t t = 3025000; t <= 3200000; t += 500) ASSERT_EQ(d.dac_at(t), 0) << t;
  EXPECT_EQ(d.board.undecodable, 0);
}

TEST(FirmwareApp, MouseEvery3msAtTheFilteredPositionWhileTheFingerIsDown) {
  Device d;
  d.zforce_model.load_trace(stroke());
  d.run_until(3200000);
  const auto& mouse = d.board.mouse;
  ASSERT_GT(mouse.size(), 2u);
  // Down from the first report (1.0 s) to lift-off (3.025 s): 2.025 s / 3 ms = 675 moves.
  EXPECT_NEAR(static_cast<double>(mouse.size()), 675.0, 1.0);
  EXPECT_LE(mouse.back().t_us, 3025500u);
  EXPECT_EQ(mouse.front().t_us, 1002000u);  // the first 3 ms step with a finger tracked
  for (size_t i = 1; i < mouse.size(); ++i) {
    ASSERT_EQ(mouse[i].t_us - mouse[i - 1].t_us, kMouseIntervalUs) << i;
    ASSERT_EQ(mouse[i].y, 240) << i;
    ASSERT_GE(mouse[i].x, mouse[i - 1].x) << i;
    if (mouse[i].t_us > 3000000) continue;  // the finger has stopped; the tracker extrapolates, then holds
    // The filtered position trails the finger by v / (2 pi fc) = 300 / (2 pi 20.1) = 2.4 px.
    const double finger_x = 100.0 + 300.0 * (mouse[i].t_us - 1000000.0) * 1e-6;
    ASSERT_NEAR(mouse[i].x, finger_x, 3.0) << mouse[i].t_us;
  }
}

TEST(FirmwareApp, AfterAStalledLoopTheMouseGoesOnEvery3msWithoutABurst) {
  Device d;
  d.zforce_model.load_trace(stroke());
  d.run_until(1500000);
  d.loop_alive = false;
  d.run_until(1540000);
  d.loop_alive = true;
  d.run_until(1600000);
  const auto& mouse = d.board.mouse;
  for (size_t i = 1; i < mouse.size(); ++i) ASSERT_GE(mouse[i].t_us - mouse[i - 1].t_us, kMouseIntervalUs) << i;
  EXPECT_GE(mouse.back().t_us, 1597000u);
}

TEST(FirmwareApp, MovesTheUsbHostDidNotTakeAreCounted) {
  Device d;
  d.zforce_model.load_trace(stroke());
  d.run_until(1500000);
  EXPECT_EQ(d.counters().mouse_moves_skipped, 0u);
  d.board.mouse_queue_full = true;
  d.run_until(1530000);  // 10 moves due
  EXPECT_EQ(d.counters().mouse_moves_skipped, 10u);
  d.board.mouse_queue_full = false;
  EXPECT_EQ(status_at(d, 1530000).device[protocol::DeviceCount::MouseMovesSkipped], 10u);
}

TEST(FirmwareApp, BeforeAnySceneIsSetAFingerFeelsTheNeutralScene) {
  Device d;
  d.zforce_model.load_trace(stroke());
  d.run_until(1500000);
  EXPECT_EQ(d.dac_at(999500), 0);      // no finger: at rest
  EXPECT_EQ(d.dac_at(1500000), 2048);  // A = 0.5: round(2047.5)
}

TEST(FirmwareApp, BeginningLateStartsEveryClockThen) {
  // begin() 3 s after reset: no watchdog trip even if the first tick comes
  // before the first loop pass (the timer starts in setup()), no tick stall
  // if the first loop pass comes first, no long loop pass, and the unplugged
  // zForce is given its whole boot wait (300 ms) from then.
  constexpr uint32_t kBegin = 3000000;
  Device tick_first(/*sensor_unplugged=*/true, kBegin);
  tick_first.tick_at(kBegin + 500);
  EXPECT_EQ(tick_first.counters().watchdog_trips, 0u);

  Device d(/*sensor_unplugged=*/true, kBegin);
  d.run_until(kBegin + 290000);
  EXPECT_EQ(d.app->sensor().state(), ZforceState::Booting);
  d.board.send_udp(command(MessageType::QueryStatus, 4));
  d.run_until(kBegin + 400000);
  EXPECT_NE(d.app->sensor().state(), ZforceState::Booting);
  EXPECT_EQ(d.counters().watchdog_trips, 0u);
  EXPECT_EQ(d.counters().tick_stalls, 0u);
  const std::vector<Message> status = d.board.udp_of(MessageType::Status);
  ASSERT_EQ(status.size(), 1u);
  EXPECT_EQ(status[0].status.loop_pass_max_us, 100u);  // the loop every 100 us, from begin() on
}

TEST(FirmwareApp, QueryConditionAnswersWhatRendersNow) {
  Device d;
  Message q = command(MessageType::QueryCondition, 1);
  d.board.send_udp(q);
  d.run_until(10000);
  ASSERT_EQ(d.board.udp_of(MessageType::Condition).size(), 1u);
  EXPECT_EQ(d.board.udp_of(MessageType::Condition)[0].condition.kind, protocol::ConditionKind::Neutral);
  Message set = command(MessageType::SetCondition, 2);
  set.condition.kind = protocol::ConditionKind::Frictionmap;
  set.condition.target = Target::Top;
  set.condition.strength = 0.66f;
  d.board.send_udp(set);
  d.board.send_udp(command(MessageType::QueryCondition, 3));
  d.run_until(20000);
  const auto echoes = d.board.udp_of(MessageType::Condition);
  ASSERT_EQ(echoes.size(), 2u);
  EXPECT_EQ(echoes[1].sequence, 3);
  EXPECT_EQ(echoes[1].condition.kind, protocol::ConditionKind::Frictionmap);
  EXPECT_EQ(echoes[1].condition.target, Target::Top);
  EXPECT_FLOAT_EQ(echoes[1].condition.strength, 0.66f);
}

// Over USB, where the SEREMU queue takes 6 reports: a scene of 8 elements
// with 16-point paths and a 16-point calibration is 22 reports long.
TEST(FirmwareApp, QueryConditionOverUsbAnswersWithTheLargestScene) {
  Device d;
  Message set = condition(protocol::ConditionKind::General, 1.0f, 4);
  set.condition.scene.rendering = Rendering::Directional;
  set.condition.scene.evaluation = Evaluation::Table;
  set.condition.scene.table = {16.0f, TableStorage::Float32, TableSource::TabulatedGradient};
  for (int e = 0; e < kMaxSceneElements; ++e) {
    Vec2 points[kMaxPolylinePoints];
    for (int i = 0; i < kMaxPolylinePoints; ++i) points[i] = {50.0f * i, 100.0f + 40.0f * e + (i % 2) * 10.0f};
    ASSERT_TRUE(set.condition.scene.add(FieldElement::path_sink(PathCurve::polyline(points, kMaxPolylinePoints), 0.1f)));
  }
  DacCalibration& cal = set.condition.calibration;
  cal.count = kMaxCalibrationPoints;
  for (int i = 0; i < kMaxCalibrationPoints; ++i) {
    cal.amplitude[i] = static_cast<float>(i) / (kMaxCalibrationPoints - 1);
    cal.code[i] = 200.0f * static_cast<float>(i);
  }
  d.board.send_hid(set);
  d.run_until(2000000);  // prepared
  d.board.send_hid(command(MessageType::QueryCondition, 5));
  d.run_until(2100000);
  const std::vector<Message> acks = d.board.hid_of(MessageType::Ack);
  ASSERT_EQ(acks.size(), 1u);
  ASSERT_EQ(acks[0].ack.status, protocol::AckStatus::Ok);
  uint8_t frame[protocol::kMaxFrame];
  Message echo_of_set = set;
  echo_of_set.type = MessageType::Condition;
  ASSERT_EQ(protocol::reports_for(protocol::encode(echo_of_set, frame, sizeof frame)), 22u);
  const std::vector<Message> echoes = d.board.hid_of(MessageType::Condition);
  ASSERT_EQ(echoes.size(), 1u);
  EXPECT_EQ(echoes[0].sequence, 5);
  EXPECT_EQ(echoes[0].condition.scene.element_count, kMaxSceneElements);
  EXPECT_EQ(echoes[0].condition.calibration.count, kMaxCalibrationPoints);
  EXPECT_EQ(d.counters().hid_frames_dropped, 0u);
}

TEST(FirmwareApp, NoForceBeforeAHostHasSpoken) {
  Device d;
  d.run_until(500000);
  EXPECT_TRUE(d.board.udp_of(MessageType::Force).empty());
}

TEST(FirmwareApp, ForceTelemetryEvery30msAveragedOver5Readings) {
  Device d;
  d.zforce_model.load_trace(stroke());
  Message hello;
  hello.type = MessageType::QueryStatus;
  d.board.send_udp(hello);  // force goes to the host that spoke last
  d.run_until(1500000);  // tared at 100 counts per cell (a finger present does not rezero)
  for (uint8_t ch = 0; ch < 4; ++ch) d.adc.set(ch, 110);  // +40 counts
  d.run_until(1800000);
  for (uint8_t ch = 0; ch < 4; ++ch) d.adc.set(ch, 115);  // +60 counts
  d.run_until(2100000);
  const auto force = d.board.udp_of(MessageType::Force);
  ASSERT_GT(force.size(), 60u);
  for (size_t i = 1; i < force.size(); ++i) ASSERT_EQ(force[i].force.t_us - force[i - 1].force.t_us, 30000u);
  // 40 counts * 1.0712 * 9.81 = 420.34 mN once all 5 readings see it; 60 counts: 630.50 mN, over 0.5 N.
  const auto at = [&](uint32_t t) {
    Message last;
    for (const Message& m : force) if (m.force.t_us <= t) last = m;
    return last.force;
  };
  EXPECT_NEAR(static_cast<double>(at(1490000).force_mN), 0.0, 1e-3);
  EXPECT_NEAR(static_cast<double>(at(1790000).force_mN), 40.0 * 1.0712 * 9.81, 0.05);
  EXPECT_FALSE(at(1790000).over_force);
  EXPECT_NEAR(static_cast<double>(at(2090000).force_mN), 60.0 * 1.0712 * 9.81, 0.05);
  EXPECT_TRUE(at(2090000).over_force);
  EXPECT_TRUE(d.board.hid_of(MessageType::Force).empty());  // USB only while streaming
  d.board.send_udp(command(MessageType::QueryStatus));  // the status says so too
  d.run_until(2110000);
  const std::vector<Message> status = d.board.udp_of(MessageType::Status);
  ASSERT_EQ(status.size(), 2u);
  EXPECT_NEAR(static_cast<double>(status[1].status.force_mN), 60.0 * 1.0712 * 9.81, 0.05);
  EXPECT_TRUE(status[1].status.over_force);
}

TEST(FirmwareApp, StalledLoopRestsThePlateAfter50msAndRendersAgainWhenItReturns) {
  Device d;
  d.zforce_model.load_trace(stroke());
  d.board.send_udp(condition(protocol::ConditionKind::Frictionmap));
  d.run_until(1200000);
  EXPECT_EQ(d.dac_at(1200000), kFrictionmapOnPath);
  const size_t kicks = d.board.kicks.size();
  d.loop_alive = false;  // the last heartbeat: 1.2 s
  d.run_until(1300000);
  EXPECT_EQ(d.dac_at(1250000), kFrictionmapOnPath);  // 50 ms: not yet
  for (uint32_t t = 1250500; t <= 1300000; t += 500) ASSERT_EQ(d.dac_at(t), 0) << t;
  EXPECT_EQ(d.counters().watchdog_trips, 1u);
  EXPECT_EQ(d.board.kicks.size(), kicks);  // the hardware watchdog is not fed either
  d.loop_alive = true;
  d.run_until(1400000);
  EXPECT_EQ(d.dac_at(1400000), kFrictionmapOnPath);
  EXPECT_EQ(d.counters().watchdog_trips, 1u);
  EXPECT_EQ(d.board.kicks.size(), kicks + 1000);  // once per loop pass again: 100 ms / 100 us
  d.board.send_udp(command(MessageType::QueryStatus));  // the host is told of the trip
  d.run_until(1410000);
  ASSERT_EQ(d.board.udp_of(MessageType::Status).size(), 1u);
  EXPECT_EQ(d.board.udp_of(MessageType::Status)[0].status.watchdog_trips, 1u);
  // The load cells' reading due 30 ms into the 100 ms stall came late: one period missed, not a burst.
  EXPECT_EQ(d.board.udp_of(MessageType::Status)[0].status.device[protocol::DeviceCount::ForcePeriodsMissed], 1u);
  // The tick ran through the stall: its clock never leapt.
  const FaultCounters faults = d.pipeline->faults();
  EXPECT_EQ(faults[Fault::BadTickTime], 0u);
  EXPECT_EQ(faults[Fault::TimeBaseReset], 0u);
}

// A preparation that takes 80 ms of device time: the pipeline's clock is
// read when it starts and ends; in between, the interrupt keeps ticking.
struct SlowPreparation {
  Device* device = nullptr;
  uint32_t duration_us = 80000;
  bool inside = false;
};
SlowPreparation* g_slow = nullptr;
uint32_t slow_clock() {
  SlowPreparation& s = *g_slow;
  Device& d = *s.device;
  if (!s.inside) {
    s.inside = true;
    return d.now;
  }
  const uint32_t end = d.now + s.duration_us;
  for (uint32_t t = d.now - d.now % 500 + 500; t < end; t += 500) d.tick_at(t);
  d.now = end;
  s.inside = false;
  return end;
}

TEST(FirmwareApp, ALongPreparationKeepsTheOldSceneAndDoesNotTripTheWatchdog) {
  Device d;
  d.zforce_model.load_trace(stroke());
  d.board.send_udp(condition(protocol::ConditionKind::Frictionmap));
  d.run_until(1200000);
  SlowPreparation slow{&d};
  g_slow = &slow;
  d.pipeline->set_clock(slow_clock);
  d.board.send_udp(condition(protocol::ConditionKind::Neutral));
  d.run_until(1300000);
  d.pipeline->set_clock(nullptr);
  EXPECT_EQ(d.pipeline->last_prepare_us(), 80000u);
  EXPECT_EQ(d.counters().watchdog_trips, 0u);
  d.board.send_udp(command(MessageType::QueryStatus));
  d.run_until(1310000);
  ASSERT_FALSE(d.board.udp_of(MessageType::Status).empty());
  EXPECT_EQ(d.board.udp_of(MessageType::Status).back().status.prepare_us_last, 80000u);
  // Through the preparation (1.2001 .. 1.2801 s) the old scene played; then neutral (0.5 -> 2048).
  for (uint32_t t = 1200500; t < 1280100; t += 500) ASSERT_EQ(d.dac_at(t), kFrictionmapOnPath) << t;
  EXPECT_EQ(d.dac_at(1280500), 2048);
  EXPECT_EQ(d.board.udp_of(MessageType::Ack).back().ack.status, protocol::AckStatus::Ok);
}

TEST(FirmwareApp, StoppedTickIsCaughtByTheLoopWhichRestsThePlate) {
  Device d;
  d.zforce_model.load_trace(stroke());
  d.board.send_udp(condition(protocol::ConditionKind::Frictionmap));
  d.run_until(1200000);
  d.ticks_alive = false;  // the last tick: 1.2 s; the loop saw it at 1.2001 s
  d.run_until(1250000);
  EXPECT_EQ(d.dac_at(1210100), kFrictionmapOnPath);
  EXPECT_EQ(d.dac_at(1210200), 0);  // over 10 ms without a tick: rested by the loop
  EXPECT_EQ(d.dac.last(), 0);
  EXPECT_EQ(d.counters().tick_stalls, 1u);
  ASSERT_FALSE(d.board.kicks.empty());
  EXPECT_EQ(d.board.kicks.back(), 1210100u);  // and the hardware watchdog starves
  d.ticks_alive = true;
  d.run_until(1300000);
  EXPECT_EQ(d.dac_at(1300000), kFrictionmapOnPath);
  EXPECT_GT(d.board.kicks.back(), 1250000u);
  EXPECT_EQ(d.counters().tick_stalls, 1u);
  d.ticks_alive = false;  // a second stall is caught as the first was
  d.run_until(1350000);
  EXPECT_EQ(d.dac.last(), 0);
  EXPECT_EQ(d.counters().tick_stalls, 2u);
  EXPECT_EQ(status_at(d, 1350000).device[protocol::DeviceCount::TickStalls], 2u);
}

TEST(FirmwareApp, StatusOverHidCarriesTheTickCostAndFaults) {
  Device d;
  d.zforce_model.load_trace(stroke());
  d.board.send_hid(condition(protocol::ConditionKind::Heightmap, 0.66f, 3));
  d.run_until(1500000);
  d.board.send_hid(command(MessageType::QueryStatus, 4));
  d.run_until(1501000);
  EXPECT_TRUE(d.board.udp_of(MessageType::Status).empty());  // replies go back on USB
  const auto status = d.board.hid_of(MessageType::Status);
  ASSERT_EQ(status.size(), 1u);
  const protocol::StatusMessage& st = status[0].status;
  EXPECT_EQ(status[0].sequence, 4);
  EXPECT_EQ(st.firmware_version, kFirmwareVersion);
  EXPECT_EQ(st.kind, protocol::ConditionKind::Heightmap);
  EXPECT_FLOAT_EQ(st.strength, 0.66f);
  EXPECT_EQ(st.ticks, 1500000u / 500u);  // every tick from 0.5 ms to 1.5 s
  EXPECT_EQ(st.tick_cycles_mean, 900u);  // the fake counter's cost per tick
  EXPECT_EQ(st.tick_cycles_max, 900u);
  EXPECT_EQ(st.isr_cycles_mean, 1000u);
  EXPECT_EQ(st.isr_cycles_max, 1000u);
  EXPECT_EQ(st.isr_cycles_p99, 1024u);  // the upper edge of 1000's 128-cycle bin, 896 .. 1024
  EXPECT_TRUE(st.finger_present);
  EXPECT_NEAR(static_cast<double>(st.carrier_hz), 34900.0, 0.3);
  EXPECT_EQ(st.faults[Fault::TouchDown], 1u);
  // Strength 0.66 around the centre: 0.5 + 0.66 * 0.25005 = 0.66503 -> round(2723.3) = 2723.
  EXPECT_EQ(d.dac_at(1500000), 2723);
}

TEST(FirmwareApp, TheStatusSaysWhereTheSensorPutsItsTimestamp) {
  for (bool inside : {false, true}) {
    Device d(false, 0, inside);
    d.zforce_model.load_trace(stroke());
    d.run_until(1500000);
    const uint32_t reports = d.app->sensor().count(ZforceCount::Samples);
    d.board.send_udp(command(MessageType::QueryStatus));
    d.run_until(1501000);
    ASSERT_EQ(d.board.udp_of(MessageType::Status).size(), 1u);
    const protocol::StatusMessage st = d.board.udp_of(MessageType::Status)[0].status;  // a copy: udp_of returns a new vector
    EXPECT_GT(reports, 90u);
    EXPECT_EQ(st.zforce_layout_beside, inside ? 0u : reports) << inside;
    EXPECT_EQ(st.zforce_layout_inside, inside ? reports : 0u) << inside;
  }
}

TEST(FirmwareApp, StreamsEveryTickAndReportWithoutLossWhileTheHostReads) {
  Device d;
  d.zforce_model.load_trace(stroke());
  d.board.send_udp(condition(protocol::ConditionKind::Frictionmap));
  const uint32_t reports_before = start_stream(d, 1100000, 1);
  const uint32_t reports_streamed = stop_stream(d, 1300000) - reports_before;
  d.run_until(1400000);

  const std::vector<protocol::TickRecord> ticks = ticks_received(d);
  const size_t samples = samples_received(d);
  // Streaming from the loop at 1.1 s to the loop at 1.3 s: ticks 1.1 .. 1.2995 s, all 400, in order.
  ASSERT_EQ(ticks.size(), 400u);
  for (size_t i = 0; i < ticks.size(); ++i) {
    ASSERT_EQ(ticks[i].t_us, 1100000u + 500u * i);
    ASSERT_EQ(ticks[i].dac, kFrictionmapOnPath);
    ASSERT_TRUE(ticks[i].present);
  }
  EXPECT_EQ(samples, reports_streamed);
  EXPECT_NEAR(static_cast<double>(samples), 40.0, 1.0);  // 200 Hz for 0.2 s
  // Records wait to fill a message, up to kStreamFlushUs from the start: no early scrap.
  for (size_t i = 0; i < d.board.hid_out.size(); ++i) {
    if (d.board.hid_out[i].type == MessageType::Ticks) {
      EXPECT_GE(d.board.hid_out_us[i], 1100000u + kStreamFlushUs);
      break;
    }
  }
  EXPECT_FALSE(d.board.hid_of(MessageType::Force).empty());  // telemetry joins the stream
  EXPECT_EQ(d.counters().stream_overruns, 0u);
  EXPECT_EQ(d.counters().hid_frames_dropped, 0u);
  const auto acks = d.board.hid_of(MessageType::Ack);
  ASSERT_EQ(acks.size(), 2u);
  EXPECT_EQ(acks[1].ack.command, MessageType::StopStream);
  EXPECT_EQ(acks[0].sequence, 9);  // a reply echoes its command's sequence; the stream is no reply
  for (const Message& m : d.board.hid_out) {
    if (m.type == MessageType::Samples || m.type == MessageType::Ticks || m.type == MessageType::Force) {
      ASSERT_EQ(m.sequence, 0) << static_cast<int>(m.type);
    }
  }
}

TEST(FirmwareApp, AStreamedRecordWaitsAtMostTheFlushTime) {
  // Every 40th tick (50 per second): a Ticks message of 32 would take 0.64 s
  // to fill; a record goes out within kStreamFlushUs instead, also after the
  // host stopped reading for 0.6 s (long enough to fill the device's outbox).
  Device d;
  d.zforce_model.load_trace(stroke());
  Message start = command(MessageType::StartStream);
  start.stream.tick_decimation = 40;
  d.board.send_hid(start);
  d.run_until(1300000);
  d.host_reads = false;
  d.run_until(1900000);
  d.host_reads = true;
  d.run_until(2200000);
  size_t records = 0;
  for (size_t i = 0; i < d.board.hid_out.size(); ++i) {
    const Message& m = d.board.hid_out[i];
    const uint32_t sent = d.board.hid_out_us[i];
    if (sent >= 1300000 && sent < 1960000) continue;  // waited for the host, then in the outbox
    if (m.type == MessageType::Ticks) {
      for (int k = 0; k < m.ticks.count; ++k, ++records) {
        ASSERT_LE(sent - m.ticks.ticks[k].t_us, kStreamFlushUs + 100u) << sent;
      }
    }
    if (m.type == MessageType::Samples) {
      for (int k = 0; k < m.samples.count; ++k, ++records) {
        ASSERT_LE(sent - m.samples.samples[k].t_us, kStreamFlushUs + 1000u) << sent;
      }
    }
  }
  EXPECT_GT(records, 100u);
  // Force, every 30 ms, is not kept for the host: each one it had no room for is counted.
  const std::vector<Message> force = d.board.hid_of(MessageType::Force);
  ASSERT_GT(force.size(), 2u);
  uint32_t missing = 0;
  for (size_t i = 1; i < force.size(); ++i) missing += (force[i].force.t_us - force[i - 1].force.t_us + 15000) / 30000 - 1;
  EXPECT_GT(missing, 0u);
  EXPECT_EQ(d.counters().hid_frames_dropped, missing);
}

// A host that stops reading for 0.6 s, long enough to fill the outbox: then
// 24 reports with their taken times wait, a Samples message of 7 reports
// (more than the SEREMU queue's 6).
TEST(FirmwareApp, SamplesFlowAgainAfterTheHostPausedReading) {
  Device d;
  d.zforce_model.load_trace(stroke());
  start_stream(d, 1100000, 40);
  d.run_until(1200000);
  d.host_reads = false;
  d.run_until(1800000);
  d.host_reads = true;
  const uint32_t reports_at_resume = d.app->sensor().count(ZforceCount::Samples);
  d.run_until(2600000);
  const uint32_t reports_since = d.app->sensor().count(ZforceCount::Samples) - reports_at_resume;
  ASSERT_GT(reports_since, 100u);
  size_t samples_after = 0;
  bool a_full_message = false;
  const std::vector<Message>& out = d.board.hid_out;
  for (size_t i = 0; i < out.size(); ++i) {
    if (out[i].type != MessageType::Samples) continue;
    a_full_message |= out[i].samples.count == protocol::kMaxSamplesPerMessage && out[i].samples.has_taken_times;
    for (int k = 0; k < out[i].samples.count; ++k) samples_after += out[i].samples.samples[k].t_us >= 1800000;
  }
  EXPECT_TRUE(a_full_message);
  // Lost at most while the outbox drains (~25 ms, 1 report per ms): counted as overruns.
  EXPECT_GE(samples_after + 10, reports_since) << "the stream stalled: " << d.counters().stream_overruns << " overruns";
}

TEST(FirmwareApp, StoppingWhileTheHostIsNotReadingCountsWhatIsDroppedOnce) {
  Device d;
  d.zforce_model.load_trace(stroke());
  const uint32_t reports_before = start_stream(d, 1100000, 1);
  d.run_until(1200000);
  d.host_reads = false;  // long enough to fill the device's outbox too
  const uint32_t reports_streamed = stop_stream(d, 1300000) - reports_before;
  d.board.send_hid(command(MessageType::StopStream));  // asked again: nothing is counted twice
  d.run_until(1310000);
  d.host_reads = true;
  d.run_until(1400000);
  // Ticks 1.1 .. 1.2995 s (400) and every report: each sent or counted.
  EXPECT_GT(d.counters().stream_overruns, 0u);
  EXPECT_EQ(ticks_received(d).size() + samples_received(d) + d.counters().stream_overruns, 400u + reports_streamed);

  // A new stream starts clean: its reports arrive, each with the tick that took it.
  const size_t messages_before = d.board.hid_out.size();
  const uint32_t reports_at_start = start_stream(d, 1400100, 1);
  const uint32_t reports_again = stop_stream(d, 1500000) - reports_at_start;
  d.run_until(1600000);
  std::vector<Message> again;
  for (size_t i = messages_before; i < d.board.hid_out.size(); ++i) {
    if (d.board.hid_out[i].type == MessageType::Samples) again.push_back(d.board.hid_out[i]);
  }
  ASSERT_GT(again.size(), 2u);
  size_t samples_again = 0;
  for (size_t i = 0; i < again.size(); ++i) {
    samples_again += again[i].samples.count;
    if (i + 1 < again.size()) {
      EXPECT_TRUE(again[i].samples.has_taken_times) << i;  // the stop's may not
    }
  }
  EXPECT_EQ(samples_again, reports_again);
}

TEST(FirmwareApp, AStreamStartedAgainLosesNothing) {
  // Every tick from 1.1 s to the stop at 1.3 s arrives once, in order, across
  // a second StartStream at 1.2 s that halves the decimation.
  Device d;
  d.zforce_model.load_trace(stroke());
  start_stream(d, 1100000, 2);
  start_stream(d, 1200000, 1);
  d.run_until(1299900);
  d.board.send_hid(command(MessageType::StopStream));
  d.run_until(1400000);
  const std::vector<protocol::TickRecord> ticks = ticks_received(d);
  // 1.1 .. 1.1995 s every 2nd tick (100), 1.2 .. 1.2995 s every tick (200).
  ASSERT_EQ(ticks.size(), 300u);
  for (size_t i = 1; i < ticks.size(); ++i) ASSERT_GT(ticks[i].t_us, ticks[i - 1].t_us) << i;
  EXPECT_EQ(d.counters().stream_overruns, 0u);
  const auto acks = d.board.hid_of(MessageType::Ack);
  ASSERT_EQ(acks.size(), 3u);
  EXPECT_EQ(acks[1].ack.command, MessageType::StartStream);
}

TEST(FirmwareApp, TicksStreamedWithoutAFingerAreNoReplyEither) {
  Device d;
  d.board.send_hid(command(MessageType::StartStream, 9));
  d.run_until(1200000);
  const auto ticks = d.board.hid_of(MessageType::Ticks);
  ASSERT_FALSE(ticks.empty());
  for (const Message& m : ticks) ASSERT_EQ(m.sequence, 0);
}

TEST(FirmwareApp, AHostThatStopsReadingCostsCountedRecordsNeverABlockedLoop) {
  Device d;
  d.zforce_model.load_trace(stroke());
  const uint32_t reports_before = start_stream(d, 1100000, 2);
  d.run_until(1200000);
  d.host_reads = false;  // ffctl hangs for 0.4 s
  d.run_until(1600000);
  d.board.send_hid(command(MessageType::QueryStatus));  // no room for the reply: dropped, counted
  d.run_until(1610000);
  EXPECT_TRUE(d.board.hid_of(MessageType::Status).empty());
  EXPECT_GE(d.counters().hid_frames_dropped, 1u);
  d.host_reads = true;
  const uint32_t reports_streamed = stop_stream(d, 1800000) - reports_before;
  d.run_until(1900000);

  const std::vector<protocol::TickRecord> ticks = ticks_received(d);
  const size_t samples = samples_received(d);
  for (size_t i = 1; i < ticks.size(); ++i) ASSERT_GT(ticks[i].t_us, ticks[i - 1].t_us);
  // Every record streamed (every 2nd tick from 1.1 s to 1.8 s, and every report) arrived or was counted.
  const FirmwareCounters c = d.counters();
  EXPECT_GT(c.stream_overruns, 0u);
  EXPECT_EQ(ticks.size() + samples + c.stream_overruns, 700u + reports_streamed);
  // Streaming resumed after the hang: records up to the stop (the last few may be counted as lost when the
  // final flush finds the host's queue full).
  EXPECT_GE(ticks.back().t_us, 1790000u);
  EXPECT_EQ(d.board.undecodable, 0);
  EXPECT_EQ(d.counters().watchdog_trips, 0u);
  d.board.send_hid(command(MessageType::QueryStatus));  // the host is told what it lost
  d.run_until(1910000);
  ASSERT_EQ(d.board.hid_of(MessageType::Status).size(), 1u);
  const protocol::StatusMessage st = d.board.hid_of(MessageType::Status)[0].status;
  EXPECT_EQ(st.stream_overruns, c.stream_overruns);
  EXPECT_EQ(st.device[protocol::DeviceCount::HidFramesDropped], c.hid_frames_dropped);
  EXPECT_GE(c.hid_frames_dropped, 1u);
}

TEST(FirmwareApp, AnAddressThatDoesNotAnswerIsCountedAndLeftAloneUntilItSpeaks) {
  Device d;
  d.board.udp_unanswered = true;
  d.board.send_udp(command(MessageType::QueryStatus));  // the reply, then force every 30 ms
  d.run_until(1300000);
  EXPECT_EQ(d.board.udp_attempts, 1);
  EXPECT_EQ(d.counters().udp_send_failures, 1u);
  d.board.udp_unanswered = false;
  d.board.send_udp(command(MessageType::QueryStatus));
  d.run_until(1310000);
  ASSERT_EQ(d.board.udp_of(MessageType::Status).size(), 1u);
  EXPECT_EQ(d.board.udp_of(MessageType::Status)[0].status.device[protocol::DeviceCount::UdpSendFailures], 1u);
  EXPECT_EQ(d.counters().udp_send_failures, 1u);
}

TEST(FirmwareApp, AFloodOfDatagramsIsTakenFourPerLoop) {
  Device d;
  for (int i = 0; i < 10; ++i) d.board.send_udp(command(MessageType::QueryStatus, static_cast<uint8_t>(i)));
  d.step();
  EXPECT_EQ(d.board.udp_of(MessageType::Status).size(), static_cast<size_t>(kMaxDatagramsPerLoop));
  d.step();
  d.step();
  const auto status = d.board.udp_of(MessageType::Status);
  ASSERT_EQ(status.size(), 10u);
  for (size_t i = 0; i < status.size(); ++i) EXPECT_EQ(status[i].sequence, i);
}

TEST(FirmwareApp, CarrierSetAndSweptByMessage) {
  Device d;
  Message carrier = command(MessageType::SetCarrier);
  carrier.carrier.frequency_hz = 35200.0f;
  d.board.send_udp(carrier);
  d.run_until(1100000);
  EXPECT_NEAR(d.dds.output_hz(), 35200.0, 0.3);  // written to the idle register, then selected
  EXPECT_EQ(d.dds.total_faults(), 0u);

  carrier.carrier.frequency_hz = 500.0f;  // below any plate mode: refused, carrier unchanged
  d.board.send_udp(carrier);
  d.run_until(1200000);
  EXPECT_EQ(d.board.udp_of(MessageType::Ack).back().ack.status, protocol::AckStatus::Refused);
  EXPECT_NEAR(d.dds.output_hz(), 35200.0, 0.3);

  Message sweep = command(MessageType::StartSweep);
  sweep.sweep = {30000.0f, 40000.0f, 100};  // 100 Hz per ms
  d.board.send_udp(sweep);
  d.run_until(1250000);  // halfway
  EXPECT_EQ(d.board.udp_of(MessageType::Ack).back().ack.status, protocol::AckStatus::Ok);
  EXPECT_NEAR(static_cast<double>(d.app->carrier_hz()), 35000.0, 100.0);
  d.run_until(1350000);
  EXPECT_NEAR(d.dds.output_hz(), 40000.0, 0.3);  // lands on the end
  EXPECT_EQ(d.dds.total_faults(), 0u);
  d.board.send_udp(command(MessageType::QueryStatus));
  d.run_until(1351000);
  // Status reports the register that plays: word 143166 = 40000.12 Hz.
  EXPECT_NEAR(static_cast<double>(d.board.udp_of(MessageType::Status).back().status.carrier_hz), 40000.12, 0.01);

  sweep.sweep = {40000.0f, 30000.0f, 100};
  d.board.send_udp(sweep);
  d.run_until(1380000);
  carrier.carrier.frequency_hz = 34900.0f;  // a carrier mid-sweep ends the sweep there
  d.board.send_udp(carrier);
  d.run_until(1500000);
  EXPECT_EQ(d.dds.output_word(), 124912u);
  sweep.sweep.duration_ms = 0;
  d.board.send_udp(sweep);
  d.run_until(1510000);
  EXPECT_EQ(d.board.udp_of(MessageType::Ack).back().ack.status, protocol::AckStatus::Refused);
  EXPECT_EQ(d.dds.output_word(), 124912u);
}

TEST(FirmwareApp, AFailedSensorIsStartedAgainAndThePlateRestsMeanwhile) {
  Device d(/*sensor_unplugged=*/true);
  d.board.send_udp(condition(protocol::ConditionKind::Neutral));  // would play 0.5 with a finger
  const protocol::StatusMessage failed = status_at(d, 1490000);  // the host can tell why nothing is felt
  ASSERT_EQ(d.app->sensor().state(), ZforceState::Failed);
  EXPECT_EQ(failed.sensor_state, protocol::SensorState::Failed);
  EXPECT_GT(failed.sensor_counts[static_cast<int>(ZforceCount::BusError)], 0u);
  EXPECT_EQ(failed.device[protocol::DeviceCount::SensorRestarts], 0u);
  for (const auto& w : d.dac.writes()) ASSERT_EQ(w.code, 0) << "at " << w.t_us;  // no finger: idle
  d.i2c.fail_next(0, BusStatus::Ok);  // plugged in again
  d.zforce_model.load_trace(stroke(5000000));
  const protocol::StatusMessage running = status_at(d, 5490000);
  EXPECT_EQ(d.counters().sensor_restarts, 1u);
  EXPECT_EQ(running.device[protocol::DeviceCount::SensorRestarts], 1u);
  EXPECT_EQ(running.sensor_state, protocol::SensorState::Running);
  EXPECT_EQ(d.app->sensor().state(), ZforceState::Running);
  EXPECT_EQ(d.dac_at(5500000), 2048);  // the neutral scene, with the finger back
}

TEST(FirmwareApp, AFailedSensorIsTriedAgainOneRetryPeriodAfterEachFailure) {
  Device d(/*sensor_unplugged=*/true);
  std::vector<uint32_t> failed_at, restarted_at;
  bool failed = false;
  uint32_t restarts = 0;
  while (d.now < 8000000) {
    d.step();
    const bool now_failed = d.app->sensor().state() == ZforceState::Failed;
    if (now_failed && !failed) failed_at.push_back(d.now);
    failed = now_failed;
    if (d.counters().sensor_restarts != restarts) {
      restarts = d.counters().sensor_restarts;
      restarted_at.push_back(d.now);
    }
  }
  ASSERT_GE(restarted_at.size(), 2u);
  ASSERT_GE(failed_at.size(), restarted_at.size());
  for (size_t i = 0; i < restarted_at.size(); ++i) {
    // The loop that sees the failure starts the wait; one that sees it kSensorRetryUs later restarts.
    EXPECT_GE(restarted_at[i] - failed_at[i], kSensorRetryUs) << i;
    EXPECT_LE(restarted_at[i] - failed_at[i], kSensorRetryUs + 100u) << i;
  }
}

TEST(FirmwareApp, RebootRestsThePlateFirst) {
  Device d;
  d.zforce_model.load_trace(stroke());
  d.board.send_udp(condition(protocol::ConditionKind::Frictionmap));
  d.run_until(1200000);
  EXPECT_EQ(d.dac.last(), kFrictionmapOnPath);
  int dac_after_tick = -1;
  d.board.while_rebooting = [&] {
    d.tick_at(d.now + 250);
    dac_after_tick = d.dac.last();
  };
  d.board.send_hid(command(MessageType::RebootToBootloader));
  d.run_until(1201000);
  // Acknowledged, the plate at rest, and the restart kept back until the Ack has left.
  ASSERT_EQ(d.board.hid_of(MessageType::Ack).size(), 1u);
  EXPECT_EQ(d.board.reboots, 0);
  EXPECT_EQ(d.dac.last(), 0);
  d.run_until(1200000 + kRebootDelayUs - 500);
  EXPECT_EQ(d.board.reboots, 0);
  EXPECT_EQ(d.dac.last(), 0) << "the ticks meanwhile keep it resting, the finger moving";
  d.run_until(1201000 + kRebootDelayUs);
  EXPECT_EQ(d.board.reboots, 1);
  EXPECT_EQ(d.board.dac_at_reboot, 0);
  EXPECT_EQ(dac_after_tick, 0);  // the tick keeps it resting until the reset
}

Message sensor_profile(const SensorProfile& p, uint8_t sequence) {
  Message m = command(MessageType::SetSensorProfile, sequence);
  m.sensor_profile = p;
  return m;
}

const SensorProfile kMeasured{1.5f, 0.5f, 250.0f, 0.25f, 180.0f, 400.0f, 3000u, 9.5f};

TEST(FirmwareApp, ASensorProfileReachesTheTrackerAtTheNextTickNotInTheLoop) {
  Device d;
  d.zforce_model.load_trace(stroke());
  d.board.send_udp(condition(protocol::ConditionKind::Heightmap));
  EXPECT_EQ(d.pipeline->tracker().config().sensor, SensorProfile{});  // start-up: the default
  d.run_until(1200000);
  ASSERT_EQ(d.dac_at(1200000), kHeightmapOnPathMovingRight);

  // The loop pass at 1.2001 s takes the message and acknowledges it; the
  // tracker is the tick's, untouched until the tick at 1.2005 s.
  d.board.send_udp(sensor_profile(kMeasured, 11));
  d.step();
  ASSERT_EQ(d.now, 1200100u);
  const auto acks = d.board.udp_of(MessageType::Ack);
  ASSERT_EQ(acks.back().sequence, 11);
  EXPECT_EQ(acks.back().ack.command, MessageType::SetSensorProfile);
  EXPECT_EQ(acks.back().ack.status, protocol::AckStatus::Ok);
  d.run_until(1200400);
  EXPECT_EQ(d.pipeline->tracker().config().sensor, SensorProfile{});
  d.step();  // 1.2005 s: the tick
  EXPECT_EQ(d.pipeline->tracker().config().sensor, kMeasured);

  // The new tracker starts afresh: the plate rests until the finger's next
  // report (stamped 1.205 s), then renders the scene again.
  d.run_until(1300000);
  for (uint32_t t = 1200500; t <= 1204500; t += 500) ASSERT_EQ(d.dac_at(t), 0) << t;
  EXPECT_EQ(d.dac_at(1300000), kHeightmapOnPathMovingRight);
  EXPECT_EQ(d.pipeline->faults()[Fault::TouchDown], 2u);

  // The host reads it back.
  d.board.send_udp(command(MessageType::QuerySensorProfile, 12));
  d.run_until(1301000);
  const auto replies = d.board.udp_of(MessageType::SensorProfile);
  ASSERT_EQ(replies.size(), 1u);
  EXPECT_EQ(replies[0].sequence, 12);
  EXPECT_EQ(replies[0].sensor_profile, kMeasured);
  EXPECT_EQ(d.counters().sensor_profiles_set, 1u);
  EXPECT_EQ(d.board.undecodable, 0);
}

TEST(FirmwareApp, ARefusedSensorProfileIsCountedAndTheTrackerKeepsItsFinger) {
  Device d;
  d.zforce_model.load_trace(stroke());
  d.board.send_hid(condition(protocol::ConditionKind::Heightmap));
  d.board.send_hid(sensor_profile(kMeasured, 2));
  d.run_until(1200000);
  SensorProfile wander_without_time = kMeasured;
  wander_without_time.correlation_time_ms = 0.0f;
  SensorProfile slow = kMeasured;
  slow.report_rate_hz = 5.0f;  // below 10 Hz
  d.board.send_hid(sensor_profile(wander_without_time, 3));
  d.board.send_hid(sensor_profile(slow, 4));
  d.run_until(1250000);
  d.board.send_hid(command(MessageType::QueryStatus, 5));
  d.board.send_hid(command(MessageType::QuerySensorProfile, 6));
  d.run_until(1300000);
  const auto acks = d.board.hid_of(MessageType::Ack);
  ASSERT_EQ(acks.size(), 4u);  // condition, profile, two refused
  EXPECT_EQ(acks[1].ack.status, protocol::AckStatus::Ok);
  for (size_t i : {2u, 3u}) {
    EXPECT_EQ(acks[i].sequence, i + 1);
    EXPECT_EQ(acks[i].ack.command, MessageType::SetSensorProfile);
    EXPECT_EQ(acks[i].ack.status, protocol::AckStatus::Refused);
  }
  EXPECT_EQ(d.counters().sensor_profiles_refused, 2u);
  EXPECT_EQ(d.counters().sensor_profiles_set, 1u);
  EXPECT_EQ(d.counters().protocol_errors, 0u);  // well-formed, only refused
  const auto status = d.board.hid_of(MessageType::Status);
  ASSERT_EQ(status.size(), 1u);
  EXPECT_EQ(status[0].status.faults[Fault::BadSensorProfile], 2u);
  const auto active = d.board.hid_of(MessageType::SensorProfile);
  ASSERT_EQ(active.size(), 1u);
  EXPECT_EQ(active[0].sensor_profile, kMeasured);
  EXPECT_EQ(d.pipeline->tracker().config().sensor, kMeasured);
  // Not reconfigured: the finger tracked throughout, the scene rendered on.
  EXPECT_EQ(d.pipeline->faults()[Fault::TouchDown], 1u);
  for (uint32_t t = 1200000; t <= 1300000; t += 500) ASSERT_EQ(d.dac_at(t), kHeightmapOnPathMovingRight) << t;
}


TEST(FirmwareApp, TheStatusCarriesWhatTheFirmwareCountsAndTheSensorsState) {
  using protocol::DeviceCount;
  Device d;  // no finger all along: the load cells may re-zero
  const auto send = [&d](const Message& m) {  // one at a time: every reply has room
    d.board.send_hid(m);
    d.run_until(d.now + 5000);
  };
  for (uint8_t i = 0; i < 3; ++i) send(condition(protocol::ConditionKind::Neutral, 1.0f, i));
  Message general = condition(protocol::ConditionKind::General, 1.0f, 3);  // a 1 px float table: too large
  general.condition.scene.rendering = Rendering::Directional;
  general.condition.scene.evaluation = Evaluation::Table;
  general.condition.scene.table = {1.0f, TableStorage::Float32, TableSource::TabulatedGradient};
  general.condition.scene.add(FieldElement::vortex({400, 240}, 1.0f));
  send(general);
  SensorProfile slow = kMeasured;
  slow.report_rate_hz = 5.0f;  // below 10 Hz
  for (uint8_t i = 0; i < 2; ++i) send(sensor_profile(kMeasured, static_cast<uint8_t>(10 + i)));
  for (uint8_t i = 0; i < 4; ++i) send(sensor_profile(slow, static_cast<uint8_t>(20 + i)));
  d.run_until(1000000);  // tared long since (5 readings from 30 ms on)
  d.adc.fail_next(5);    // each failed reading stops at its first channel: 5 readings lost
  d.run_until(1200000);
  for (uint8_t ch = 0; ch < 4; ++ch) d.adc.set(ch, 101);  // +4 counts, 42 mN: drift, re-zeroed
  const protocol::StatusMessage st = status_at(d, 1500000);

  protocol::DeviceCounts want;
  want[DeviceCount::ConditionsSet] = 3;
  want[DeviceCount::ConditionsRefused] = 1;
  want[DeviceCount::SensorProfilesSet] = 2;
  want[DeviceCount::SensorProfilesRefused] = 4;
  want[DeviceCount::ForceReadErrors] = 5;
  want[DeviceCount::ForceRezeros] = 5;  // once per reading while the step passes through the 5-reading mean
  expect_device_counts(st.device, want);
  EXPECT_EQ(st.sensor_state, protocol::SensorState::Running);
  ASSERT_EQ(st.sensor_count_n, static_cast<uint8_t>(ZforceCount::kCount));
  EXPECT_EQ(st.sensor_counts[static_cast<int>(ZforceCount::FramesRead)], 7u);  // boot complete and six answers
  EXPECT_EQ(st.sensor_counts[static_cast<int>(ZforceCount::Samples)], 0u);
}

TEST(FirmwareApp, TheStatusSaysTheLoadCellsSawSomethingRestingOnThePlate) {
  using protocol::DeviceCount;
  Device d;
  d.run_until(1000000);
  for (uint8_t ch = 0; ch < 4; ++ch) d.adc.set(ch, 120);  // +80 counts: 16 a reading into the mean, 168 mN
  const protocol::StatusMessage st = status_at(d, 1300000);
  EXPECT_EQ(st.device[DeviceCount::ForceRezeros], 0u);
  // Every reading from the step on (1.02 s, then each 30 ms to 1.29 s): 10.
  EXPECT_EQ(st.device[DeviceCount::ForceRezerosRefused], 10u);
  EXPECT_EQ(st.device[DeviceCount::ForcePeriodsMissed], 0u);
}

}  // namespace
}  // namespace ff::firmware
