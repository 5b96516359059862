// ffctl without hardware. Two fake devices: the firmware itself
// (firmware/app) on emulated peripherals, reached through a transport that
// moves USB packets as HidTransport writes them and advances simulated time
// while ffctl waits; and a scripted device for replies the firmware would
// never send.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <deque>
#include <filesystem>
#include <functional>
#include <fstream>
#include <memory>
#include <sstream>
#include <thread>

#include <unistd.h>

#include "device_client.hpp"
#include "firmware/app/firmware_app.hpp"
#include "frictionfield/core/scenes.hpp"
#include "frictionfield/emulated/ad9834_model.hpp"
#include "frictionfield/emulated/i2c_bus.hpp"
#include "frictionfield/emulated/recording_dac.hpp"
#include "frictionfield/emulated/scripted_adc.hpp"
#include "frictionfield/emulated/zforce_model.hpp"
#include "frictionfield/host/scene_file.hpp"
#include "frictionfield/host/trace_csv.hpp"
#include "frictionfield/protocol/hid_channel.hpp"
#include "emulated_firmware.hpp"
#include "hid_transport.hpp"
#include "support/file_contents.hpp"
#include "support/file_size_limit.hpp"
#include "support/scratch_path.hpp"

namespace ff::ffctl {
namespace {

using protocol::Message;
using protocol::MessageType;

class SimulatedDevice final : public Transport, public firmware::Board {
 public:
  SimulatedDevice() {
    fw_.start(*this);
    while (fw_.app->sensor().state() != ZforceState::Running && fw_.now < 1000000) fw_.step();
    // A finger along the middle path at 300 px/s for 3 s.
    std::vector<SensorSample> trace;
    for (uint32_t t = 1000000; t <= 4000000; t += 5000) {
      trace.push_back({t, 100.0f + 200.0f * static_cast<float>(t - 1000000) * 1e-6f, 240.0f, true});
    }
    fw_.zforce.load_trace(trace);
  }

  // Transport: as HidTransport writes them, each 64-byte report as two
  // 32-byte OUT reports (SEREMU_RX_SIZE).
  bool send(const uint8_t* frame, size_t size) override {
    if (disconnected) return false;
    uint8_t reports[protocol::kMaxHidReports][protocol::kHidReportBytes];
    const size_t n = protocol::split_into_reports(frame, size, reports, protocol::kMaxHidReports);
    for (size_t i = 0; i < n; ++i) {
      for (size_t half = 0; half < 2; ++half) {
        const uint8_t* p = reports[i] + half * kSeremuOutReportBytes;
        packets_to_device_.emplace_back(p, p + kSeremuOutReportBytes);
      }
    }
    return true;
  }
  bool request_bootloader() override {
    ++feature_reboots;
    return true;
  }
  ReceiveResult receive(std::vector<uint8_t>& frame, int timeout_ms) override {
    const uint32_t until = fw_.now + static_cast<uint32_t>(timeout_ms) * 1000u;
    while (from_device_.empty() && static_cast<int32_t>(until - fw_.now) > 0) fw_.step();
    if (from_device_.empty()) return ReceiveResult::Timeout;
    if (disconnect_after_frames >= 0 && frames_delivered_ >= disconnect_after_frames) {
      disconnected = true;
      return ReceiveResult::Disconnected;
    }
    frame = from_device_.front();
    from_device_.pop_front();
    ++frames_delivered_;
    if (corrupt_next_reply) {
      frame[frame.size() - 1] ^= 0x5A;  // bad CRC
      corrupt_next_reply = false;
    }
    return ReceiveResult::Frame;
  }

  // Board.
  bool mouse_move_to(int, int) override { return true; }
  bool udp_receive(uint8_t*, size_t, size_t&, firmware::UdpEndpoint&) override { return false; }
  bool udp_send(const firmware::UdpEndpoint&, const uint8_t*, size_t) override { return true; }
  // The Teensy binding's part: raw OUT packets joined in pairs.
  bool hid_receive(uint8_t* report) override {
    if (packets_to_device_.size() < 2) return false;
    for (size_t half = 0; half < 2; ++half) {
      std::copy(packets_to_device_.front().begin(), packets_to_device_.front().end(),
                report + half * kSeremuOutReportBytes);
      packets_to_device_.pop_front();
    }
    return true;
  }
  void hid_send(const uint8_t* report) override {
    if (reassembler_.push(report)) from_device_.emplace_back(reassembler_.frame(), reassembler_.frame() + reassembler_.size());
  }
  uint32_t cycles() override { return cycles_ += 700; }
  void reboot_to_bootloader() override { ++reboots; }

  // Device time goes on by `us` (the loop and the tick) without the host.
  void run_for(uint32_t us) {
    const uint32_t until = fw_.now + us;
    while (static_cast<int32_t>(until - fw_.now) > 0) fw_.step();
  }

  int disconnect_after_frames = -1;
  bool corrupt_next_reply = false;
  bool disconnected = false;
  int reboots = 0;
  int feature_reboots = 0;

