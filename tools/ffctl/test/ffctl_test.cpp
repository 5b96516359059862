// ffctl without hardware: the fake device is the firmware itself (firmware/app)
// running on emulated peripherals, reached through a transport that moves
// HID reports and advances simulated time while ffctl waits.
#include <gtest/gtest.h>

#include <algorithm>
#include <deque>
#include <fstream>
#include <memory>
#include <sstream>

#include "device_client.hpp"
#include "firmware/app/firmware_app.hpp"
#include "frictionfield/core/scenes.hpp"
#include "frictionfield/emulated/ad9834_model.hpp"
#include "frictionfield/emulated/i2c_bus.hpp"
#include "frictionfield/emulated/recording_dac.hpp"
#include "frictionfield/emulated/scripted_adc.hpp"
#include "frictionfield/emulated/zforce_model.hpp"
#include "frictionfield/protocol/hid_channel.hpp"
#include "halfkay.hpp"
#include "intel_hex.hpp"

namespace ff::ffctl {
namespace {

using protocol::Message;
using protocol::MessageType;

class SimulatedDevice final : public Transport, public firmware::Board {
 public:
  SimulatedDevice() {
    const ZforceConfig config;
    i2c_.attach(config.address, zforce_);
    zforce_.set_calibration(config.calibration);
    for (uint8_t ch = 0; ch < 4; ++ch) adc_.set(ch, 100);
    app_ = std::make_unique<firmware::FirmwareApp>(firmware::Peripherals{dds_, 0, i2c_, zforce_, dac_, adc_}, *this,
                                                   *pipeline_);
    app_->begin(now_);
    while (app_->sensor().state() != ZforceState::Running && now_ < 1000000) step();
    // A finger along the middle path at 300 px/s for 3 s.
    std::vector<SensorSample> trace;
    for (uint32_t t = 1000000; t <= 4000000; t += 5000) {
      trace.push_back({t, 100.0f + 200.0f * static_cast<float>(t - 1000000) * 1e-6f, 240.0f, true});
    }
    zforce_.load_trace(trace);
  }

