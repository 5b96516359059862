#include "frictionfield/protocol/codec.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "frictionfield/core/scenes.hpp"
#include "frictionfield/host/scene_file.hpp"

namespace ff::protocol {
namespace {

std::vector<uint8_t> frame_of(const Message& m) {
  std::vector<uint8_t> buf(kMaxFrame);
  const size_t n = encode(m, buf.data(), buf.size());
  EXPECT_GT(n, 0u);
  buf.resize(n);
  return buf;
}

Message round_trip(const Message& m) {
  const std::vector<uint8_t> f = frame_of(m);
  Message out;
  EXPECT_EQ(decode(f.data(), f.size(), out), DecodeStatus::Ok);
  EXPECT_EQ(out.type, m.type);
  EXPECT_EQ(out.sequence, m.sequence);
  return out;
}

// A valid CRC around whatever the bytes now say.
std::vector<uint8_t> reseal(std::vector<uint8_t> f) {
  const uint16_t crc = crc16_ccitt(f.data() + 2, f.size() - 4);
  f[f.size() - 2] = uint8_t(crc);
  f[f.size() - 1] = uint8_t(crc >> 8);
  return f;
}

// Header, payload and CRC for hand-made payloads.
std::vector<uint8_t> frame_with_payload(MessageType type, const std::vector<uint8_t>& payload) {
  std::vector<uint8_t> f = {'F', 'F', kVersion, static_cast<uint8_t>(type), 0,
                            uint8_t(payload.size()), uint8_t(payload.size() >> 8)};
  f.insert(f.end(), payload.begin(), payload.end());
  f.push_back(0);
  f.push_back(0);
  return reseal(f);
}

// The frame with `count` bytes at `at` replaced by `with`, its length and CRC mended.
std::vector<uint8_t> spliced(std::vector<uint8_t> f, size_t at, size_t count, const std::vector<uint8_t>& with) {
  f.erase(f.begin() + static_cast<std::ptrdiff_t>(at), f.begin() + static_cast<std::ptrdiff_t>(at + count));
  f.insert(f.begin() + static_cast<std::ptrdiff_t>(at), with.begin(), with.end());
  const size_t payload = f.size() - 7 - 2;  // less header and CRC
  f[5] = uint8_t(payload);
  f[6] = uint8_t(payload >> 8);
  return reseal(f);
}

DecodeStatus status_of(const std::vector<uint8_t>& f) {
  Message out;
  return decode(f.data(), f.size(), out);
}

Message condition(ConditionKind kind) {
  Message m;
  m.type = MessageType::SetCondition;
  m.condition.kind = kind;
  return m;
}

TEST(Codec, CrcIsCcittFalse) {
  EXPECT_EQ(crc16_ccitt(reinterpret_cast<const uint8_t*>("123456789"), 9), 0x29B1);  // the standard check value
}

TEST(Codec, QueryStatusIsTheHandDerivedFrame) {
  Message m;
  m.type = MessageType::QueryStatus;
  m.sequence = 7;
  // 'F' 'F', version 2, type 0x02, sequence 7, length 0, then CRC-16/CCITT-FALSE of
  // 02 02 07 00 00 = 0x3D77, low byte first. Computed outside the project, by Python's
  // binascii.crc_hqx(bytes([2, 2, 7, 0, 0]), 0xFFFF) (poly 0x1021, init 0xFFFF, no reflection, no final xor).
  const std::vector<uint8_t> expected = {'F', 'F', 2, 0x02, 7, 0, 0, 0x77, 0x3D};
  EXPECT_EQ(frame_of(m), expected);
}

TEST(Codec, ForceIsExplicitLittleEndian) {
  Message m;
  m.type = MessageType::Force;
  m.sequence = 9;
  m.force = {0x01020304u, 1.0f, true};
  // t_us 04 03 02 01, 1.0f = 0x3F800000 -> 00 00 80 3F, over-force 01; CRC 0x08BE (binascii.crc_hqx as above).
  const std::vector<uint8_t> expected = {'F', 'F', 2, 0x83, 9, 9, 0, 0x04, 0x03, 0x02, 0x01,
                                         0x00, 0x00, 0x80, 0x3F, 0x01, 0xBE, 0x08};
  EXPECT_EQ(frame_of(m), expected);
}

TEST(Codec, ThesisConditionRoundTripsAndBecomesTheBuiltInScene) {
  Message m = condition(ConditionKind::Heightmap);
  m.condition.target = Target::Top;
  m.condition.strength = 0.66f;
  m.condition.idle_amplitude = 0.125f;
  m.condition.s_curve = 0.25f;
  const Message out = round_trip(m);
  EXPECT_EQ(out.condition.kind, ConditionKind::Heightmap);
  EXPECT_EQ(out.condition.target, Target::Top);
  EXPECT_FLOAT_EQ(out.condition.strength, 0.66f);
  const Condition c = out.condition.to_condition();
  EXPECT_EQ(host::format_scene_text(c.scene), host::format_scene_text(scenes::heightmap(Target::Top)));
  EXPECT_FLOAT_EQ(c.amplitude.strength, 0.66f);
  EXPECT_FLOAT_EQ(c.amplitude.idle_amplitude, 0.125f);
  EXPECT_FLOAT_EQ(c.amplitude.s_curve, 0.25f);
  // A thesis condition is short: 7 header + 15 condition + 2 x 8 calibration + 2 CRC.
  EXPECT_EQ(frame_of(m).size(), 7u + 15u + 16u + 2u);
}

TEST(Codec, GeneralSceneRoundTripsEveryField) {
  SceneDefinition s;
  std::string err;
  ASSERT_TRUE(host::parse_scene_text(
      "rendering directional\n"
      "evaluation table 8 float height\n"
      "element point_sink weight -0.5 centre 600 400 radius 12 feather 15\n"
      "element path_sink weight 0.7 a 0.5 band 10 20 curve polyline 0,300 300,200 799,250\n"
      "element path_sink weight 0.2 curve sine 240 120 400 10\n"
      "element tunnel weight 1 x_start 100 length 400 width 60 20 scale 10 y_centre 240\n"
      "element saddle weight 0.001 centre 400 240\n"
      "element vortex weight 0.002 centre 400 240\n"
      "element texture weight 0.3 wavelength 100 80 height 5\n",
      s, err)) << err;
  Message m = condition(ConditionKind::General);
  m.condition.scene = s;
  m.condition.s_curve = 0.5f;
  m.condition.idle_amplitude = 0.25f;
  const Message out = round_trip(m);
  EXPECT_EQ(host::format_scene_text(out.condition.scene), host::format_scene_text(s));
  EXPECT_FLOAT_EQ(out.condition.s_curve, 0.5f);
  EXPECT_FLOAT_EQ(out.condition.idle_amplitude, 0.25f);
  // Constant and position-only scenes carry their constant and bias.
  Message k = condition(ConditionKind::General);
  k.condition.scene.rendering = Rendering::PositionOnly;
  k.condition.scene.bias = 0.125f;
  k.condition.scene.constant = 0.75f;
  const Message ko = round_trip(k);
  EXPECT_EQ(ko.condition.scene.rendering, Rendering::PositionOnly);
  EXPECT_FLOAT_EQ(ko.condition.scene.bias, 0.125f);
  EXPECT_FLOAT_EQ(ko.condition.scene.constant, 0.75f);
}

TEST(Codec, TheLargestSceneFitsOneFrame) {
  Message m = condition(ConditionKind::General);
  Vec2 points[kMaxPolylinePoints];
  for (int i = 0; i < kMaxPolylinePoints; ++i) points[i] = {10.0f + 50.0f * static_cast<float>(i), 240.0f};
  for (int i = 0; i < kMaxSceneElements; ++i) {
    ASSERT_TRUE(m.condition.scene.add(FieldElement::path_sink(PathCurve::polyline(points, kMaxPolylinePoints), 0.2f)));
  }
  for (int i = 0; i < kMaxCalibrationPoints; ++i) {
    m.condition.calibration.amplitude[i] = static_cast<float>(i) / (kMaxCalibrationPoints - 1);
    m.condition.calibration.code[i] = 4095.0f * static_cast<float>(i) / (kMaxCalibrationPoints - 1);
  }
  m.condition.calibration.count = kMaxCalibrationPoints;
  const std::vector<uint8_t> f = frame_of(m);
  // 7 header + 143 condition + 17 scene header + 8 x 147 elements + 2 CRC.
  EXPECT_EQ(f.size(), 1345u);
  EXPECT_LE(f.size(), kMaxFrame);
  EXPECT_EQ(round_trip(m).condition.scene.elements[7].valley.curve.points[15].x, 760.0f);
}

TEST(Codec, DacCalibrationTravelsWhole) {
  Message m = condition(ConditionKind::Neutral);
  m.condition.calibration = DacCalibration::inverted();
  const Message inv = round_trip(m);
  EXPECT_EQ(inv.condition.to_condition().amplitude.calibration.code_for(0.0f), DacCalibration::inverted().code_for(0.0f));
  const float amps[4] = {0.0f, 0.2f, 0.7f, 1.0f};
  const float codes[4] = {100.0f, 900.0f, 3000.0f, 4000.0f};
  ASSERT_TRUE(DacCalibration::from_points(amps, codes, 4, m.condition.calibration));
  const Message out = round_trip(m);
  ASSERT_EQ(out.condition.calibration.count, 4);
  EXPECT_FLOAT_EQ(out.condition.calibration.amplitude[2], 0.7f);
  EXPECT_FLOAT_EQ(out.condition.calibration.code[3], 4000.0f);
  EXPECT_EQ(out.condition.to_condition().amplitude.calibration.code_for(0.2f), 900);
}

TEST(Codec, DeviceMessagesRoundTrip) {
  Message st;
  st.type = MessageType::Status;
  st.status.firmware_version = 0x0102;
  st.status.tick_cycles_mean = 1234;
  st.status.tick_cycles_max = 5678;
  st.status.watchdog_trips = 2;
  st.status.stream_overruns = 17;
  st.status.force_mN = 412.5f;
  st.status.finger_present = true;
  st.status.carrier_hz = 34900.0f;
  st.status.faults.count[static_cast<int>(Fault::JumpRejected)] = 3;
  st.status.isr_cycles_mean = 2100;
  st.status.isr_cycles_max = 7000;
  st.status.isr_cycles_p99 = 4096;
  st.status.prepare_us_last = 1800;
  st.status.loop_pass_max_us = 950;
  st.status.zforce_layout_beside = 11;
  st.status.zforce_layout_inside = 12;
  const Message s = round_trip(st);
  EXPECT_EQ(s.status.isr_cycles_mean, 2100u);
  EXPECT_EQ(s.status.isr_cycles_max, 7000u);
  EXPECT_EQ(s.status.isr_cycles_p99, 4096u);
  EXPECT_EQ(s.status.prepare_us_last, 1800u);
  EXPECT_EQ(s.status.loop_pass_max_us, 950u);
  EXPECT_EQ(s.status.zforce_layout_beside, 11u);
  EXPECT_EQ(s.status.zforce_layout_inside, 12u);
  EXPECT_EQ(s.status.firmware_version, 0x0102);
  EXPECT_EQ(s.status.tick_cycles_mean, 1234u);
  EXPECT_EQ(s.status.tick_cycles_max, 5678u);
  EXPECT_EQ(s.status.watchdog_trips, 2u);
  EXPECT_EQ(s.status.stream_overruns, 17u);
  EXPECT_FLOAT_EQ(s.status.force_mN, 412.5f);
  EXPECT_FLOAT_EQ(s.status.carrier_hz, 34900.0f);
  EXPECT_TRUE(s.status.finger_present);
  EXPECT_FALSE(s.status.over_force);
  EXPECT_EQ(s.status.faults[Fault::JumpRejected], 3u);

  Message t;
  t.type = MessageType::Ticks;
  t.ticks.count = 2;
  t.ticks.ticks[0] = {1000, 0.25f, 1024, true};
  t.ticks.ticks[1] = {1500, 0.0f, 4095, false};
  const Message tt = round_trip(t);
  ASSERT_EQ(tt.ticks.count, 2);
  EXPECT_EQ(tt.ticks.ticks[0].dac, 1024);
  EXPECT_TRUE(tt.ticks.ticks[0].present);
  EXPECT_EQ(tt.ticks.ticks[1].dac, 4095);
  EXPECT_FALSE(tt.ticks.ticks[1].present);

  Message sm;
  sm.type = MessageType::Samples;
  sm.samples.count = 1;
  sm.samples.samples[0] = {4294967000u, 12.5f, 300.25f, true};
  const Message ss = round_trip(sm);
  EXPECT_EQ(ss.samples.samples[0].t_us, 4294967000u);
  EXPECT_FLOAT_EQ(ss.samples.samples[0].y, 300.25f);
  EXPECT_FALSE(ss.samples.has_taken_times);
  EXPECT_EQ(frame_of(sm).size(), 7u + 2u + 13u + 2u);
  sm.samples.has_taken_times = true;
  sm.samples.taken_us[0] = 200u;  // the tick after the wrap
  const Message st2 = round_trip(sm);
  EXPECT_TRUE(st2.samples.has_taken_times);
  EXPECT_EQ(st2.samples.taken_us[0], 200u);
  EXPECT_EQ(frame_of(sm).size(), 7u + 2u + 17u + 2u);

  Message c = condition(ConditionKind::Frictionmap);
  c.type = MessageType::Condition;
  c.condition.target = Target::Bottom;
  EXPECT_EQ(round_trip(c).condition.target, Target::Bottom);

  Message a;
  a.type = MessageType::Ack;
  a.ack = {MessageType::SetCondition, AckStatus::Refused, 2};
  EXPECT_EQ(round_trip(a).ack.detail, 2);

  Message e;
  e.type = MessageType::Error;
  e.error = {ErrorCode::BadCrc, 0x01};
  EXPECT_EQ(round_trip(e).error.code, ErrorCode::BadCrc);

  Message sw;
  sw.type = MessageType::StartSweep;
  sw.sweep = {30000.0f, 40000.0f, 5000};
  EXPECT_EQ(round_trip(sw).sweep.duration_ms, 5000u);
}

TEST(Codec, EveryFramingFaultIsRejected) {
  const std::vector<uint8_t> good = frame_of(condition(ConditionKind::Heightmap));
  EXPECT_EQ(status_of({}), DecodeStatus::TooShort);
  EXPECT_EQ(status_of(std::vector<uint8_t>(good.begin(), good.begin() + 8)), DecodeStatus::TooShort);
  auto bad = good;
  bad[0] = 'X';
  EXPECT_EQ(status_of(bad), DecodeStatus::BadMagic);
  bad = good;
  bad[2] = 1;  // the previous version
  EXPECT_EQ(status_of(bad), DecodeStatus::BadVersion);
  bad = good;
  bad.push_back(0);
  EXPECT_EQ(status_of(bad), DecodeStatus::BadLength);
  bad = good;
  bad.pop_back();
  EXPECT_EQ(status_of(bad), DecodeStatus::BadLength);
  bad = good;
  bad[5] = 0xFF;  // claims 1535 bytes: over the maximum
  bad[6] = 0x05;
  EXPECT_EQ(status_of(bad), DecodeStatus::BadLength);
  for (size_t i = 2; i < good.size(); ++i) {  // any flipped bit outside the magic
    if (i == 5 || i == 6) continue;         // (the length is caught first)
    bad = good;
    bad[i] ^= 0x10;
    EXPECT_EQ(status_of(bad), i == 2 ? DecodeStatus::BadVersion : DecodeStatus::BadCrc) << "byte " << i;
  }
  bad = good;
  bad[3] = 0x55;
  EXPECT_EQ(status_of(reseal(bad)), DecodeStatus::UnknownType);
}

// The Status tail after the fault counters, byte by byte: the device counts
// (their number, then each), the sensor's state, the zForce counts.
TEST(Codec, StatusEndsWithTheDeviceCountsTheSensorStateAndItsCounts) {
  Message m;
  m.type = MessageType::Status;
  m.status.device[DeviceCount::ConditionsSet] = 0x01020304;
  m.status.device[DeviceCount::ForcePeriodsMissed] = 0xA0B0C0D0;
  m.status.device[DeviceCount::UdpUnavailable] = 1;
  m.status.sensor_state = SensorState::Failed;
  m.status.sensor_count_n = 2;
  m.status.sensor_counts[0] = 5;
  m.status.sensor_counts[1] = 0x0100;
  m.status.sensor_counts[2] = 77;  // beyond the count: not sent
  const std::vector<uint8_t> f = frame_of(m);
  std::vector<uint8_t> tail = {14, 0x04, 0x03, 0x02, 0x01};
  tail.insert(tail.end(), 11 * 4, 0);
  for (uint8_t b : {0xD0, 0xC0, 0xB0, 0xA0, 1, 0, 0, 0, 3, 2, 5, 0, 0, 0, 0, 1, 0, 0}) tail.push_back(b);
  ASSERT_GT(f.size(), tail.size() + 2);
  EXPECT_EQ(std::vector<uint8_t>(f.end() - 2 - tail.size(), f.end() - 2), tail);
  const Message out = round_trip(m);
  EXPECT_EQ(out.status.device[DeviceCount::ConditionsSet], 0x01020304u);
  EXPECT_EQ(out.status.device[DeviceCount::ForcePeriodsMissed], 0xA0B0C0D0u);
  EXPECT_EQ(out.status.device[DeviceCount::UdpUnavailable], 1u);
  EXPECT_EQ(out.status.sensor_state, SensorState::Failed);
  ASSERT_EQ(out.status.sensor_count_n, 2);
  EXPECT_EQ(out.status.sensor_counts[1], 0x0100u);
  EXPECT_EQ(out.status.sensor_counts[2], 0u);
}

TEST(DeviceCount, EachHasItsOwnName) {
  std::set<std::string> names;
  for (int i = 0; i < static_cast<int>(DeviceCount::kCount); ++i) {
    const std::string name = to_string(static_cast<DeviceCount>(i));
    EXPECT_NE(name, "?");
    EXPECT_TRUE(names.insert(name).second) << name;
  }
  EXPECT_STREQ(to_string(DeviceCount::kCount), "?");
  EXPECT_STREQ(to_string(SensorState::Booting), "booting");
  EXPECT_STREQ(to_string(SensorState::Configuring), "configuring");
  EXPECT_STREQ(to_string(SensorState::Running), "running");
  EXPECT_STREQ(to_string(SensorState::Failed), "failed");
  EXPECT_STREQ(to_string(SensorState::Unknown), "unknown");
}

// A Status payload of firmware 1.0 (it ends after the faults): version, kind 2,
// target 1, then zeros: strength, six counters, force, flags (byte
// kStatusFlags), carrier, seven more counters, and no faults.
constexpr size_t kStatusFlags = 2 + 1 + 1 + 4 + 6 * 4 + 4;
std::vector<uint8_t> status_payload_of_firmware_1_0() {
  std::vector<uint8_t> p = {0x00, 0x01, 2, 1};
  p.insert(p.end(), 4 + 6 * 4 + 4 + 1 + 4 + 7 * 4, 0);
  p.push_back(0);  // no faults
  return p;
}

TEST(Codec, StatusFieldsOutOfRangeAreMalformed) {
  const auto status_with = [](size_t at, uint8_t value) {
    std::vector<uint8_t> p = status_payload_of_firmware_1_0();
    p[at] = value;
    return status_of(frame_with_payload(MessageType::Status, p));
  };
  EXPECT_EQ(status_with(2, 3), DecodeStatus::Ok);  // kind 3: general
  EXPECT_EQ(status_with(2, 4), DecodeStatus::Malformed);
  EXPECT_EQ(status_with(3, 2), DecodeStatus::Ok);  // target 2
  EXPECT_EQ(status_with(3, 3), DecodeStatus::Malformed);
  EXPECT_EQ(status_with(kStatusFlags, 3), DecodeStatus::Ok);  // over force, finger present
  EXPECT_EQ(status_with(kStatusFlags, 4), DecodeStatus::Malformed);
}

TEST(Codec, StatusTailsOfOtherFirmwareVersions) {
  const std::vector<uint8_t> fixed = status_payload_of_firmware_1_0();
  const auto u32 = [](std::vector<uint8_t>& p, uint32_t v) {
    for (int i = 0; i < 4; ++i) p.push_back(static_cast<uint8_t>(v >> (8 * i)));
  };
  Message out;
  // Firmware 1.0 ended after the faults.
  std::vector<uint8_t> f = frame_with_payload(MessageType::Status, fixed);
  ASSERT_EQ(decode(f.data(), f.size(), out), DecodeStatus::Ok);
  EXPECT_EQ(out.status.sensor_state, SensorState::Unknown);
  EXPECT_EQ(out.status.sensor_count_n, 0);
  // A newer one counting two more things, with 40 sensor counts: what is known is kept.
  std::vector<uint8_t> p = fixed;
  p.push_back(15);
  for (uint32_t i = 1; i <= 15; ++i) u32(p, i);
  p.push_back(2);
  p.push_back(40);
  for (uint32_t i = 100; i < 140; ++i) u32(p, i);
  f = frame_with_payload(MessageType::Status, p);
  ASSERT_EQ(decode(f.data(), f.size(), out), DecodeStatus::Ok);
  for (int i = 0; i < static_cast<int>(DeviceCount::kCount); ++i) EXPECT_EQ(out.status.device.count[i], i + 1u);
  EXPECT_EQ(out.status.sensor_state, SensorState::Running);
  ASSERT_EQ(out.status.sensor_count_n, kMaxSensorCounts);
  EXPECT_EQ(out.status.sensor_counts[kMaxSensorCounts - 1], 100u + kMaxSensorCounts - 1);
  // A state past Unknown, or a tail cut short: malformed.
  std::vector<uint8_t> bad = fixed;
  bad.push_back(0);
  bad.push_back(static_cast<uint8_t>(SensorState::Unknown) + 1);
  bad.push_back(0);
  EXPECT_EQ(status_of(frame_with_payload(MessageType::Status, bad)), DecodeStatus::Malformed);
  bad[bad.size() - 2] = static_cast<uint8_t>(SensorState::Failed);
  EXPECT_EQ(status_of(frame_with_payload(MessageType::Status, bad)), DecodeStatus::Ok);
  bad.pop_back();
  EXPECT_EQ(status_of(frame_with_payload(MessageType::Status, bad)), DecodeStatus::Malformed);
}

TEST(Codec, EveryMalformedPayloadIsRejected) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  // Condition: kind, target, strength 1, idle 0, s-curve 0, calibration 2 points.
  auto cond = [](uint8_t kind, uint8_t target, float strength, uint8_t points) {
    std::vector<uint8_t> p = {kind, target};
    auto f32 = [&](float v) {
      uint8_t b[4];
      std::memcpy(b, &v, 4);  // the test host is little-endian, like the wire
      p.insert(p.end(), b, b + 4);
    };
    f32(strength);
    f32(0.0f);
    f32(0.0f);
    p.push_back(points);
    for (int i = 0; i < points; ++i) {
      f32(points > 1 ? static_cast<float>(i) / static_cast<float>(points - 1) : 0.0f);
      f32(points > 1 ? 4095.0f * static_cast<float>(i) / static_cast<float>(points - 1) : 0.0f);
    }
    return p;
  };
  EXPECT_EQ(status_of(frame_with_payload(MessageType::SetCondition, cond(0, 1, 1.0f, 2))), DecodeStatus::Ok);
  EXPECT_EQ(status_of(frame_with_payload(MessageType::SetCondition, cond(4, 1, 1.0f, 2))), DecodeStatus::Malformed);
  EXPECT_EQ(status_of(frame_with_payload(MessageType::SetCondition, cond(0, 3, 1.0f, 2))), DecodeStatus::Malformed);
  EXPECT_EQ(status_of(frame_with_payload(MessageType::SetCondition, cond(0, 1, 0.0f, 2))), DecodeStatus::Malformed);
  EXPECT_EQ(status_of(frame_with_payload(MessageType::SetCondition, cond(0, 1, 1.5f, 2))), DecodeStatus::Malformed);
  EXPECT_EQ(status_of(frame_with_payload(MessageType::SetCondition, cond(0, 1, nan, 2))), DecodeStatus::Malformed);
  EXPECT_EQ(status_of(frame_with_payload(MessageType::SetCondition, cond(0, 1, inf, 2))), DecodeStatus::Malformed);
  EXPECT_EQ(status_of(frame_with_payload(MessageType::SetCondition, cond(0, 1, 1.0f, 1))), DecodeStatus::Malformed);
  EXPECT_EQ(status_of(frame_with_payload(MessageType::SetCondition, cond(0, 1, 1.0f, 17))), DecodeStatus::Malformed);
  // Truncated and overlong payloads.
  auto p = cond(0, 1, 1.0f, 2);
  p.pop_back();
  EXPECT_EQ(status_of(frame_with_payload(MessageType::SetCondition, p)), DecodeStatus::Malformed);
  p = cond(0, 1, 1.0f, 2);
  p.push_back(0);
  EXPECT_EQ(status_of(frame_with_payload(MessageType::SetCondition, p)), DecodeStatus::Malformed);
  EXPECT_EQ(status_of(frame_with_payload(MessageType::QueryStatus, {0})), DecodeStatus::Malformed);
  // A non-monotonic calibration.
  Message m = condition(ConditionKind::Neutral);
  m.condition.calibration.code[1] = 0.0f;
  std::vector<uint8_t> flat(kMaxFrame);
  flat.resize(encode(m, flat.data(), flat.size()));
  EXPECT_EQ(status_of(flat), DecodeStatus::Malformed);
  // General scene (after 15 condition and 16 calibration bytes): rendering at
  // +0, element count at +16, the first element's kind at +17.
  Message g = condition(ConditionKind::General);
  g.condition.scene.element_count = 1;
  auto bad = frame_of(g);
  bad[7 + 15 + 16 + 16] = 9;
  EXPECT_EQ(status_of(reseal(bad)), DecodeStatus::Malformed);
  bad = frame_of(g);
  bad[7 + 15 + 16] = 3;  // rendering 3
  EXPECT_EQ(status_of(reseal(bad)), DecodeStatus::Malformed);
  bad = frame_of(g);
  bad[7 + 15 + 16 + 17] = 6;  // element kind 6
  EXPECT_EQ(status_of(reseal(bad)), DecodeStatus::Malformed);
  // Streams: counts over the limit, reserved bits, flags that are not 0/1.
  EXPECT_EQ(status_of(frame_with_payload(MessageType::Samples, {25, 0})), DecodeStatus::Malformed);
  EXPECT_EQ(status_of(frame_with_payload(MessageType::Samples, {0, 2})), DecodeStatus::Malformed);  // flags
  EXPECT_EQ(status_of(frame_with_payload(MessageType::Ticks, {33})), DecodeStatus::Malformed);
  std::vector<uint8_t> ticks(1 + 33 * 10, 0);  // 33 whole records: one more than a message holds
  ticks[0] = 33;
  EXPECT_EQ(status_of(frame_with_payload(MessageType::Ticks, ticks)), DecodeStatus::Malformed);
  ticks.resize(1 + 32 * 10);
  ticks[0] = 32;
  EXPECT_EQ(status_of(frame_with_payload(MessageType::Ticks, ticks)), DecodeStatus::Ok);
  EXPECT_EQ(status_of(frame_with_payload(MessageType::Ticks, {1, 0, 0, 0, 0, 0, 0, 0, 0, 0x00, 0x10})),
            DecodeStatus::Malformed);  // dac bit 12
  EXPECT_EQ(status_of(frame_with_payload(MessageType::Ticks, {1, 0, 0, 0, 0, 0, 0, 0, 0, 0xFF, 0x8F})),
            DecodeStatus::Ok);
  EXPECT_EQ(status_of(frame_with_payload(MessageType::Samples, {1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 2})),
            DecodeStatus::Malformed);  // touch 2
  EXPECT_EQ(status_of(frame_with_payload(MessageType::Samples, {1, 0, 0, 0, 0, 0, 0, 0, 0xC0, 0x7F, 0, 0, 0, 0, 1})),
            DecodeStatus::Malformed);  // x NaN
  EXPECT_EQ(status_of(frame_with_payload(MessageType::Samples, {1, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1})),
            DecodeStatus::Malformed);  // taken times announced, missing
  EXPECT_EQ(status_of(frame_with_payload(MessageType::StartStream, {0})), DecodeStatus::Malformed);
  EXPECT_EQ(status_of(frame_with_payload(MessageType::SetCarrier, {0, 0, 0x80, 0x7F})), DecodeStatus::Malformed);
  EXPECT_EQ(status_of(frame_with_payload(MessageType::Ack, {0x55, 0, 0})), DecodeStatus::Malformed);
  EXPECT_EQ(status_of(frame_with_payload(MessageType::Ack, {0x01, 2, 0})), DecodeStatus::Malformed);
  EXPECT_EQ(status_of(frame_with_payload(MessageType::Error, {0, 1})), DecodeStatus::Malformed);
  EXPECT_EQ(status_of(frame_with_payload(MessageType::Force, {0, 0, 0, 0, 0, 0, 0, 0, 2})), DecodeStatus::Malformed);
}

TEST(Codec, ElementAndCurveKindsAndPolylineSizesAreChecked) {
  // A general condition of one element: the element from byte 55 (7 header,
  // 15 condition, 16 calibration, 17 scene), its kind, weight, then its own fields.
  constexpr size_t kElement = 7 + 15 + 16 + 17, kCurve = kElement + 5, kCount = kCurve + 1;
  Message g = condition(ConditionKind::General);
  g.condition.scene.element_count = 1;
  FieldElement& e = g.condition.scene.elements[0];
  // Kind 6, nothing after its weight: only the kind's own check can refuse
  // it, for the payload's length is then what a kind without fields would have.
  e.kind = ElementKind::Vortex;
  std::vector<uint8_t> f = spliced(frame_of(g), kElement + 5, 8, {});  // the centre gone
  f[kElement] = 6;
  EXPECT_EQ(status_of(reseal(f)), DecodeStatus::Malformed);
  // Curve kind 3 laid out as a sine (every kind but the polyline has six numbers).
  e = FieldElement{};
  e.kind = ElementKind::PathSink;
  e.valley.curve.kind = CurveKind::Sine;
  f = frame_of(g);
  ASSERT_EQ(f[kCurve], static_cast<uint8_t>(CurveKind::Sine));
  f[kCurve] = 3;
  EXPECT_EQ(status_of(reseal(f)), DecodeStatus::Malformed);
  // A polyline of one point more than it may have, its points all there.
  e.valley.curve.kind = CurveKind::Polyline;
  e.valley.curve.count = kMaxPolylinePoints;
  for (int i = 0; i < kMaxPolylinePoints; ++i) e.valley.curve.points[i] = {10.0f * static_cast<float>(i), 100.0f};
  f = frame_of(g);
  ASSERT_EQ(status_of(f), DecodeStatus::Ok);
  ASSERT_EQ(f[kCount], kMaxPolylinePoints);
  f = spliced(f, kCount + 1 + 8 * kMaxPolylinePoints, 0, std::vector<uint8_t>(8, 0));
  f[kCount] = kMaxPolylinePoints + 1;
  EXPECT_EQ(status_of(reseal(f)), DecodeStatus::Malformed);
}

TEST(Codec, ABadHeaderLeavesTheOutputUntouchedAMalformedPayloadLeavesItDefault) {
  Message out;
  out.type = MessageType::Force;
  out.force.force_mN = 12.0f;
  auto bad = frame_of(condition(ConditionKind::Heightmap));
  bad[7] = 9;  // kind 9
  EXPECT_EQ(decode(bad.data(), bad.size(), out), DecodeStatus::BadCrc);
  EXPECT_EQ(decode(nullptr, 20, out), DecodeStatus::TooShort);
  EXPECT_EQ(out.type, MessageType::Force);
  EXPECT_FLOAT_EQ(out.force.force_mN, 12.0f);
  // Decoded in place: a bad payload is found after `out` was written, which
  // then holds a default Message (messages.hpp: QueryStatus, force 0), never half a condition.
  EXPECT_EQ(decode(reseal(bad).data(), bad.size(), out), DecodeStatus::Malformed);
  EXPECT_EQ(out.type, MessageType::QueryStatus);
  EXPECT_EQ(out.force.force_mN, 0.0f);
  EXPECT_EQ(out.condition.kind, ConditionKind::Heightmap);
}

TEST(Codec, DecodingInPlaceKeepsNothingOfWhatTheMessageHeldBefore) {
  Message out;
  out.type = MessageType::Samples;
  out.samples.count = 3;
  out.samples.has_taken_times = true;
  for (int i = 0; i < 3; ++i) {
    out.samples.samples[i] = {100u + i, 1.0f, 2.0f, true};
    out.samples.taken_us[i] = 7u + i;
  }
  out.condition.kind = ConditionKind::General;
  out.condition.scene.element_count = 2;
  // One report, no taken times: bytes count 1, flags 0, t_us 5, x 0, y 0, touch 1.
  const auto f = frame_with_payload(MessageType::Samples, {1, 0, 5, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1});
  ASSERT_EQ(decode(f.data(), f.size(), out), DecodeStatus::Ok);
  EXPECT_EQ(out.samples.count, 1);
  EXPECT_FALSE(out.samples.has_taken_times);
  EXPECT_EQ(out.samples.samples[0].t_us, 5u);
  EXPECT_TRUE(out.samples.samples[0].touch);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(out.samples.taken_us[i], 0u) << i;  // as in a fresh Message
  EXPECT_EQ(out.samples.samples[1].t_us, 0u);
  EXPECT_EQ(out.condition.kind, ConditionKind::Heightmap);
  EXPECT_EQ(out.condition.scene.element_count, 0);
}

TEST(Codec, EncodeRefusesASmallBufferAndNonFiniteNumbers) {
  Message m;
  m.type = MessageType::Status;
  uint8_t small[10];
  EXPECT_EQ(encode(m, small, sizeof small), 0u);
  std::vector<uint8_t> buf(kMaxFrame);
  EXPECT_EQ(encode(m, buf.data(), 0), 0u);
  EXPECT_EQ(encode(m, nullptr, buf.size()), 0u);
  m.status.force_mN = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(encode(m, buf.data(), buf.size()), 0u);
  // Exactly enough room works, one byte less does not.
  Message q;
  q.type = MessageType::QueryStatus;
  EXPECT_EQ(encode(q, buf.data(), kHeaderBytes + kCrcBytes), kHeaderBytes + kCrcBytes);
  EXPECT_EQ(encode(q, buf.data(), kHeaderBytes + kCrcBytes - 1), 0u);
}

// {1.5 px, 0.5 px over 250 ms, 0.25 px, 200 Hz, 150 us, 3000 us, 9.5 Hz}: every float exact in binary.
SensorProfile example_profile() { return {1.5f, 0.5f, 250.0f, 0.25f, 200.0f, 150.0f, 3000u, 9.5f}; }

TEST(Codec, SensorProfileIsTheHandDerivedFrame) {
  Message m;
  m.type = MessageType::SetSensorProfile;
  m.sequence = 3;
  m.sensor_profile = example_profile();
  // 32 bytes: 1.5f = 0x3FC00000, 0.5f = 0x3F000000, 250.0f = 0x437A0000, 0.25f = 0x3E800000,
  // 200.0f = 0x43480000, 150.0f = 0x43160000 (each little-endian), 3000 = 0x00000BB8, 9.5f =
  // 0x41180000. CRC 0x4A64: binascii.crc_hqx(bytes([2, 9, 3, 32, 0]) + payload, 0xFFFF), computed
  // outside the project.
  const std::vector<uint8_t> expected = {'F',  'F',  2,    0x09, 3,    0x20, 0x00, 0x00, 0x00, 0xC0, 0x3F, 0x00,
                                         0x00, 0x00, 0x3F, 0x00, 0x00, 0x7A, 0x43, 0x00, 0x00, 0x80, 0x3E, 0x00,
                                         0x00, 0x48, 0x43, 0x00, 0x00, 0x16, 0x43, 0xB8, 0x0B, 0x00, 0x00, 0x00,
                                         0x00, 0x18, 0x41, 0x64, 0x4A};
  EXPECT_EQ(frame_of(m), expected);
  Message out;
  ASSERT_EQ(decode(expected.data(), expected.size(), out), DecodeStatus::Ok);
  EXPECT_EQ(out.type, MessageType::SetSensorProfile);
  EXPECT_EQ(out.sensor_profile.white_noise_px, 1.5f);
  EXPECT_EQ(out.sensor_profile.correlated_noise_px, 0.5f);
  EXPECT_EQ(out.sensor_profile.correlation_time_ms, 250.0f);
  EXPECT_EQ(out.sensor_profile.tremor_px, 0.25f);
  EXPECT_EQ(out.sensor_profile.report_rate_hz, 200.0f);
  EXPECT_EQ(out.sensor_profile.jitter_us, 150.0f);
  EXPECT_EQ(out.sensor_profile.latency_us, 3000u);
  EXPECT_EQ(out.sensor_profile.tremor_hz, 9.5f);
}

TEST(Codec, TheQueryAndTheReplyOfASensorProfileRoundTrip) {
  Message q;
  q.type = MessageType::QuerySensorProfile;
  q.sequence = 4;
  EXPECT_EQ(frame_of(q).size(), kHeaderBytes + kCrcBytes);  // no payload
  round_trip(q);
  Message r;
  r.type = MessageType::SensorProfile;
  r.sensor_profile = example_profile();
  r.sensor_profile.latency_us = 0xFEDCBA98u;  // all 32 bits travel
  const Message out = round_trip(r);
  EXPECT_EQ(out.sensor_profile.latency_us, 0xFEDCBA98u);
  EXPECT_EQ(out.sensor_profile.tremor_px, 0.25f);
  EXPECT_EQ(out.sensor_profile.tremor_hz, 9.5f);
  Message ack;
  ack.type = MessageType::Ack;
  ack.ack = {MessageType::SetSensorProfile, AckStatus::Refused, 0};
  EXPECT_EQ(round_trip(ack).ack.command, MessageType::SetSensorProfile);
}

TEST(Codec, ASensorProfileNeedsItsWholePayloadAndFiniteNumbersButNotValidOnes) {
  auto payload = [](const SensorProfile& p) {
    std::vector<uint8_t> b(32);
    const float f[6] = {p.white_noise_px, p.correlated_noise_px, p.correlation_time_ms,
                        p.tremor_px,      p.report_rate_hz,      p.jitter_us};
    std::memcpy(b.data(), f, 24);  // the test host is little-endian, like the wire
    std::memcpy(b.data() + 24, &p.latency_us, 4);
    std::memcpy(b.data() + 28, &p.tremor_hz, 4);
    return b;
  };
  const std::vector<uint8_t> good = payload(example_profile());
  EXPECT_EQ(status_of(frame_with_payload(MessageType::SetSensorProfile, good)), DecodeStatus::Ok);
  // A host from before the tremor's frequency sends 28 bytes: read as not measured.
  const std::vector<uint8_t> before = frame_with_payload(MessageType::SetSensorProfile, {good.begin(), good.end() - 4});
  Message old;
  ASSERT_EQ(decode(before.data(), before.size(), old), DecodeStatus::Ok);
  EXPECT_EQ(old.sensor_profile.latency_us, 3000u);
  EXPECT_EQ(old.sensor_profile.tremor_hz, 0.0f);
  for (size_t cut = 1; cut < 4; ++cut)
    EXPECT_EQ(status_of(frame_with_payload(MessageType::SetSensorProfile, {good.begin(), good.end() - cut})),
              DecodeStatus::Malformed) << cut;
  EXPECT_EQ(status_of(frame_with_payload(MessageType::SetSensorProfile, {good.begin(), good.end() - 1})),
            DecodeStatus::Malformed);
  std::vector<uint8_t> longer = good;
  longer.push_back(0);
  EXPECT_EQ(status_of(frame_with_payload(MessageType::SetSensorProfile, longer)), DecodeStatus::Malformed);
  EXPECT_EQ(status_of(frame_with_payload(MessageType::QuerySensorProfile, {0})), DecodeStatus::Malformed);
  // A NaN (0x7FC00000) or an infinity (0x7F800000) in any of the seven floats: malformed.
  for (size_t field : {0, 1, 2, 3, 4, 5, 7}) {
    for (uint32_t bits : {0x7FC00000u, 0x7F800000u, 0xFF800000u}) {
      std::vector<uint8_t> bad = good;
      std::memcpy(bad.data() + 4 * field, &bits, 4);
      EXPECT_EQ(status_of(frame_with_payload(MessageType::SetSensorProfile, bad)), DecodeStatus::Malformed)
          << "field " << field << " bits " << std::hex << bits;
    }
  }
  std::vector<uint8_t> buf(kMaxFrame);
  Message m;
  m.type = MessageType::SetSensorProfile;
  m.sensor_profile.jitter_us = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(encode(m, buf.data(), buf.size()), 0u);
  // Finite but outside the limits (negative noise, 1 Hz, a wander without its time): the
  // codec carries it; the device judges it and answers Ack refused.
  SensorProfile odd = example_profile();
  odd.white_noise_px = -1.0f;
  odd.report_rate_hz = 1.0f;
  odd.correlation_time_ms = 0.0f;
  EXPECT_EQ(status_of(frame_with_payload(MessageType::SetSensorProfile, payload(odd))), DecodeStatus::Ok);
}

TEST(Codec, ErrorCodesNameTheFailedCheck) {
  EXPECT_EQ(error_code_for(DecodeStatus::TooShort), ErrorCode::TooShort);
  EXPECT_EQ(error_code_for(DecodeStatus::BadMagic), ErrorCode::BadMagic);
  EXPECT_EQ(error_code_for(DecodeStatus::BadVersion), ErrorCode::BadVersion);
  EXPECT_EQ(error_code_for(DecodeStatus::BadLength), ErrorCode::BadLength);
  EXPECT_EQ(error_code_for(DecodeStatus::BadCrc), ErrorCode::BadCrc);
  EXPECT_EQ(error_code_for(DecodeStatus::UnknownType), ErrorCode::UnknownType);
  EXPECT_EQ(error_code_for(DecodeStatus::Malformed), ErrorCode::Malformed);
  EXPECT_STREQ(to_string(ErrorCode::BadVersion), "unsupported protocol version");
  EXPECT_STREQ(to_string(DecodeStatus::BadLength), "length does not match");
}

}  // namespace
}  // namespace ff::protocol