 private:
  EmulatedFirmware fw_;
  protocol::HidReassembler reassembler_;
  std::deque<std::vector<uint8_t>> packets_to_device_, from_device_;
  uint32_t cycles_ = 0;
  int frames_delivered_ = 0;
};

Message set_heightmap_top() {
  Message m;
  m.type = MessageType::SetCondition;
  m.condition.kind = protocol::ConditionKind::Heightmap;
  m.condition.target = Target::Top;
  m.condition.strength = 0.66f;
  return m;
}

TEST(Ffctl, StatusAndSceneOverTheHostChannel) {
  SimulatedDevice device;
  DeviceClient client(device);
  Message reply;
  std::string error;
  ASSERT_TRUE(client.request(set_heightmap_top(), reply, error)) << error;
  EXPECT_EQ(reply.type, MessageType::Ack);
  EXPECT_EQ(reply.ack.command, MessageType::SetCondition);
  EXPECT_EQ(reply.ack.status, protocol::AckStatus::Ok);
  Message q;
  q.type = MessageType::QueryStatus;
  ASSERT_TRUE(client.request(q, reply, error)) << error;
  EXPECT_EQ(reply.type, MessageType::Status);
  EXPECT_EQ(reply.status.kind, protocol::ConditionKind::Heightmap);
  EXPECT_EQ(reply.status.target, Target::Top);
  EXPECT_FLOAT_EQ(reply.status.strength, 0.66f);
  EXPECT_EQ(reply.status.tick_cycles_mean, 700u);  // the fake cycle counter advances 700 a call
  EXPECT_FLOAT_EQ(reply.status.carrier_hz, 34900.0f);
  EXPECT_EQ(reply.status.protocol_errors, 0u);
  EXPECT_EQ(client.malformed_replies(), 0u);
}

TEST(Ffctl, ARefusedSceneIsAnsweredNotApplied) {
  SimulatedDevice device;
  DeviceClient client(device);
  Message m = set_heightmap_top();
  m.condition.kind = protocol::ConditionKind::General;
  m.condition.scene.rendering = Rendering::Directional;
  m.condition.scene.add(FieldElement::point_sink({400.0f, 240.0f}));
  m.condition.scene.elements[0].point.radius = -5.0f;  // prepare refuses it
  Message reply;
  std::string error;
  ASSERT_TRUE(client.request(m, reply, error)) << error;
  EXPECT_EQ(reply.ack.status, protocol::AckStatus::Refused);
  Message q;
  q.type = MessageType::QueryStatus;
  ASSERT_TRUE(client.request(q, reply, error)) << error;
  EXPECT_EQ(reply.status.kind, protocol::ConditionKind::Neutral);  // unchanged since boot
}

TEST(Ffctl, RecordThenVerifyAgreesTickForTickAndCatchesTampering) {
  SimulatedDevice device;
  DeviceClient client(device);
  Message reply;
  std::string error;
  ASSERT_TRUE(client.request(set_heightmap_top(), reply, error)) << error;
  Recording r;
  int progress_calls = 0, touching_calls = 0;
  ASSERT_TRUE(record(client, 2.5, r, error, [&](const RecordProgress& p) {
    ++progress_calls;
    // What the live view shows is what was recorded so far.
    EXPECT_EQ(p.ticks, r.ticks.size());
    EXPECT_EQ(p.samples, r.samples.size());
    if (!r.samples.empty()) {
      const host::TraceRow& last = r.samples.back().row;
      EXPECT_EQ(p.finger, last.touch);
      EXPECT_EQ(p.x, last.x);
      EXPECT_EQ(p.y, last.y);
      touching_calls += last.touch;
    }
    EXPECT_EQ(p.forces, r.forces.size());
    EXPECT_EQ(p.have_force, !r.forces.empty());
    if (!r.forces.empty()) {
      EXPECT_EQ(p.last_force.t_us, r.forces.back().t_us);
      EXPECT_EQ(p.last_force.force_mN, r.forces.back().force_mN);
    }
    return true;
  })) << error;
  EXPECT_GT(progress_calls, 10);
  EXPECT_GT(touching_calls, 5);
  EXPECT_GT(r.forces.size(), 0u);
  EXPECT_NEAR(static_cast<double>(r.ticks.size()), 5000.0, 120.0);  // 2.5 s of 2 kHz
  for (size_t i = 1; i < r.ticks.size(); ++i) ASSERT_EQ(r.ticks[i].t_us - r.ticks[i - 1].t_us, 500u) << i;
  // The finger arrives 1 s after the stream starts: ~1.5 s of 200 Hz reports.
  EXPECT_GT(r.samples.size(), 280u);
  // It ends mid-stroke: the reports, which trail the ticks by up to the
  // stream's flush, were read on until one taken at or after the last kept tick.
  ASSERT_TRUE(r.samples.back().taken_known);
  EXPECT_GE(r.samples.back().taken_us, r.ticks.back().t_us);

  const std::string path = support::scratch_path("ffctl_rec.csv");
  ASSERT_TRUE(write_recording(path, r, error)) << error;
  Recording back;
  ASSERT_TRUE(read_recording(path, back, error)) << error;
  ASSERT_EQ(back.samples.size(), r.samples.size());
  ASSERT_EQ(back.ticks.size(), r.ticks.size());
  Condition c;
  c.scene = scenes::heightmap(Target::Top);
  c.amplitude.strength = 0.66f;
  const VerifyResult v = verify(back, c);
  EXPECT_TRUE(v.synchronised);
  EXPECT_EQ(v.warm_up, 0u);  // no finger at the start
  EXPECT_EQ(v.compared, r.ticks.size());
  EXPECT_EQ(v.beyond_one_code, 0u);
  EXPECT_LE(v.max_dac_difference, 1);
  EXPECT_EQ(v.missing_ticks, 0u);

  back.ticks[4000].dac = static_cast<uint16_t>(back.ticks[4000].dac ^ 0x400);
  const VerifyResult tampered = verify(back, c);
  ASSERT_EQ(tampered.beyond_one_code, 1u);
  ASSERT_EQ(tampered.runs.size(), 1u);
  EXPECT_EQ(tampered.runs[0].first_t_us, back.ticks[4000].t_us);
  EXPECT_EQ(tampered.runs[0].max_dac_difference, 0x400);
}

TEST(Ffctl, ASensorProfileIsAcknowledgedOrRefusedAndReadBack) {
  SimulatedDevice device;
  DeviceClient client(device);
  SensorProfile active;
  std::string error;
  ASSERT_TRUE(query_sensor_profile(client, active, error)) << error;
  EXPECT_EQ(active.report_rate_hz, SensorProfile{}.report_rate_hz);  // the default since power-on
  Message m, reply;
  m.type = MessageType::SetSensorProfile;
  m.sensor_profile = {2.0f, 0.0f, 0.0f, 0.5f, 120.0f, 300.0f, 8000u};
  ASSERT_TRUE(client.request(m, reply, error)) << error;
  EXPECT_EQ(reply.type, MessageType::Ack);
  EXPECT_EQ(reply.ack.status, protocol::AckStatus::Ok);
  ASSERT_TRUE(query_sensor_profile(client, active, error)) << error;
  EXPECT_EQ(active.white_noise_px, 2.0f);
  EXPECT_EQ(active.report_rate_hz, 120.0f);
  EXPECT_EQ(active.latency_us, 8000u);
  // Outside the limits (a wander without its time): refused, the old one stays.
  m.sensor_profile.correlated_noise_px = 1.0f;
  ASSERT_TRUE(client.request(m, reply, error)) << error;
  EXPECT_EQ(reply.ack.status, protocol::AckStatus::Refused);
  EXPECT_FALSE(command(client, m, error));
  ASSERT_TRUE(query_sensor_profile(client, active, error)) << error;
  EXPECT_EQ(active.correlated_noise_px, 0.0f);
  EXPECT_EQ(active.latency_us, 8000u);
}

TEST(Ffctl, ARecordingKeepsItsSensorProfileBesideItAndDropsAStaleOne) {
  Recording r;
  r.ticks.push_back({500, 0.0f, 0, false});
  r.has_sensor_profile = true;
  r.sensor_profile = {1.25f, 0.75f, 125.0f, 0.5f, 250.0f, 80.0f, 4500u};
  const std::string path = support::scratch_path("ffctl_profile_rec.csv");
  std::string error;
  ASSERT_TRUE(write_recording(path, r, error)) << error;
  Recording back;
  ASSERT_TRUE(read_recording(path, back, error)) << error;
  ASSERT_TRUE(back.has_sensor_profile);
  EXPECT_EQ(back.sensor_profile.correlated_noise_px, 0.75f);
  EXPECT_EQ(back.sensor_profile.correlation_time_ms, 125.0f);
  EXPECT_EQ(back.sensor_profile.latency_us, 4500u);
  EXPECT_EQ(tracker_config_of(back).sensor.white_noise_px, 1.25f);  // verify's tracker is for that sensor
  // The file says it in words and as the flags for ffctl sensor-profile.
  std::ifstream in(sensor_profile_path_for(path));
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_NE(text.str().find("# ffctl sensor-profile --white-noise-px 1.25 --correlated-noise-px 0.75 "
                            "--correlation-time-ms 125 --tremor-px 0.5 --tremor-hz 0 --report-rate-hz 250 --jitter-us 80 "
                            "--latency-us 4500\n"),
            std::string::npos)
      << text.str();

  // Recorded again without one (a firmware before profiles): the old file goes, verify assumes the default.
  r.has_sensor_profile = false;
  ASSERT_TRUE(write_recording(path, r, error)) << error;
  Recording again;
  ASSERT_TRUE(read_recording(path, again, error)) << error;
  EXPECT_FALSE(again.has_sensor_profile);
  EXPECT_EQ(tracker_config_of(again).sensor.white_noise_px, SensorProfile{}.white_noise_px);

  // A profile file whose frame the device would refuse is bad input.
  Message bad;
  bad.type = MessageType::SetSensorProfile;
  bad.sensor_profile.report_rate_hz = 1.0f;
  uint8_t frame[protocol::kMaxFrame];
  const size_t n = protocol::encode(bad, frame, sizeof frame);
  std::ofstream out(sensor_profile_path_for(path));
  out << "frame ";
  for (size_t i = 0; i < n; ++i) out << "0123456789abcdef"[frame[i] >> 4] << "0123456789abcdef"[frame[i] & 15];
  out << "\n";
  out.close();
  Recording refused;
  EXPECT_FALSE(read_recording(path, refused, error));
  EXPECT_NE(error.find("outside SensorProfileLimits"), std::string::npos) << error;
}

TEST(Ffctl, RecordingEndsWhenProgressSaysSo) {
  SimulatedDevice device;
  DeviceClient client(device);
  Recording r;
  std::string error;
  int calls = 0;
  ASSERT_TRUE(record(client, 0.0, r, error, [&](const RecordProgress& p) {
    ++calls;
    return p.done_s < 0.2;  // Ctrl-C after 0.2 s
  })) << error;
  EXPECT_NEAR(static_cast<double>(r.ticks.size()), 400.0, 40.0);
  Message q, reply;
  q.type = MessageType::QueryStatus;
  ASSERT_TRUE(client.request(q, reply, error)) << error;  // the stream was stopped: a plain reply
}

TEST(Ffctl, MalformedRepliesAreCountedAndDisconnectIsReported) {
  SimulatedDevice device;
  DeviceClient client(device);
  Message reply;
  std::string error;
  device.corrupt_next_reply = true;
  EXPECT_FALSE(client.request(set_heightmap_top(), reply, error));  // its only reply was corrupt: no answer
  EXPECT_EQ(client.malformed_replies(), 1u);
  EXPECT_NE(error.find("no reply"), std::string::npos) << error;
  device.disconnect_after_frames = 20;
  Recording r;
  EXPECT_FALSE(record(client, 5.0, r, error));
  EXPECT_NE(error.find("disconnected"), std::string::npos) << error;
  EXPECT_GT(r.ticks.size(), 0u);  // what arrived is kept
}

TEST(Ffctl, ADeviceThatLeavesBeforeItAnswersIsReportedAsGoneNotSilent) {
  SimulatedDevice device;
  DeviceClient client(device);
  device.disconnect_after_frames = 0;  // takes the command, then leaves
  Message reply;
  std::string error;
  EXPECT_FALSE(client.request(set_heightmap_top(), reply, error));
  EXPECT_EQ(error, "the device disconnected");
}

TEST(Ffctl, TheRebootRequestGoesBelowTheProtocolAndTheMessageStillWorks) {
  SimulatedDevice device;
  EXPECT_TRUE(static_cast<Transport&>(device).request_bootloader());
  EXPECT_EQ(device.feature_reboots, 1);
  DeviceClient client(device);
  Message m, reply;
  m.type = MessageType::RebootToBootloader;
  std::string error;
  ASSERT_TRUE(client.request(m, reply, error)) << error;
  EXPECT_EQ(reply.ack.command, MessageType::RebootToBootloader);
  // The acknowledgement leaves before the restart (kRebootDelayUs later), which would drop it.
  EXPECT_EQ(device.reboots, 0);
  device.run_for(firmware::kRebootDelayUs - 1000);
  EXPECT_EQ(device.reboots, 0);
  device.run_for(1100);
  EXPECT_EQ(device.reboots, 1);
}

TEST(Ffctl, RebootAsksTheFirmwareFirstSoThePlateRests) {
  SimulatedDevice device;
  std::string error;
  bool by_transport = true;
  ASSERT_TRUE(reboot_device(device, error, by_transport)) << error;
  EXPECT_FALSE(by_transport);
  device.run_for(firmware::kRebootDelayUs);
  EXPECT_EQ(device.reboots, 1);          // the firmware's own reboot: it rests the plate first
  EXPECT_EQ(device.feature_reboots, 0);  // no feature report when the firmware answers
}

// A device whose firmware never answers, but whose USB stack takes the feature report.
class SilentDevice final : public Transport {
 public:
  bool send(const uint8_t*, size_t) override {
    ++commands;
    return true;
  }
  ReceiveResult receive(std::vector<uint8_t>&, int) override { return ReceiveResult::Timeout; }
  bool request_bootloader() override {
    ++feature_reboots;
    return true;
  }
  int commands = 0, feature_reboots = 0;
};

TEST(Ffctl, RebootFallsBackToTheFeatureReportWithoutAnAck) {
  SilentDevice device;
  std::string error;
  bool by_transport = false;
  ASSERT_TRUE(reboot_device(device, error, by_transport, 20)) << error;
  EXPECT_TRUE(by_transport);
  EXPECT_EQ(device.commands, 1);  // the protocol message went first
  EXPECT_EQ(device.feature_reboots, 1);
}

// --- a scripted device -----------------------------------------------------------

// Answers each command with whatever the test queued for it (frames, already
// encoded or deliberately broken), Pigweed-mock style: sent commands are kept.
class ScriptedDevice final : public Transport {
 public:
  bool send(const uint8_t* frame, size_t size) override {
    Message m;
    EXPECT_EQ(protocol::decode(frame, size, m), protocol::DecodeStatus::Ok);
    sent.push_back(m);
    if (!replies.empty()) {
      for (auto& f : replies.front()(m)) pending_.push_back(f);
      replies.pop_front();
    }
    return true;
  }
  ReceiveResult receive(std::vector<uint8_t>& frame, int) override {
    if (pending_.empty()) return gone_when_quiet ? ReceiveResult::Disconnected : ReceiveResult::Timeout;
    frame = pending_.front();
    pending_.pop_front();
    return ReceiveResult::Frame;
  }

