// zForce frames: the request builders byte for byte against the frames
// Neonode's Arduino library sends, the decoder on hand-encoded frames, and
// one test per rejection reason.
#include "frictionfield/drivers/zforce_frame.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "frictionfield/drivers/zforce_protocol.hpp"

namespace ff::zforce {
namespace {

using Bytes = std::vector<uint8_t>;

template <typename Build>
Bytes built(Build build) {
  uint8_t buf[kMaxFrameBytes];
  const size_t n = build(buf, sizeof(buf));
  return Bytes(buf, buf + n);
}

// A touch notification, one touch, default format: id 0, down, x 400, y 960,
// size 48, confidence 100, timestamp 32.
const Bytes kTouch{0xEE, 0x16, 0xF0, 0x14, 0x40, 0x02, 0x02, 0x00, 0xA0, 0x0B, 0x42, 0x09,
                   0x00, 0x00, 0x01, 0x90, 0x03, 0xC0, 0x00, 0x30, 0x64, 0x58, 0x01, 0x20};

FrameError decode(const Bytes& b, Message& m, uint32_t max_x = 3200, uint32_t max_y = 1920) {
  FrameDecoder d;
  d.set_limits(max_x, max_y);
  return d.decode(b.data(), b.size(), m);
}

FrameError decode(const Bytes& b) {
  Message m;
  return decode(b, m);
}

// kTouch with its lengths recomputed after editing the touch content.
Bytes touch_frame(const Bytes& touches_content) {
  Bytes content{0x40, 0x02, 0x02, 0x00, 0xA0, static_cast<uint8_t>(touches_content.size())};
  content.insert(content.end(), touches_content.begin(), touches_content.end());
  Bytes payload{0xF0, static_cast<uint8_t>(content.size())};
  payload.insert(payload.end(), content.begin(), content.end());
  Bytes frame{0xEE, static_cast<uint8_t>(payload.size())};
  frame.insert(frame.end(), payload.begin(), payload.end());
  return frame;
}

Bytes one_touch(uint8_t id, uint8_t event, uint16_t x, uint16_t y) {
  return {0x42, 0x09, id, event, static_cast<uint8_t>(x >> 8), static_cast<uint8_t>(x), static_cast<uint8_t>(y >> 8),
          static_cast<uint8_t>(y), 0x00, 0x30, 0x64};
}

TEST(ZforceRequests, MatchTheArduinoLibraryBytes) {
  EXPECT_EQ(built(build_touch_format_request), (Bytes{0xEE, 0x08, 0xEE, 0x06, 0x40, 0x02, 0x02, 0x00, 0x66, 0x00}));
  EXPECT_EQ(built([](uint8_t* b, size_t n) { return build_enable(b, n, true); }),
            (Bytes{0xEE, 0x0B, 0xEE, 0x09, 0x40, 0x02, 0x02, 0x00, 0x65, 0x03, 0x81, 0x01, 0x00}));
  EXPECT_EQ(built([](uint8_t* b, size_t n) { return build_enable(b, n, false); }),
            (Bytes{0xEE, 0x0A, 0xEE, 0x08, 0x40, 0x02, 0x02, 0x00, 0x65, 0x02, 0x80, 0x00}));
  EXPECT_EQ(built(build_operation_mode_detection),
            (Bytes{0xEE, 0x17, 0xEE, 0x15, 0x40, 0x02, 0x02, 0x00, 0x67, 0x0F, 0x80, 0x01, 0xFF, 0x81, 0x01, 0x00,
                   0x82, 0x01, 0x00, 0x83, 0x01, 0x00, 0x84, 0x01, 0x00}));
  EXPECT_EQ(built([](uint8_t* b, size_t n) { return build_frequency(b, n, 200, 50); }),
            (Bytes{0xEE, 0x0F, 0xEE, 0x0D, 0x40, 0x02, 0x00, 0x00, 0x68, 0x07, 0x80, 0x02, 0x00, 0xC8, 0x82, 0x01,
                   0x32}));
  EXPECT_EQ(built([](uint8_t* b, size_t n) { return build_reported_touches(b, n, 2); }),
            (Bytes{0xEE, 0x0B, 0xEE, 0x09, 0x40, 0x02, 0x02, 0x00, 0x73, 0x03, 0x86, 0x01, 0x02}));
  // resolution [APPLICATION 9] { x [0] 3200, y [1] 1920 }: 0x0C80, 0x0780.
  EXPECT_EQ(built([](uint8_t* b, size_t n) { return build_resolution(b, n, 3200, 1920); }),
            (Bytes{0xEE, 0x10, 0xEE, 0x0E, 0x40, 0x02, 0x02, 0x00, 0x69, 0x08, 0x80, 0x02, 0x0C, 0x80, 0x81, 0x02,
                   0x07, 0x80}));
}

TEST(ZforceRequests, TooSmallABufferGivesNothing) {
  uint8_t buf[8] = {};
  EXPECT_EQ(build_enable(buf, sizeof(buf), true), 0u);
  // No room even for the header: nothing written, not even the frame's start.
  EXPECT_EQ(build_enable(buf, 1, true), 0u);
  EXPECT_EQ(build_enable(buf, 0, true), 0u);
  EXPECT_EQ(buf[0], 0u);
  EXPECT_EQ(build_enable(nullptr, 64, true), 0u);
}

TEST(ZforceDecoder, DecodesATouchNotification) {
  Message m;
  ASSERT_EQ(decode(kTouch, m), FrameError::None);
  EXPECT_EQ(m.kind, MessageKind::Touches);
  EXPECT_TRUE(m.has_address);
  EXPECT_EQ(m.device_type, kDeviceTypeAir);
  ASSERT_EQ(m.touch_count, 1);
  EXPECT_EQ(m.touches[0].id, 0);
  EXPECT_EQ(m.touches[0].event, TouchEvent::Down);
  EXPECT_EQ(m.touches[0].x, 400u);
  EXPECT_EQ(m.touches[0].y, 960u);
  EXPECT_TRUE(m.has_timestamp);
  EXPECT_EQ(m.timestamp, 32u);
}

TEST(ZforceDecoder, TakesTheDeviceIndexFromTheAddress) {
  Bytes b = kTouch;
  b[7] = 0x05;  // address 40 02 02 05: an air device, the sixth
  Message m;
  ASSERT_EQ(decode(b, m), FrameError::None);
  EXPECT_EQ(m.device_type, kDeviceTypeAir);
  EXPECT_EQ(m.device_index, 5);
}

TEST(ZforceDecoder, ANewMessageForgetsTheLastOne) {
  // The driver decodes every frame into one Message: a response after a
  // touch must not still carry the touch or its timestamp.
  Message m;
  ASSERT_EQ(decode(kTouch, m), FrameError::None);
  ASSERT_EQ(decode({0xEE, 0x09, 0xEF, 0x07, 0x40, 0x02, 0x02, 0x00, 0x65, 0x01, 0x00}, m), FrameError::None);
  EXPECT_EQ(m.kind, MessageKind::Response);
  EXPECT_EQ(m.touch_count, 0);
  EXPECT_FALSE(m.has_timestamp);
  EXPECT_EQ(m.timestamp, 0u);
}

// The same touch with the timestamp inside the touch sequence: A0 0E { 42 09 ... 58 01 20 }.
// Lengths by hand: touch sequence 11 + 3 = 14 (0x0E), notification 4 + 2 + 14 = 20 (0x14).
const Bytes kTouchStampInside{0xEE, 0x16, 0xF0, 0x14, 0x40, 0x02, 0x02, 0x00, 0xA0, 0x0E, 0x42, 0x09,
                              0x00, 0x00, 0x01, 0x90, 0x03, 0xC0, 0x00, 0x30, 0x64, 0x58, 0x01, 0x20};

TEST(ZforceDecoder, TakesTheTimestampInsideTheTouchSequenceToo) {
  Message beside, inside;
  ASSERT_EQ(decode(kTouch, beside), FrameError::None);
  ASSERT_EQ(decode(kTouchStampInside, inside), FrameError::None);
  EXPECT_FALSE(beside.timestamp_inside);
  EXPECT_TRUE(inside.timestamp_inside);
  ASSERT_EQ(inside.touch_count, 1);
  EXPECT_EQ(inside.touches[0].x, 400u);
  EXPECT_EQ(inside.touches[0].y, 960u);
  EXPECT_TRUE(inside.has_timestamp);
  EXPECT_EQ(inside.timestamp, 32u);
  // Still malformed: a stamp in both places, two stamps inside, a sequence with a stamp and no touch.
  Bytes both = one_touch(0, 0, 400, 960);
  both.insert(both.end(), {0x58, 0x01, 0x20});
  Bytes framed = touch_frame(both);
  framed.insert(framed.end(), {0x58, 0x01, 0x20});
  framed[1] = static_cast<uint8_t>(framed.size() - 2);
  framed[3] = static_cast<uint8_t>(framed.size() - 4);
  EXPECT_EQ(decode(framed), FrameError::MalformedTag);
  Bytes twice = one_touch(0, 0, 400, 960);
  twice.insert(twice.end(), {0x58, 0x01, 0x20, 0x58, 0x01, 0x21});
  EXPECT_EQ(decode(touch_frame(twice)), FrameError::MalformedTag);
  EXPECT_EQ(decode(touch_frame(Bytes{0x58, 0x01, 0x20})), FrameError::MalformedTag);
}

TEST(ZforceDecoder, DecodesTwoTouchesASingleTouchAndLongLengths) {
  Bytes two = one_touch(0, 1, 100, 200);
  const Bytes second = one_touch(3, 0, 300, 400);
  two.insert(two.end(), second.begin(), second.end());
  Message m;
  ASSERT_EQ(decode(touch_frame(two), m), FrameError::None);
  ASSERT_EQ(m.touch_count, 2);
  EXPECT_EQ(m.touches[1].id, 3);
  EXPECT_EQ(m.touches[1].y, 400u);

  // singleTouch: a bare TouchNotification instead of the sequence, lengths in long form.
  const Bytes single{0xEE, 0x13, 0xF0, 0x81, 0x10, 0x40, 0x02, 0x02, 0x00, 0x42, 0x81, 0x09,
                     0x07, 0x02, 0x00, 0x10, 0x00, 0x20, 0x00, 0x30, 0x64};
  ASSERT_EQ(decode(single, m), FrameError::None);
  EXPECT_EQ(m.kind, MessageKind::Touches);
  ASSERT_EQ(m.touch_count, 1);
  EXPECT_EQ(m.touches[0].id, 7);
  EXPECT_EQ(m.touches[0].event, TouchEvent::Up);
  EXPECT_FALSE(m.has_timestamp);
}

TEST(ZforceDecoder, DecodesBootCompleteStatusAndResponses) {
  Message m;
  ASSERT_EQ(decode({0xEE, 0x0F, 0xF0, 0x0D, 0x40, 0x02, 0x00, 0x00, 0x63, 0x07, 0x80, 0x01, 0x00, 0x81, 0x02, 0x07, 0x80},
                   m),
            FrameError::None);
  EXPECT_EQ(m.kind, MessageKind::BootComplete);
  ASSERT_EQ(decode({0xEE, 0x0B, 0xF0, 0x09, 0x40, 0x02, 0x02, 0x00, 0x7B, 0x03, 0x81, 0x01, 0xFF}, m), FrameError::None);
  EXPECT_EQ(m.kind, MessageKind::OtherNotification);
  ASSERT_EQ(decode({0xEE, 0x0B, 0xEF, 0x09, 0x40, 0x02, 0x02, 0x00, 0x65, 0x03, 0x81, 0x01, 0x00}, m), FrameError::None);
  EXPECT_EQ(m.kind, MessageKind::Response);
  EXPECT_EQ(m.response_to, kEnable);
}

TEST(ZforceDecoder, LearnsATouchFormatWithThreeByteCoordinates) {
  // id, event, x1-x3, y1-y3: bits 0-7 = 0xFF, 8 bits used.
  Message m;
  ASSERT_EQ(decode({0xEE, 0x0C, 0xEF, 0x0A, 0x40, 0x02, 0x02, 0x00, 0x66, 0x04, 0x41, 0x02, 0x00, 0xFF}, m),
            FrameError::None);
  ASSERT_TRUE(m.has_format);
  EXPECT_EQ(m.format.bytes(), 8);
  FrameDecoder d;
  ASSERT_TRUE(d.set_format(m.format));
  d.set_limits(0xFFFFFF, 0xFFFFFF);
  const Bytes t = touch_frame({0x42, 0x08, 0x05, 0x01, 0x01, 0x02, 0x03, 0x00, 0x00, 0x09});
  ASSERT_EQ(d.decode(t.data(), t.size(), m), FrameError::None);
  EXPECT_EQ(m.touches[0].x, 0x010203u);
  EXPECT_EQ(m.touches[0].y, 9u);
}

TEST(ZforceDecoder, TouchDescriptorRules) {
  TouchFormat f;
  const uint8_t unused8[] = {0x08, 0xF6};
  EXPECT_EQ(parse_touch_descriptor(unused8, 2, f), FrameError::MalformedTag);
  const uint8_t no_id[] = {0x00, 0x76};  // event, x1, x2, y1, y2 without id
  EXPECT_EQ(parse_touch_descriptor(no_id, 2, f), FrameError::ImpossibleValue);
  const uint8_t bit23[] = {0x00, 0xF6, 0x18, 0x05};  // bit 23: no such field
  EXPECT_EQ(parse_touch_descriptor(bit23, 4, f), FrameError::ImpossibleValue);
  const uint8_t no_data[] = {0x00};  // the unused-bits octet alone
  EXPECT_EQ(parse_touch_descriptor(no_data, 1, f), FrameError::MalformedTag);
  EXPECT_EQ(parse_touch_descriptor(no_data, 0, f), FrameError::MalformedTag);
  const uint8_t forty_bits[] = {0x00, 0xF6, 0x18, 0x04, 0x00, 0x00};  // the default's fields, then 16 more bits
  EXPECT_EQ(parse_touch_descriptor(forty_bits, 6, f), FrameError::ImpossibleValue);
  const uint8_t ok[] = {0x01, 0xF6, 0x18, 0x04};
  ASSERT_EQ(parse_touch_descriptor(ok, 4, f), FrameError::None);
  EXPECT_EQ(f.fields, TouchFormat::assumed_default().fields);
  FrameDecoder d;
  TouchFormat unusable;
  EXPECT_FALSE(d.set_format(unusable));
}

TEST(ZforceDecoder, WrongHeader) { EXPECT_EQ(decode(Bytes{0xEF, 0x02, 0xF0, 0x00}), FrameError::WrongHeader); }

TEST(ZforceDecoder, LengthOverMax) {
  Bytes b(2 + 129, 0x00);
  b[0] = 0xEE;
  b[1] = 129;
  EXPECT_EQ(decode(b), FrameError::LengthOverMax);
}

TEST(ZforceDecoder, APayloadOverMaxIsRefusedEvenWhenWellFormed) {
  // 130 bytes: a response (EF 81 7F) of an address and an Enable member of
  // 121 bytes, valid BER, but longer than any frame the sensor sends.
  Bytes p{0xEF, 0x81, 0x7F, 0x40, 0x02, 0x02, 0x00, 0x65, 0x79};
  p.resize(130, 0x00);
  FrameDecoder d;
  Message m;
  EXPECT_EQ(d.decode_payload(p.data(), p.size(), m), FrameError::LengthOverMax);
  EXPECT_EQ(d.decode_payload(p.data(), kMaxFramePayload + 1, m), FrameError::LengthOverMax);
}

TEST(ZforceDecoder, Truncated) {
  Bytes short_frame(kTouch.begin(), kTouch.end() - 1);  // fewer bytes than the length byte says
  EXPECT_EQ(decode(short_frame), FrameError::Truncated);
  Bytes cut(kTouch.begin(), kTouch.end() - 3);  // the message cut, length byte agreeing
  cut[1] = static_cast<uint8_t>(cut.size() - 2);
  EXPECT_EQ(decode(cut), FrameError::Truncated);
  EXPECT_EQ(decode(Bytes{0xEE, 0x00}), FrameError::Truncated);
  EXPECT_EQ(decode(Bytes{0xEE}), FrameError::Truncated);
}

TEST(ZforceDecoder, MalformedTags) {
  Bytes b = kTouch;
  b[3] = 0x80;  // indefinite length
  EXPECT_EQ(decode(b), FrameError::MalformedTag);
  b = kTouch;
  b[9] = 0x83;  // three length octets
  EXPECT_EQ(decode(b), FrameError::MalformedTag);
  // High-tag form needing two subsequent octets.
  EXPECT_EQ(decode(Bytes{0xEE, 0x06, 0xF0, 0x04, 0x5F, 0x81, 0x01, 0x00}), FrameError::MalformedTag);
  b = kTouch;
  b.push_back(0x00);  // a byte after the message
  b[1] = static_cast<uint8_t>(b[1] + 1);
  EXPECT_EQ(decode(b), FrameError::MalformedTag);
  b = kTouch;
  b.push_back(0x00);  // a byte after the frame its length byte declares
  EXPECT_EQ(decode(b), FrameError::MalformedTag);
  // Timestamp before the notification; two notifications; address not first.
  EXPECT_EQ(decode({0xEE, 0x0B, 0xF0, 0x09, 0x40, 0x02, 0x02, 0x00, 0x58, 0x01, 0x20, 0xA0, 0x00}),
            FrameError::MalformedTag);
  EXPECT_EQ(decode({0xEE, 0x0A, 0xF0, 0x08, 0x40, 0x02, 0x02, 0x00, 0xA0, 0x00, 0xA0, 0x00}),
            FrameError::MalformedTag);
  EXPECT_EQ(decode({0xEE, 0x08, 0xF0, 0x06, 0xA0, 0x00, 0x40, 0x02, 0x02, 0x00}), FrameError::MalformedTag);
  // Timestamp of 6 octets; address of 3.
  EXPECT_EQ(decode({0xEE, 0x0C, 0xF0, 0x0A, 0xA0, 0x00, 0x58, 0x06, 0x01, 0x02, 0x03, 0x04, 0x05, 0x06}),
            FrameError::MalformedTag);
  EXPECT_EQ(decode({0xEE, 0x09, 0xF0, 0x07, 0x40, 0x03, 0x02, 0x00, 0x00, 0xA0, 0x00}), FrameError::MalformedTag);
  // A response with its address after a member; a touch format answer
  // holding its descriptor and one byte more.
  EXPECT_EQ(decode({0xEE, 0x08, 0xEF, 0x06, 0x65, 0x00, 0x40, 0x02, 0x02, 0x00}), FrameError::MalformedTag);
  EXPECT_EQ(decode({0xEE, 0x0D, 0xEF, 0x0B, 0x40, 0x02, 0x02, 0x00, 0x66, 0x05, 0x41, 0x02, 0x00, 0xFF, 0x00}),
            FrameError::MalformedTag);
  // A response answering nothing.
  EXPECT_EQ(decode({0xEE, 0x06, 0xEF, 0x04, 0x40, 0x02, 0x02, 0x00}), FrameError::MalformedTag);
}

TEST(ZforceDecoder, UnknownTags) {
  EXPECT_EQ(decode({0xEE, 0x08, 0xEE, 0x06, 0x40, 0x02, 0x02, 0x00, 0x66, 0x00}), FrameError::UnknownTag);  // a request
  Bytes b = kTouch;
  b[8] = 0xA5;  // [5] is no notification
  EXPECT_EQ(decode(b), FrameError::UnknownTag);
  b = kTouch;
  b[10] = 0x43;  // not a TouchNotification inside the sequence
  EXPECT_EQ(decode(b), FrameError::UnknownTag);
  EXPECT_EQ(decode({0xEE, 0x08, 0xEF, 0x06, 0x40, 0x02, 0x02, 0x00, 0x7E, 0x00}), FrameError::UnknownTag);
  // A touch format answer whose item is not a TouchDescriptor (42: a TouchNotification's tag).
  EXPECT_EQ(decode({0xEE, 0x0C, 0xEF, 0x0A, 0x40, 0x02, 0x02, 0x00, 0x66, 0x04, 0x42, 0x02, 0x00, 0xFF}),
            FrameError::UnknownTag);
  EXPECT_EQ(decode({0xEE, 0x02, 0x30, 0x00}), FrameError::UnknownTag);
}

TEST(ZforceDecoder, ImpossibleValues) {
  EXPECT_EQ(decode(touch_frame(one_touch(0, 5, 10, 10))), FrameError::ImpossibleValue);      // event 5
  EXPECT_EQ(decode(touch_frame(one_touch(0, 1, 3201, 10))), FrameError::ImpossibleValue);    // x beyond 3200
  EXPECT_EQ(decode(touch_frame(one_touch(0, 1, 10, 1921))), FrameError::ImpossibleValue);    // y beyond 1920
  EXPECT_EQ(decode(touch_frame(one_touch(0, 1, 3200, 1920))), FrameError::None);             // the edge itself
  EXPECT_EQ(decode(touch_frame(one_touch(0, 3, 0xFFFF, 0xFFFF))), FrameError::None);         // invalid: no position
  EXPECT_EQ(decode(touch_frame({0x42, 0x08, 0, 1, 0, 10, 0, 10, 0, 48})), FrameError::ImpossibleValue);  // 8 bytes
  Bytes dup = one_touch(2, 1, 10, 10);
  const Bytes again = one_touch(2, 1, 20, 20);
  dup.insert(dup.end(), again.begin(), again.end());
  EXPECT_EQ(decode(touch_frame(dup)), FrameError::ImpossibleValue);  // one id twice
  Bytes eleven;
  for (uint8_t i = 0; i < 11; ++i) {
    const Bytes t = one_touch(i, 1, 10, 10);
    eleven.insert(eleven.end(), t.begin(), t.end());
  }
  EXPECT_EQ(decode(touch_frame(eleven)), FrameError::LengthOverMax);  // 11 touches do not fit 128 bytes
  EXPECT_EQ(decode({0xEE, 0x08, 0xF0, 0x06, 0x40, 0x02, 0x09, 0x00, 0xA0, 0x00}), FrameError::ImpossibleValue);
}

TEST(ZforceDecoder, MoreTouchesThanTheSensorReportsAreImpossible) {
  // Eleven 3-byte touches (id, event, x1, y1 = 4 bytes) fit in a frame but the sensor reports ten at most.
  const uint8_t descriptor[] = {0x02, 0xE4};  // bits 0, 1, 2, 5 (6 bits used)
  TouchFormat f;
  ASSERT_EQ(parse_touch_descriptor(descriptor, 2, f), FrameError::None);
  ASSERT_EQ(f.bytes(), 4);
  FrameDecoder d;
  ASSERT_TRUE(d.set_format(f));
  Bytes touches;
  for (uint8_t i = 0; i < 11; ++i) touches.insert(touches.end(), {0x42, 0x04, i, 0x01, 0x10, 0x10});
  const Bytes frame = touch_frame(touches);
  Message m;
  EXPECT_EQ(d.decode(frame.data(), frame.size(), m), FrameError::ImpossibleValue);
}

TEST(ZforceDecoder, ErrorsHaveNames) {
  EXPECT_STREQ(to_string(FrameError::Truncated), "truncated");
  EXPECT_STREQ(to_string(FrameError::ImpossibleValue), "impossible value");
}

}  // namespace
}  // namespace ff::zforce
