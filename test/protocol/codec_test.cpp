#include "frictionfield/protocol/codec.hpp"

#include <gtest/gtest.h>

#include <cstring>
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

TEST(Codec, QueryStatusIsTheHandDerivedFrame) {
  Message m;
  m.type = MessageType::QueryStatus;
  m.sequence = 7;
  const std::vector<uint8_t> f = frame_of(m);
  // 'F' 'F' version 1, type 0x02, seq 7, length 0, CRC-16/CCITT-FALSE of 01 02 07 00 00
  // = 0xD3A5, low byte first. Computed outside the project, by Python's
  // binascii.crc_hqx(bytes([1, 2, 7, 0, 0]), 0xFFFF) and a bitwise loop
  // (poly 0x1021, init 0xFFFF, no reflection, no final xor).
  const std::vector<uint8_t> expected = {'F', 'F', 1, 0x02, 7, 0, 0, 0xA5, 0xD3};
  EXPECT_EQ(f, expected);
  EXPECT_EQ(crc16_ccitt(reinterpret_cast<const uint8_t*>("123456789"), 9), 0x29B1);  // the standard check value
}

TEST(Codec, ThesisConditionRoundTripsAndBecomesTheBuiltInScene) {
  Message m;
  m.type = MessageType::SetCondition;
  m.condition.kind = ConditionKind::Heightmap;
  m.condition.target = Target::Top;
  m.condition.strength = 0.66f;
  const Message out = round_trip(m);
  EXPECT_EQ(out.condition.kind, ConditionKind::Heightmap);
  EXPECT_EQ(out.condition.target, Target::Top);
  EXPECT_FLOAT_EQ(out.condition.strength, 0.66f);
  const Condition c = out.condition.to_condition();
  EXPECT_EQ(host::format_scene_text(c.scene), host::format_scene_text(scenes::heightmap(Target::Top)));
  EXPECT_FLOAT_EQ(c.amplitude.strength, 0.66f);
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
  Message m;
  m.type = MessageType::SetCondition;
  m.condition.kind = ConditionKind::General;
  m.condition.scene = s;
  m.condition.inverted_dac = true;
  const Message out = round_trip(m);
  EXPECT_EQ(host::format_scene_text(out.condition.scene), host::format_scene_text(s));
  EXPECT_TRUE(out.condition.inverted_dac);
}

TEST(Codec, DeviceMessagesRoundTrip) {
  Message st;
  st.type = MessageType::Status;
  st.status.firmware_version = 0x0102;
  st.status.tick_cycles_mean = 1234;
  st.status.tick_cycles_max = 5678;
  st.status.force_mN = 412.5f;
  st.status.over_force = false;
  st.status.finger_present = true;
  st.status.faults.count[static_cast<int>(Fault::JumpRejected)] = 3;
  const Message s = round_trip(st);
  EXPECT_EQ(s.status.firmware_version, 0x0102);
  EXPECT_EQ(s.status.tick_cycles_max, 5678u);
  EXPECT_TRUE(s.status.finger_present);
  EXPECT_EQ(s.status.faults[Fault::JumpRejected], 3u);

  Message t;
  t.type = MessageType::Ticks;
  t.ticks.count = 2;
  t.ticks.ticks[0] = {1000, 0.25f, 1024, true};
  t.ticks.ticks[1] = {1500, 0.0f, 0, false};
  const Message tt = round_trip(t);
  EXPECT_EQ(tt.ticks.count, 2);
  EXPECT_EQ(tt.ticks.ticks[0].dac, 1024);
  EXPECT_TRUE(tt.ticks.ticks[0].present);
  EXPECT_FALSE(tt.ticks.ticks[1].present);

  Message sm;
  sm.type = MessageType::Samples;
  sm.samples.count = 1;
  sm.samples.samples[0] = {4294967000u, 12.5f, 300.25f, true};
  const Message ss = round_trip(sm);
  EXPECT_EQ(ss.samples.samples[0].t_us, 4294967000u);
  EXPECT_FLOAT_EQ(ss.samples.samples[0].y, 300.25f);

  Message f;
  f.type = MessageType::Force;
  f.force = {30000, 520.0f, true};
  EXPECT_TRUE(round_trip(f).force.over_force);
}

TEST(Codec, EveryMalformedClassIsRejected) {
  Message m;
  m.type = MessageType::SetCondition;
  const std::vector<uint8_t> good = frame_of(m);
  Message out;
  auto status_of = [&](std::vector<uint8_t> f) { return decode(f.data(), f.size(), out); };
  EXPECT_EQ(status_of({}), DecodeStatus::TooShort);
  auto bad = good; bad[0] = 'X';
  EXPECT_EQ(status_of(bad), DecodeStatus::BadMagic);
  bad = good; bad[2] = 9;
  EXPECT_EQ(status_of(bad), DecodeStatus::BadVersion);
  bad = good; bad.push_back(0);
  EXPECT_EQ(status_of(bad), DecodeStatus::BadLength);
  bad = good; bad[8] ^= 0x40;
  EXPECT_EQ(status_of(bad), DecodeStatus::BadCrc);
  // A valid CRC around nonsense: unknown type, out-of-range enum, trailing bytes.
  auto reseal = [](std::vector<uint8_t> f) {
    const uint16_t crc = crc16_ccitt(f.data() + 2, f.size() - 4);
    f[f.size() - 2] = uint8_t(crc);
    f[f.size() - 1] = uint8_t(crc >> 8);
    return f;
  };
  bad = good; bad[3] = 0x55;
  EXPECT_EQ(status_of(reseal(bad)), DecodeStatus::UnknownType);
  bad = good; bad[7] = 9;  // condition kind 9
  EXPECT_EQ(status_of(reseal(bad)), DecodeStatus::Malformed);
  Message g;
  g.type = MessageType::SetCondition;
  g.condition.kind = ConditionKind::General;
  g.condition.scene.element_count = 1;
  bad = frame_of(g);
  bad[7 + 15 + 16] = 9;  // the scene's element count (after 15 condition + 16 scene bytes)
  EXPECT_EQ(status_of(reseal(bad)), DecodeStatus::Malformed);
  EXPECT_EQ(out.type, MessageType::QueryStatus);  // `out` untouched by failures
}

TEST(Codec, EncodeRefusesASmallBuffer) {
  Message m;
  m.type = MessageType::Status;
  uint8_t small[10];
  EXPECT_EQ(encode(m, small, sizeof small), 0u);
}

}  // namespace
}  // namespace ff::protocol