  using Script = std::function<std::vector<std::vector<uint8_t>>(const Message& command)>;
  std::deque<Script> replies;
  std::vector<Message> sent;
  bool gone_when_quiet = false;  // unplugged once every queued frame is read

 private:
  std::deque<std::vector<uint8_t>> pending_;
};

std::vector<uint8_t> encoded(Message m, uint8_t sequence) {
  m.sequence = sequence;
  std::vector<uint8_t> f(protocol::kMaxFrame);
  f.resize(protocol::encode(m, f.data(), f.size()));
  return f;
}

Message ack_for(MessageType command) {
  Message m;
  m.type = MessageType::Ack;
  m.ack.command = command;
  return m;
}

TEST(Ffctl, RepliesAreMatchedBySequenceWhateverArrivesFirst) {
  ScriptedDevice device;
  DeviceClient client(device);
  device.replies.push_back([](const Message& c) {
    Message stale;
    stale.type = MessageType::Error;  // an old command's error: not ours
    stale.error = {protocol::ErrorCode::BadCrc, 0x02};
    std::vector<uint8_t> broken = encoded(ack_for(c.type), c.sequence);
    broken.pop_back();  // truncated: a length mismatch
    Message ticks;
    ticks.type = MessageType::Ticks;
    return std::vector<std::vector<uint8_t>>{encoded(stale, static_cast<uint8_t>(c.sequence - 1)), broken,
                                             encoded(ticks, c.sequence), encoded(ack_for(c.type), c.sequence)};
  });
  Message cmd, reply;
  cmd.type = MessageType::StopStream;
  std::string error;
  ASSERT_TRUE(client.request(cmd, reply, error)) << error;
  EXPECT_EQ(reply.type, MessageType::Ack);
  EXPECT_EQ(client.malformed_replies(), 1u);
}

TEST(Ffctl, EachCommandHasItsOwnSequenceSoALateReplyIsNotTakenForTheNext) {
  ScriptedDevice device;
  DeviceClient client(device);
  device.replies.push_back([](const Message&) { return std::vector<std::vector<uint8_t>>{}; });  // too slow
  device.replies.push_back([&device](const Message& c) {
    Message refused;  // the first command's answer, arriving now
    refused.type = MessageType::Error;
    refused.error = {protocol::ErrorCode::Busy, static_cast<uint8_t>(MessageType::StopStream)};
    return std::vector<std::vector<uint8_t>>{encoded(refused, device.sent.front().sequence),
                                             encoded(ack_for(c.type), c.sequence)};
  });
  Message cmd, reply;
  cmd.type = MessageType::StopStream;
  std::string error;
  EXPECT_FALSE(client.request(cmd, reply, error, 20));
  ASSERT_TRUE(client.request(cmd, reply, error, 200)) << error;
  EXPECT_EQ(reply.type, MessageType::Ack);
  ASSERT_EQ(device.sent.size(), 2u);
  EXPECT_NE(device.sent[0].sequence, device.sent[1].sequence);
}

Message ticks_at(uint64_t t_us) {
  Message m;
  m.type = MessageType::Ticks;
  m.ticks.count = 1;
  m.ticks.ticks[0].t_us = static_cast<uint32_t>(t_us);  // the device's clock wraps
  return m;
}

Message reports_at(std::initializer_list<uint32_t> times) {
  Message m;
  m.type = MessageType::Samples;
  for (uint32_t t : times) m.samples.samples[m.samples.count++] = {t, 10.0f, 20.0f, true};
  return m;
}

// StartStream acknowledged, then `stream` (each message's sequence 0), then silence.
ScriptedDevice::Script streams(std::vector<Message> stream) {
  return [stream](const Message& c) {
    std::vector<std::vector<uint8_t>> frames{encoded(ack_for(c.type), c.sequence)};
    for (const Message& m : stream) frames.push_back(encoded(m, 0));
    return frames;
  };
}

// Counts what reached it and what of that a flush made durable.
struct DurableCount final : RecordSink {
  void sample(const DeviceSample&) override { ++samples; }
  void tick(const DeviceTick&) override { ++ticks; }
  void force(const DeviceForce&) override {}
  bool flush(std::string& error) override {
    durable = samples;
    if (failing_flushes == 0) return true;
    --failing_flushes;
    return error = "cannot write run.csv: No space left on device", false;
  }
  size_t samples = 0, ticks = 0, durable = 0;
  int failing_flushes = 0;  // the next ones fail (a full disk), the rest succeed (space freed)
};

TEST(Ffctl, ARecordingLongerThanHalfTheClocksRangeKeepsItsTimes) {
  // Ticks 1000 s apart cross the 32-bit microsecond clock's wrap (4295 s)
  // and its half range (2147 s) from the first tick more than once.
  ScriptedDevice device;
  DeviceClient client(device);
  std::vector<Message> stream;
  for (uint64_t k = 0; k < 6; ++k) stream.push_back(ticks_at(1000 + k * 1000000000));
  device.replies.push_back(streams(stream));
  Recording r;
  std::string error;
  EXPECT_FALSE(record(client, 0.0, r, error));
  EXPECT_EQ(error, "the device stopped streaming");
  ASSERT_EQ(r.ticks.size(), 6u);
  for (uint64_t k = 0; k < 6; ++k) EXPECT_EQ(r.ticks[k].t_us, 1000 + k * 1000000000) << k;
}

TEST(Ffctl, AReportStampedBeforeTheRecordingsFirstTimeIsAtZero) {
  // The first tick at 100 us; a report stamped 150 us before it (the device's
  // clock read backwards, 2^32 - 50) cannot be 2^64 - 50 us long after it.
  ScriptedDevice device;
  DeviceClient client(device);
  device.replies.push_back(streams({ticks_at(100), reports_at({0xFFFFFFFFu - 49u}), ticks_at(600)}));
  Recording r;
  std::string error;
  record(client, 0.0, r, error);
  ASSERT_EQ(r.samples.size(), 1u);
  EXPECT_EQ(r.samples[0].row.t_us, 0u);
  ASSERT_EQ(r.ticks.size(), 2u);
  EXPECT_EQ(r.ticks[1].t_us, 600u);
}

TEST(Ffctl, AnotherAnswerToTheProfileQueryIsAnError) {
  ScriptedDevice device;
  DeviceClient client(device);
  device.replies.push_back(
      [](const Message& c) { return std::vector<std::vector<uint8_t>>{encoded(ack_for(c.type), c.sequence)}; });
  SensorProfile profile;
  profile.white_noise_px = 2.5f;
  std::string error;
  EXPECT_FALSE(query_sensor_profile(client, profile, error));
  EXPECT_EQ(error, "the device answered QuerySensorProfile with another message");
  EXPECT_EQ(profile.white_noise_px, 2.5f);  // untouched
}

TEST(Ffctl, ReportsThatArrivedBeforeAnUnplugAreMadeDurable) {
  DurableCount sink;
  ScriptedDevice device;
  DeviceClient client(device);
  device.replies.push_back(streams({reports_at({0, 5000, 10000})}));  // then unplugged before their ticks
  device.gone_when_quiet = true;
  std::string error;
  EXPECT_FALSE(record(client, 0.0, sink, error));
  EXPECT_EQ(error, "the device disconnected while recording");
  EXPECT_EQ(sink.samples, 3u);
  EXPECT_EQ(sink.durable, 3u);
}

TEST(Ffctl, ReportsReadAfterTheLastTickAreMadeDurableToo) {
  DurableCount sink;
  ScriptedDevice device;
  DeviceClient client(device);
  // 0.5 ms recorded, then the reports that trail the ticks.
  device.replies.push_back(streams({ticks_at(1000), ticks_at(1500), reports_at({600, 1100})}));
  std::string error;
  EXPECT_TRUE(record(client, 0.0004, sink, error)) << error;
  EXPECT_EQ(sink.ticks, 2u);
  EXPECT_EQ(sink.samples, 2u);
  EXPECT_EQ(sink.durable, 2u);
}

TEST(Ffctl, AFullDiskEndsTheRecordingWithItsReason) {
  DurableCount sink;
  sink.failing_flushes = 1;  // space freed right after: the recording has lost rows all the same
  ScriptedDevice device;
  DeviceClient client(device);
  device.replies.push_back(streams({ticks_at(1000), ticks_at(1500), ticks_at(2000)}));
  std::string error;
  EXPECT_FALSE(record(client, 0.0, sink, error));
  EXPECT_EQ(error, "cannot write run.csv: No space left on device");  // the sink's own words
  EXPECT_EQ(sink.ticks, 1u);  // nothing read after the failed write
}

TEST(Ffctl, TicksMissingFromTheStreamAreCountedAsTheyArrive) {
  // 500 us apart: 1000, 1500 and 2000 are missing before 2500; 3600 is a
  // late tick (within 1.5 periods), not a lost one; 4000 is missing before 4500.
  ScriptedDevice device;
  DeviceClient client(device);
  device.replies.push_back(
      streams({ticks_at(0), ticks_at(500), ticks_at(2500), ticks_at(3000), ticks_at(3600), ticks_at(4500)}));
  Recording r;
  std::string error;
  size_t lost = 0;
  record(client, 0.0, r, error, [&](const RecordProgress& p) { return lost = p.lost_ticks, true; });
  EXPECT_EQ(r.ticks.size(), 6u);
  EXPECT_EQ(lost, 4u);
}

TEST(Ffctl, ErrorRepliesAndOtherVersionsReadPlainly) {
  ScriptedDevice device;
  DeviceClient client(device);
  device.replies.push_back([](const Message& c) {
    Message e;
    e.type = MessageType::Error;
    e.error = {protocol::ErrorCode::UnknownType, static_cast<uint8_t>(c.type)};
    return std::vector<std::vector<uint8_t>>{encoded(e, c.sequence)};
  });
  device.replies.push_back([](const Message& c) {
    std::vector<uint8_t> other = encoded(ack_for(c.type), c.sequence);
    other[2] = static_cast<uint8_t>(protocol::kVersion + 1);  // a newer firmware
    return std::vector<std::vector<uint8_t>>{other};
  });
  Message cmd, reply;
  cmd.type = MessageType::StopStream;
  std::string error;
  EXPECT_FALSE(client.request(cmd, reply, error, 50));
  EXPECT_EQ(error, "the device refused the message: unknown message type");
  EXPECT_FALSE(client.request(cmd, reply, error, 50));
  const std::string expected = "it speaks protocol version " + std::to_string(protocol::kVersion + 1) +
                               ", this ffctl version " + std::to_string(protocol::kVersion);
  EXPECT_NE(error.find(expected), std::string::npos) << error;
  EXPECT_EQ(client.foreign_version(), protocol::kVersion + 1);
}

// A device that keeps sending frames ffctl cannot decode: a firmware of
// another protocol version left streaming. Each receive waits 5 ms; it
// disconnects after `limit` of them, to bound the old code's wait.
class ForeignStream final : public Transport {
 public:
  explicit ForeignStream(int limit) : limit_(limit) {}
  bool send(const uint8_t*, size_t) override { return true; }
  ReceiveResult receive(std::vector<uint8_t>& frame, int) override {
    if (++receives_ > limit_) return ReceiveResult::Disconnected;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    Message m;
    m.type = MessageType::Force;
    frame.resize(protocol::kMaxFrame);
    frame.resize(protocol::encode(m, frame.data(), frame.size()));
    frame[2] = static_cast<uint8_t>(protocol::kVersion + 1);
    return ReceiveResult::Frame;
  }
  int receives() const { return receives_; }