  // Transport.
  bool send(const uint8_t* frame, size_t size) override {
    if (disconnected) return false;
    uint8_t reports[protocol::kMaxHidReports][protocol::kHidReportBytes];
    const size_t n = protocol::split_into_reports(frame, size, reports, protocol::kMaxHidReports);
    for (size_t i = 0; i < n; ++i) to_device_.emplace_back(reports[i], reports[i] + protocol::kHidReportBytes);
    return true;
  }
  ReceiveResult receive(std::vector<uint8_t>& frame, int timeout_ms) override {
    const uint32_t until = now_ + static_cast<uint32_t>(timeout_ms) * 1000u;
    while (from_device_.empty() && static_cast<int32_t>(until - now_) > 0) step();
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
  void mouse_move_to(int, int) override {}
  bool udp_receive(uint8_t*, size_t, size_t&) override { return false; }
  void udp_send(const uint8_t*, size_t) override {}
  bool hid_receive(uint8_t* report) override {
    if (to_device_.empty()) return false;
    std::copy(to_device_.front().begin(), to_device_.front().end(), report);
    to_device_.pop_front();
    return true;
  }
  void hid_send(const uint8_t* report) override {
    if (reassembler_.push(report)) from_device_.emplace_back(reassembler_.frame(), reassembler_.frame() + reassembler_.size());
  }
  uint32_t cycles() override { return cycles_ += 700; }
  void reboot_to_bootloader() override { ++reboots; }

  int disconnect_after_frames = -1;
  bool corrupt_next_reply = false;
  bool disconnected = false;
  int reboots = 0;

 private:
  void step() {  // 100 us of device time: loop every step, tick every 5th
    now_ += 100;
    zforce_.advance_to(now_);
    app_->loop(now_);
    if (now_ % 500 == 0) app_->tick(now_);
  }

  emulated::Ad9834Model dds_;
  emulated::ZforceModel zforce_;
  emulated::EmulatedI2cBus i2c_;
  emulated::RecordingDac dac_;
  emulated::ScriptedAdc adc_;
  std::unique_ptr<HapticPipeline> pipeline_ = std::make_unique<HapticPipeline>();
  std::unique_ptr<firmware::FirmwareApp> app_;
  protocol::HidReassembler reassembler_;
  std::deque<std::vector<uint8_t>> to_device_, from_device_;
  uint32_t now_ = 0;
  uint32_t cycles_ = 0;
  int frames_delivered_ = 0;
};

Message heightmap_top() {
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
  ASSERT_TRUE(client.request(heightmap_top(), reply, error)) << error;
  EXPECT_EQ(reply.type, MessageType::Ack);
  EXPECT_EQ(reply.ack.status, protocol::AckStatus::Ok);
  Message q;
  q.type = MessageType::QueryStatus;
  ASSERT_TRUE(client.request(q, reply, error)) << error;
  EXPECT_EQ(reply.status.kind, protocol::ConditionKind::Heightmap);
  EXPECT_FLOAT_EQ(reply.status.strength, 0.66f);
  EXPECT_EQ(reply.status.tick_cycles_mean, 700u);
}

TEST(Ffctl, RecordThenVerifyAgreesTickForTickAndCatchesTampering) {
  SimulatedDevice device;
  DeviceClient client(device);
  Message reply;
  std::string error;
  ASSERT_TRUE(client.request(heightmap_top(), reply, error)) << error;
  Recording r;
  int progress_calls = 0;
  ASSERT_TRUE(record(client, 2.5, r, error, [&](double, size_t, size_t) { ++progress_calls; })) << error;
  EXPECT_GT(progress_calls, 10);
  EXPECT_NEAR(static_cast<double>(r.ticks.size()), 5000.0, 120.0);  // 2.5 s of 2 kHz
  // The finger arrives 1 s after the stream starts: ~1.5 s of 200 Hz reports.
  EXPECT_GT(r.samples.size(), 280u);

  const std::string path = ::testing::TempDir() + "ffctl_rec.csv";
  ASSERT_TRUE(write_recording(path, r, error)) << error;
  Recording back;
  ASSERT_TRUE(read_recording(path, back, error)) << error;
  Condition c;
  c.scene = scenes::heightmap(Target::Top);
  c.amplitude.strength = 0.66f;
  const VerifyResult v = verify(back, c);
  EXPECT_EQ(v.compared, r.ticks.size());
  EXPECT_EQ(v.beyond_one_code, 0u);
  EXPECT_LE(v.max_dac_difference, 1);

  back.ticks[1000].dac = static_cast<uint16_t>(back.ticks[1000].dac ^ 0x400);
  const VerifyResult tampered = verify(back, c);
  ASSERT_EQ(tampered.beyond_one_code, 1u);
  EXPECT_EQ(tampered.first[0].t_us, back.ticks[1000].t_us);
}

TEST(Ffctl, MalformedRepliesAreCountedAndDisconnectIsReported) {
  SimulatedDevice device;
  DeviceClient client(device);
  Message reply;
  std::string error;
  device.corrupt_next_reply = true;
  EXPECT_FALSE(client.request(heightmap_top(), reply, error));  // its only reply was corrupt: no answer
  EXPECT_EQ(client.malformed_replies(), 1u);
  EXPECT_NE(error.find("no reply"), std::string::npos) << error;
  device.disconnect_after_frames = 20;
  Recording r;
  EXPECT_FALSE(record(client, 5.0, r, error));
  EXPECT_NE(error.find("disconnected"), std::string::npos) << error;
  EXPECT_GT(r.ticks.size(), 0u);  // what arrived is kept
}

TEST(IntelHex, ParsesWithExtendedAddressesAndRejectsBadRecords) {
  FlashImage image;
  std::string error;
  // Two bytes at 0x0000, one at 0x10000 (extended linear address 0x0001), end.
  ASSERT_TRUE(parse_intel_hex(":020000000102FB\n:020000040001F9\n:0100000055AA\n:00000001FF\n", image, error)) << error;
  EXPECT_EQ(image.bytes[0], 0x01);
  EXPECT_EQ(image.bytes[1], 0x02);
  EXPECT_EQ(image.bytes[0x10000], 0x55);
  EXPECT_EQ(image.highest, 0x10001u);
  FlashImage bad;
  EXPECT_FALSE(parse_intel_hex(":020000000102FC\n:00000001FF\n", bad, error));
  EXPECT_NE(error.find("line 1: checksum"), std::string::npos) << error;
  EXPECT_FALSE(parse_intel_hex(":00000007F9\n", bad, error));
  EXPECT_NE(error.find("unknown record type 7"), std::string::npos) << error;
  EXPECT_FALSE(parse_intel_hex(":020000000102FB\n", bad, error));
  EXPECT_NE(error.find("no end-of-file"), std::string::npos) << error;
}

TEST(HalfKay, BlocksHaveTheMk66LayoutSkipBlanksButTheFirstAndEndWithBoot) {
  FlashImage image;
  image.bytes[5] = 0xAB;         // block 0
  image.bytes[3 * 1024 + 7] = 1;  // block 3; blocks 1 and 2 stay blank
  image.highest = 3 * 1024 + 8;
  const auto writes = halfkay_writes(image);
  ASSERT_EQ(writes.size(), 3u);  // block 0, block 3, boot
  EXPECT_EQ(writes[0].report.size(), 64u + 1024u);
  EXPECT_EQ(writes[0].report[0], 0);
  EXPECT_EQ(writes[0].report[64 + 5], 0xAB);
  EXPECT_EQ(writes[1].address, 3u * 1024u);
  EXPECT_EQ(writes[1].report[0], 0x00);
  EXPECT_EQ(writes[1].report[1], 0x0C);  // 3072 = 0x000C00, little-endian
  EXPECT_EQ(writes[1].report[2], 0x00);
  EXPECT_EQ(writes[1].report[64 + 7], 1);
  EXPECT_EQ(writes[2].report[0], 0xFF);
  EXPECT_EQ(writes[2].report[1], 0xFF);
  EXPECT_EQ(writes[2].report[2], 0xFF);
  FlashImage blank;
  blank.highest = 2048;
  EXPECT_EQ(halfkay_writes(blank).size(), 2u);  // the first block is always written: it erases the chip
}

#ifdef FF_TOOLCHAIN_HEX
std::string slurp(const char* path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(HalfKay, ImageFromTheCrossToolchainsObjcopy) {
  // objcopy put intel_hex.cpp's bytes at 0x10000 (extended linear address records).
  const std::string data = slurp(FF_TOOLCHAIN_HEX_SOURCE);
  FlashImage image;
  std::string error;
  ASSERT_TRUE(parse_intel_hex(slurp(FF_TOOLCHAIN_HEX), image, error)) << error;
  ASSERT_EQ(image.highest, 0x10000u + data.size());
  EXPECT_TRUE(std::equal(data.begin(), data.end(), image.bytes.begin() + 0x10000));
  const auto writes = halfkay_writes(image);
  // Block 0 (blank, but written: it erases), every block under the data, the boot command.
  const size_t data_blocks = (data.size() + kHalfKayBlock - 1) / kHalfKayBlock;
  ASSERT_EQ(writes.size(), 1 + data_blocks + 1);
  EXPECT_EQ(writes[0].address, 0u);
  EXPECT_EQ(writes[1].address, 0x10000u);
  EXPECT_EQ(writes[1].report[2], 0x01);  // 0x010000 little-endian: byte 2
  EXPECT_EQ(writes[1].report[kHalfKayHeader], static_cast<uint8_t>(data[0]));
}
#endif

}  // namespace
}  // namespace ff::ffctl
