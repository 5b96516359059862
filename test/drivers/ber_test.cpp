// BER (X.690) items as the zForce speaks them: tags of one or two octets,
// lengths of up to two octets. Every byte sequence is written out by hand
// from X.690 section 8.1; each reader check has the shortest input it refuses.
#include "frictionfield/drivers/ber.hpp"

#include <gtest/gtest.h>

namespace ff::ber {
namespace {

TEST(BerReader, ReadsAHighTagNumberFromItsSecondOctet) {
  // [APPLICATION 32] primitive: 0x5F (class 01, number 11111) then 0x20, length 1.
  const uint8_t item[] = {0x5F, 0x20, 0x01, 0xAA};
  Tlv t;
  ASSERT_EQ(read_tlv(item, sizeof(item), t), Status::Ok);
  EXPECT_EQ(t.tag, 0x5F20);
  EXPECT_FALSE(t.constructed);
  EXPECT_EQ(t.length, 1u);
  EXPECT_EQ(t.value, item + 3);
  EXPECT_EQ(t.size, 4u);
}

TEST(BerReader, NothingOrOneOctetIsTruncated) {
  Tlv t;
  EXPECT_EQ(read_tlv(nullptr, 0, t), Status::Truncated);
  const uint8_t tag_only[] = {0x04};
  EXPECT_EQ(read_tlv(tag_only, 1, t), Status::Truncated);
}

TEST(BerReader, AHighTagWithoutItsLengthIsTruncated) {
  // The third octet lies beyond what is available: it must not be read.
  const uint8_t item[] = {0x5F, 0x20, 0x00};
  Tlv t;
  EXPECT_EQ(read_tlv(item, 2, t), Status::Truncated);
}

TEST(BerReader, ALongLengthWithoutItsOctetsIsTruncated) {
  // 0x82: two length octets follow, one is available.
  const uint8_t item[] = {0x04, 0x82, 0x00, 0x00};
  Tlv t;
  EXPECT_EQ(read_tlv(item, 3, t), Status::Truncated);
  EXPECT_EQ(read_tlv(item, 4, t), Status::Ok);
  EXPECT_EQ(t.length, 0u);
}

TEST(BerReader, FiveOctetsOfUnsignedOnlyWithALeadingZero) {
  const uint8_t ok[] = {0x02, 0x05, 0x00, 0xFF, 0xFF, 0xFF, 0xFF};  // 2^32 - 1
  const uint8_t too_big[] = {0x02, 0x05, 0x01, 0x00, 0x00, 0x00, 0x00};  // 2^32
  Tlv t;
  uint32_t v = 0;
  ASSERT_EQ(read_tlv(ok, sizeof(ok), t), Status::Ok);
  ASSERT_TRUE(read_unsigned(t, v));
  EXPECT_EQ(v, 0xFFFFFFFFu);
  ASSERT_EQ(read_tlv(too_big, sizeof(too_big), t), Status::Ok);
  EXPECT_FALSE(read_unsigned(t, v));
}

TEST(BerWriter, WidensALengthPast127) {
  uint8_t buf[200];
  Writer w(buf, sizeof(buf));
  w.begin(0x30);
  uint8_t payload[130] = {};
  w.octets(0x04, payload, sizeof(payload));
  w.end();
  ASSERT_TRUE(w.ok());
  EXPECT_EQ(w.size(), 3u + 3u + 130u);
  EXPECT_EQ(buf[1], 0x81);
  EXPECT_EQ(buf[2], 133);
  Tlv t;
  ASSERT_EQ(read_tlv(buf, w.size(), t), Status::Ok);
  EXPECT_EQ(t.length, 133u);
}

TEST(BerWriter, WritesAHighTagAndATwoOctetLength) {
  uint8_t buf[310];
  Writer w(buf, sizeof(buf));
  uint8_t payload[300] = {};  // 300 = 0x012C
  w.octets(0x5F20, payload, sizeof(payload));
  ASSERT_TRUE(w.ok());
  EXPECT_EQ(w.size(), 5u + 300u);
  const uint8_t header[] = {0x5F, 0x20, 0x82, 0x01, 0x2C};
  for (size_t i = 0; i < sizeof(header); ++i) EXPECT_EQ(buf[i], header[i]) << "octet " << i;
}

TEST(BerWriter, WideningAnItemMovesItsContentBehindTheLength) {
  uint8_t buf[320];
  Writer w(buf, sizeof(buf));
  uint8_t payload[300];
  for (size_t i = 0; i < sizeof(payload); ++i) payload[i] = static_cast<uint8_t>(i + 1);
  w.begin(0x30);
  w.octets(0x04, payload, sizeof(payload));
  w.end();
  ASSERT_TRUE(w.ok());
  // SEQUENCE of 4 + 300 = 304 = 0x0130 octets, its OCTET STRING 300 = 0x012C.
  const uint8_t header[] = {0x30, 0x82, 0x01, 0x30, 0x04, 0x82, 0x01, 0x2C};
  ASSERT_EQ(w.size(), sizeof(header) + sizeof(payload));
  for (size_t i = 0; i < sizeof(header); ++i) EXPECT_EQ(buf[i], header[i]) << "octet " << i;
  for (size_t i = 0; i < sizeof(payload); ++i) ASSERT_EQ(buf[sizeof(header) + i], payload[i]) << "payload " << i;
}

TEST(BerWriter, NoRoomToWidenALengthIsAnError) {
  // SEQUENCE { OCTET STRING of 126 }: 2 + 2 + 126 = 130 octets with a short
  // length, but its 128 octets of content need a long one: 131.
  uint8_t payload[126] = {};
  for (size_t capacity : {130u, 131u}) {
    uint8_t buf[131];
    Writer w(buf, capacity);
    w.begin(0x30);
    w.octets(0x04, payload, sizeof(payload));
    w.end();
    EXPECT_EQ(w.ok(), capacity == 131u) << capacity;
  }
}

TEST(BerWriter, NestingDeeperThanItsLimitIsAnError) {
  for (int depth : {4, 5}) {  // four may be open at once
    uint8_t buf[64];
    Writer w(buf, sizeof(buf));
    for (int i = 0; i < depth; ++i) w.begin(0x30);
    for (int i = 0; i < 4; ++i) w.end();  // a refused fifth is not closed, and stays an error
    EXPECT_EQ(w.ok(), depth == 4) << depth;
  }
}

TEST(BerWriter, AfterAnErrorNothingMoreIsWritten) {
  uint8_t buf[8] = {0xA5, 0xA5};
  Writer w(buf, sizeof(buf));
  w.end();  // nothing open
  EXPECT_FALSE(w.ok());
  w.null(0x05);
  EXPECT_EQ(w.size(), 0u);
  EXPECT_EQ(buf[0], 0xA5);
}

}  // namespace
}  // namespace ff::ber