 private:
  int limit_;
  int receives_ = 0;
};

TEST(Ffctl, TheReplyDeadlineHoldsWhileUndecodableFramesKeepComing) {
  // Each foreign frame gave the next receive the whole timeout again: a 2 s
  // request waited as long as the stream lasted (17 s against a streaming
  // protocol-1 device). 100 ms at 5 ms a frame is about 20 receives, not 1000.
  ForeignStream device(1000);
  DeviceClient client(device);
  Message q, reply;
  q.type = MessageType::QueryStatus;
  std::string error;
  EXPECT_FALSE(client.request(q, reply, error, 100));
  EXPECT_LT(device.receives(), 100);
  EXPECT_NE(error.find("no reply from the device within 100 ms: it speaks protocol version"), std::string::npos)
      << error;
  ForeignStream streaming(1000);
  DeviceClient reader(streaming);
  Message m;
  EXPECT_EQ(reader.next(m, 100), ReceiveResult::Timeout);
  EXPECT_LT(streaming.receives(), 100);
}

TEST(Ffctl, ARecordingRunsThroughTheClockWrapAndKeepsTheCondition) {
  ScriptedDevice device;
  DeviceClient client(device);
  device.replies.push_back([](const Message& c) {  // StartStream: ack, then 30 ms of data across a clock wrap
    std::vector<std::vector<uint8_t>> out = {encoded(ack_for(c.type), c.sequence)};
    uint32_t t = 0xFFFFFFFFu - 9999u;  // 10 ms before the wrap
    for (int frame = 0; frame < 2; ++frame) {
      Message s;
      s.type = MessageType::Samples;
      s.samples.count = 1;
      s.samples.samples[0] = {t + 100u, 300.0f, 200.0f, true};
      out.push_back(encoded(s, c.sequence));
      Message k;
      k.type = MessageType::Ticks;
      k.ticks.count = 30;
      for (int i = 0; i < 30; ++i) k.ticks.ticks[i] = {t + 500u * static_cast<uint32_t>(i + 1), 0.5f, 2048, true};
      out.push_back(encoded(k, c.sequence));
      t += 15000u;
    }
    return out;
  });
  device.replies.push_back([](const Message& c) {  // StopStream
    return std::vector<std::vector<uint8_t>>{encoded(ack_for(c.type), c.sequence)};
  });
  Recording r;
  std::string error;
  ASSERT_TRUE(record(client, 0.02, r, error)) << error;
  ASSERT_EQ(device.sent.size(), 2u);
  EXPECT_EQ(device.sent[0].type, MessageType::StartStream);
  EXPECT_EQ(device.sent[0].stream.tick_decimation, 1);  // every tick: verify needs them all
  EXPECT_EQ(device.sent[1].type, MessageType::StopStream);
  ASSERT_EQ(r.ticks.size(), 60u);
  ASSERT_EQ(r.samples.size(), 2u);
  // 64-bit times run on through the wrap.
  const uint64_t t0 = 0xFFFFFFFFull - 9999u;
  EXPECT_EQ(r.ticks[0].t_us, t0 + 500u);
  EXPECT_EQ(r.ticks[59].t_us, t0 + 30000u);
  EXPECT_EQ(r.samples[0].row.t_us, t0 + 100u);
  EXPECT_EQ(r.samples[1].row.t_us, t0 + 15100u);
  for (size_t i = 1; i < r.ticks.size(); ++i) EXPECT_EQ(r.ticks[i].t_us - r.ticks[i - 1].t_us, 500u);

  // What ffctl record writes, read back: the condition set with the scene
  // words, and which tick took each report when the firmware says.
  r.has_condition = true;
  r.condition.kind = protocol::ConditionKind::General;
  r.condition.strength = 0.33f;
  r.condition.scene = scenes::heightmap(Target::Bottom);
  r.condition.scene.evaluation = Evaluation::Table;
  r.samples[1].taken_known = true;
  r.samples[1].taken_us = t0 + 16000u;
  const std::string path = support::scratch_path("ffctl_scripted.csv");
  ASSERT_TRUE(write_recording(path, r, error)) << error;
  Recording back;
  ASSERT_TRUE(read_recording(path, back, error)) << error;
  ASSERT_TRUE(back.has_condition);
  EXPECT_EQ(back.condition.kind, protocol::ConditionKind::General);
  EXPECT_FLOAT_EQ(back.condition.strength, 0.33f);
  EXPECT_EQ(host::format_scene_text(back.condition.scene), host::format_scene_text(r.condition.scene));
  ASSERT_EQ(back.samples.size(), 2u);
  EXPECT_FALSE(back.samples[0].taken_known);
  EXPECT_TRUE(back.samples[1].taken_known);
  EXPECT_EQ(back.samples[1].taken_us, t0 + 16000u);
  EXPECT_EQ(back.ticks[59].t_us, r.ticks[59].t_us);
  std::ifstream trace(path);
  std::string header;
  std::getline(trace, header);
  EXPECT_EQ(header, "t_us,x,y,touch,taken_us");  // docs/spec.md#sensor-trace's columns, then the device's: ff-replay reads it
  std::vector<host::TraceRow> replay_rows;  // what ff-replay's reader makes of it
  host::TraceError trace_error;
  ASSERT_TRUE(host::read_sensor_trace_file(path, replay_rows, trace_error)) << trace_error.to_string(path);
  ASSERT_EQ(replay_rows.size(), 2u);
  EXPECT_EQ(replay_rows[1].t_us, t0 + 15100u);
  EXPECT_FLOAT_EQ(replay_rows[1].x, 300.0f);
  EXPECT_FLOAT_EQ(replay_rows[1].y, 200.0f);
  EXPECT_TRUE(replay_rows[1].touch);
  // The condition file shows the scene in words, a comment per line.
  std::stringstream condition_text;
  condition_text << std::ifstream(condition_path_for(path)).rdbuf();
  std::istringstream scene_lines(host::format_scene_text(r.condition.scene));
  for (std::string line; std::getline(scene_lines, line);) {
    EXPECT_NE(condition_text.str().find("#   " + line + "\n"), std::string::npos) << line;
  }
  EXPECT_EQ(condition_text.str().back(), '\n');  // a text file: its frame line ends too
  // Without a condition, a stale NAME.condition goes.
  r.has_condition = false;
  ASSERT_TRUE(write_recording(path, r, error)) << error;
  EXPECT_FALSE(std::ifstream(condition_path_for(path)).good());
  // A folder where the condition file would go is named, not written around.
  r.has_condition = true;
  const std::string blocked = support::scratch_path("ffctl_condition_blocked.csv");
  std::filesystem::remove_all(condition_path_for(blocked));
  std::filesystem::create_directory(condition_path_for(blocked));
  EXPECT_FALSE(write_recording(blocked, r, error));
  EXPECT_EQ(error, "cannot write " + condition_path_for(blocked) + ": Is a directory");
  std::filesystem::remove_all(condition_path_for(blocked));
  // The condition file is written whole through NAME.condition.partial: where that cannot be
  // made (a folder in its way), the file already there is left as it was.
  std::ofstream(condition_path_for(blocked)) << "kept\n";
  std::filesystem::create_directory(condition_path_for(blocked) + ".partial");
  EXPECT_FALSE(write_recording(blocked, r, error));
  EXPECT_EQ(error, "cannot write " + condition_path_for(blocked) + ": Is a directory");  // its .partial is
  std::stringstream kept;
  kept << std::ifstream(condition_path_for(blocked)).rdbuf();
  EXPECT_EQ(kept.str(), "kept\n");
  std::filesystem::remove_all(condition_path_for(blocked) + ".partial");
  std::filesystem::remove(condition_path_for(blocked));
}

TEST(Ffctl, ARecordingWithBrokenTicksIsRefusedWithItsLine) {
  const std::string path = support::scratch_path("ffctl_broken.csv");
  std::ofstream(path) << "t_us,x,y,touch\n1000,10,10,1\n";
  std::ofstream(ticks_path_for(path)) << "t_us,amplitude,dac,present\n500,0.5,2048,1\n1000,0.5,5000,1\n";
  Recording r;
  std::string error;
  EXPECT_FALSE(read_recording(path, r, error));
  EXPECT_NE(error.find("ffctl_broken.ticks.csv:3:"), std::string::npos) << error;
  std::ofstream(ticks_path_for(path)) << "t_us,amplitude,dac,present\n500,0.5,2048,1\n500,0.5,2048,1\n";
  Recording again;
  EXPECT_FALSE(read_recording(path, again, error));
  EXPECT_NE(error.find("must increase"), std::string::npos) << error;
  std::ofstream(ticks_path_for(path)) << "t_us,amplitude,dac,present\n500,nan,2048,1\n";
  Recording nan;
  EXPECT_FALSE(read_recording(path, nan, error));
  std::ofstream(ticks_path_for(path)) << "t_us,amplitude,dac,present\n500,0.5,2048,1\n";
  Recording plain;  // a trace without the device column: fine, by timestamps
  ASSERT_TRUE(read_recording(path, plain, error)) << error;
  EXPECT_FALSE(plain.samples[0].taken_known);
  EXPECT_FALSE(plain.has_condition);
}

TEST(Ffctl, ARecordingsTakenTimesStayWithTheirRowsWhateverLinesAreBetween) {
  // Edited by hand: a note and a blank line between the rows, Windows line ends.
  const std::string path = support::scratch_path("ffctl_annotated.csv");
  std::ofstream(path) << "# ffctl record\r\nt_us,x,y,touch,taken_us\r\n1000,10,10,1,1500\r\n"
                         "# the finger slipped here\r\n   \r\n2000,20,10,1,-1\r\n3000,30,10,1,3000\r\n";
  std::ofstream(ticks_path_for(path)) << "t_us,amplitude,dac,present\n500,0.5,2048,1\n";
  Recording r;
  std::string error;
  ASSERT_TRUE(read_recording(path, r, error)) << error;
  ASSERT_EQ(r.samples.size(), 3u);
  EXPECT_TRUE(r.samples[0].taken_known);
  EXPECT_EQ(r.samples[0].taken_us, 1500u);
  EXPECT_FALSE(r.samples[1].taken_known);
  EXPECT_EQ(r.samples[1].row.x, 20.0f);
  EXPECT_TRUE(r.samples[2].taken_known);
  EXPECT_EQ(r.samples[2].taken_us, 3000u);
  // Errors name the file's own line, metadata counted.
  std::ofstream(path) << "# ffctl record\nt_us,x,y,touch,taken_us\n1000,10,10,1,1500\n\n2000,20,10,1,soon\n";
  Recording bad_taken;
  EXPECT_FALSE(read_recording(path, bad_taken, error));
  EXPECT_EQ(error, path + ":5:5: taken_us must be a time in us or -1 (got 'soon')");
  std::ofstream(path) << "# ffctl record\nt_us,x,y,touch,taken_us\n1000,10,10,1\n";
  Recording short_row;
  EXPECT_FALSE(read_recording(path, short_row, error));
  EXPECT_EQ(error, path + ":3:5: taken_us must be a time in us or -1 (got '')");
  std::ofstream(path) << "# ffctl record\n# 200 Hz\nt_us,x,y,touch,taken_us\n1000,ten,10,1,1500\n";
  Recording bad_x;
  EXPECT_FALSE(read_recording(path, bad_x, error));
  EXPECT_EQ(error.rfind(path + ":4:2: x is not a number", 0), 0u) << error;
}

// A ticks file without its header would lose its first tick as the header;
// a time written with a sign would wrap to a huge one (%llu takes "-5").
TEST(Ffctl, ATicksFileWithoutItsHeaderOrWithASignedTimeIsRefused) {
  const std::string path = support::scratch_path("ffctl_ticks_header.csv");
  std::ofstream(path) << "t_us,x,y,touch\n1000,10,10,1\n";
  std::ofstream(ticks_path_for(path)) << "# ffctl record\n500,0.5,2048,1\n1000,0.5,2048,1\n";
  Recording headless;
  std::string error;
  EXPECT_FALSE(read_recording(path, headless, error));
  EXPECT_EQ(error, ticks_path_for(path) + ":2: expected the header t_us,amplitude,dac,present");
  for (const char* time : {"-5", "+5", " -5"}) {
    std::ofstream(ticks_path_for(path)) << "t_us,amplitude,dac,present\n" << time << ",0.5,2048,1\n";
    Recording signed_time;
    EXPECT_FALSE(read_recording(path, signed_time, error)) << time;
    EXPECT_EQ(error, ticks_path_for(path) + ":2: expected t_us,amplitude,dac,present") << time;
  }
  std::ofstream(ticks_path_for(path)) << "  t_us,amplitude,dac,present \r\n 500,0.5,2048,1\n";
  Recording padded;
  EXPECT_TRUE(read_recording(path, padded, error)) << error;
  EXPECT_EQ(padded.ticks.size(), 1u);
  std::filesystem::remove(ticks_path_for(path));
  std::filesystem::remove(path);
}

TEST(Ffctl, ATicksFileReadsLikeEveryTraceFile) {
  const std::string path = support::scratch_path("ffctl_ticks_shape.csv");
  std::ofstream(path) << "t_us,x,y,touch\n1000,10,10,1\n";
  std::ofstream(ticks_path_for(path)) << "# ffctl record\r\nt_us,amplitude,dac,present\r\n500,0.5,2048,1\r\n"
                                         "# the plate was touched here\r\n\r\n   \r\n1000,0.25,1024,0\r\n";
  Recording r;
  std::string error;
  ASSERT_TRUE(read_recording(path, r, error)) << error;
  ASSERT_EQ(r.ticks.size(), 2u);
  EXPECT_EQ(r.ticks[1].t_us, 1000u);
  EXPECT_EQ(r.ticks[1].amplitude, 0.25f);
  EXPECT_EQ(r.ticks[1].dac, 1024u);
  EXPECT_FALSE(r.ticks[1].present);
  // Errors name the file's own line, metadata counted.
  std::ofstream(ticks_path_for(path)) << "# a\n# b\nt_us,amplitude,dac,present\n500,0.5,2048,1\n# c\n1000,0.5,5000,1\n";
  Recording broken;
  EXPECT_FALSE(read_recording(path, broken, error));
  EXPECT_EQ(error, ticks_path_for(path) + ":6: expected t_us,amplitude,dac,present");
  std::filesystem::remove(ticks_path_for(path));
  Recording no_ticks;
  EXPECT_FALSE(read_recording(path, no_ticks, error));
  EXPECT_EQ(error, ticks_path_for(path) +
                       ": cannot open: No such file or directory (ffctl record writes it next to the trace)");
  std::filesystem::remove(path);
  Recording nothing;
  EXPECT_FALSE(read_recording(path, nothing, error));
  EXPECT_EQ(error, path + ": cannot open: No such file or directory");
}

TEST(Ffctl, ARecordingsForcesAreWrittenBesideIt) {
  Recording r;
  r.forces = {{1000, 250.5f, false}, {3000, 4100.0f, true}};
  const std::string path = support::scratch_path("ffctl_forces.csv");
  std::string error;
  ASSERT_TRUE(write_recording(path, r, error, {"ffctl record"})) << error;
  EXPECT_EQ(support::file_contents(force_path_for(path)), "# ffctl record\nt_us,force_mN,over_force\n1000,250.5,0\n3000,4100,1\n");
}

TEST(Ffctl, AnOutputPathIsCheckedBeforeTheDeviceIsTouched) {
  std::string error;
  EXPECT_FALSE(check_output_path("", error));
  EXPECT_EQ(error, "-o: no file name");
  const std::string folder = support::scratch_path("ffctl_out_folder");
  std::filesystem::create_directories(folder);
  EXPECT_FALSE(check_output_path(folder, error));
  EXPECT_EQ(error, "-o " + folder + ": is a folder; give a file name such as " + folder + "/run1.csv");
  EXPECT_FALSE(check_output_path(folder + "/missing/run1.csv", error));
  EXPECT_EQ(error, "-o " + folder + "/missing/run1.csv: the folder " + folder + "/missing does not exist");
  EXPECT_TRUE(check_output_path(folder + "/run1.csv", error)) << error;
  // A recording is several files named after -o: not standard output, not a device (as root, /dev/null.ticks.csv
  // would be made in /dev).
  const std::string several = "a recording is several files named after it (NAME.csv, NAME.ticks.csv, "
                              "NAME.force.csv); give a file name such as run1.csv";
  EXPECT_FALSE(check_output_path("-", error));
  EXPECT_EQ(error, "-o -: " + several);
  EXPECT_FALSE(check_output_path("/dev/null", error));
  EXPECT_EQ(error, "-o /dev/null: not a regular file: " + several);
  std::ofstream(folder + "/old.csv") << "t_us,x,y,touch\n";
  EXPECT_TRUE(check_output_path(folder + "/old.csv", error)) << error;  // a file there is replaced, as asked
}

TEST(Ffctl, TheSideFilesOfARecordingAreNamedAfterItsSuffixOnly) {
  EXPECT_EQ(ticks_path_for("runs/p01.csv"), "runs/p01.ticks.csv");
  EXPECT_EQ(force_path_for("runs/p01.csv"), "runs/p01.force.csv");
  EXPECT_EQ(condition_path_for("runs/p01.csv"), "runs/p01.condition");
  EXPECT_EQ(sensor_profile_path_for("runs/p01.csv"), "runs/p01.sensor-profile");
  // A ".csv" elsewhere in the name is not the suffix: the side files stay beside the trace.
  EXPECT_EQ(ticks_path_for("runs.csv.d/p01"), "runs.csv.d/p01.ticks.csv");
  EXPECT_EQ(ticks_path_for("p01.csv.bak"), "p01.csv.bak.ticks.csv");
}

DeviceSample sample_at(uint64_t i) {
  return {{1000000 + 5000 * i, 100.0f + 0.25f * static_cast<float>(i % 7), 240.5f, true}, false, 0};
}

TEST(Ffctl, ARecordingReachesTheDiskInWholeRowsWhenFlushed) {
  // A killed recorder leaves what the last flush wrote: rows kept back until
  // then may be lost, but never half a row.
  const std::string path = support::scratch_path("ffctl_whole_rows.csv");
  RecordingWriter w;
  std::string error;
  ASSERT_TRUE(w.open(path, {"ffctl record"}, Recording{}, error)) << error;
  const std::string header = "# ffctl record\nt_us,x,y,touch,taken_us\n";
  EXPECT_EQ(support::file_contents(path), header);
  for (uint64_t i = 0; i < 3000; ++i) w.sample(sample_at(i));  // ~80 kB, several stdio buffers' worth
  EXPECT_EQ(support::file_contents(path), header);
  ASSERT_TRUE(w.flush(error)) << error;
  const std::string flushed = support::file_contents(path);
  EXPECT_EQ(std::count(flushed.begin(), flushed.end(), '\n'), 3002);
  EXPECT_EQ(flushed.back(), '\n');
  EXPECT_TRUE(w.close(error)) << error;
}

TEST(Ffctl, AWriteThatFailsIsReportedWithTheFilesName) {
  const std::string path = support::scratch_path("ffctl_disk_full.csv");
  std::string error;
  {
    support::FileSizeLimit full(8);  // not even the header fits
    RecordingWriter w;
    EXPECT_FALSE(w.open(path, {"ffctl record"}, Recording{}, error));
  }
  EXPECT_EQ(error, "cannot write " + path + ": File too large");  // EFBIG: the limit stands in for a full disk
  {
    support::FileSizeLimit full(16384);  // the header fits, the rows do not
    RecordingWriter w;
    ASSERT_TRUE(w.open(path, {"ffctl record"}, Recording{}, error)) << error;
    for (uint64_t i = 0; i < 3000; ++i) w.sample(sample_at(i));
    EXPECT_FALSE(w.close(error));
  }
  EXPECT_EQ(error, "cannot write " + path + ": File too large");
  {
    RecordingWriter w;  // rows past the 1 MiB buffer without a flush (write_recording): a write fails mid-way
    ASSERT_TRUE(w.open(path, {"ffctl record"}, Recording{}, error)) << error;
    {
      support::FileSizeLimit full(16384);
      for (uint64_t i = 0; i < 60000; ++i) w.sample(sample_at(i));  // ~1.6 MB
    }
    EXPECT_FALSE(w.close(error));  // space freed before the close: the rows lost are still said
  }
  EXPECT_EQ(error, "cannot write " + path + ": File too large");
  {
    RecordingWriter w;  // close(2) itself fails (as on a full NFS server): the ticks file's descriptor is pulled
    ASSERT_TRUE(w.open(path, {"ffctl record"}, Recording{}, error)) << error;
    for (const auto& fd : std::filesystem::directory_iterator("/proc/self/fd")) {
      std::error_code ec;
      if (std::filesystem::read_symlink(fd.path(), ec) == std::filesystem::absolute(ticks_path_for(path))) {
        ::close(std::stoi(fd.path().filename().string()));
      }
    }
    EXPECT_FALSE(w.close(error));
  }
  EXPECT_EQ(error, "cannot write " + ticks_path_for(path) + ": Bad file descriptor");
  std::filesystem::remove(ticks_path_for(path));
  std::filesystem::create_directory(ticks_path_for(path));  // a side file that cannot be made is the one named
  {
    RecordingWriter w;
    EXPECT_FALSE(w.open(path, {"ffctl record"}, Recording{}, error));
  }
  EXPECT_EQ(error, "cannot write " + ticks_path_for(path) + ": Is a directory");
  std::filesystem::remove(ticks_path_for(path));
}

}  // namespace
}  // namespace ff::ffctl
