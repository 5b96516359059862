// The zForce model: requests answered as Neonode documents them, traces
// turned into frames and DR edges, faults as asked. Frames checked byte by
// byte against hand encodings.
#include "frictionfield/emulated/zforce_model.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "frictionfield/emulated/i2c_bus.hpp"

namespace ff::emulated {
namespace {

using Bytes = std::vector<uint8_t>;

Bytes read_frame(EmulatedI2cBus& bus) {
  Bytes h(2);
  EXPECT_EQ(bus.read(0x50, h.data(), 2, 1000), BusStatus::Ok);
  Bytes p(h[1]);
  if (!p.empty()) {
    EXPECT_EQ(bus.read(0x50, p.data(), p.size(), 1000), BusStatus::Ok);
  }
  h.insert(h.end(), p.begin(), p.end());
  return h;
}

struct Fixture {
  ZforceModel model;
  EmulatedI2cBus bus;
  Fixture() { bus.attach(0x50, model); }
  void write(const Bytes& b) { ASSERT_EQ(bus.write(0x50, b.data(), b.size(), 1000), BusStatus::Ok); }
  void enable() {
    write({0xEE, 0x0B, 0xEE, 0x09, 0x40, 0x02, 0x02, 0x00, 0x65, 0x03, 0x81, 0x01, 0x00});
    read_frame(bus);
  }
};

TEST(ZforceModel, SendsBootCompleteFirst) {
  Fixture f;
  f.model.advance_to(0);
  ASSERT_TRUE(f.model.asserted());
  const Bytes b = read_frame(f.bus);
  EXPECT_EQ(b, (Bytes{0xEE, 0x0F, 0xF0, 0x0D, 0x40, 0x02, 0x00, 0x00, 0x63, 0x07, 0x80, 0x01, 0x00, 0x81, 0x02, 0x07,
                      0x80}));
  EXPECT_FALSE(f.model.asserted());
}

TEST(ZforceModel, AnswersEnableAsTheArduinoLibrarySendsIt) {
  ZforceModel::Options o;
  o.boot_complete = false;
  ZforceModel m(o);
  EmulatedI2cBus bus;
  bus.attach(0x50, m);
  const Bytes enable{0xEE, 0x0B, 0xEE, 0x09, 0x40, 0x02, 0x02, 0x00, 0x65, 0x03, 0x81, 0x01, 0x00};
  ASSERT_EQ(bus.write(0x50, enable.data(), enable.size(), 1000), BusStatus::Ok);
  EXPECT_TRUE(m.enabled());
  ASSERT_TRUE(m.asserted());
  EXPECT_EQ(read_frame(bus), (Bytes{0xEE, 0x0B, 0xEF, 0x09, 0x40, 0x02, 0x02, 0x00, 0x65, 0x03, 0x81, 0x01, 0x00}));
}

TEST(ZforceModel, AnswersTouchFormatWithItsDescriptor) {
  ZforceModel::Options o;
  o.boot_complete = false;
  ZforceModel m(o);
  EmulatedI2cBus bus;
  bus.attach(0x50, m);
  const Bytes req{0xEE, 0x08, 0xEE, 0x06, 0x40, 0x02, 0x02, 0x00, 0x66, 0x00};
  ASSERT_EQ(bus.write(0x50, req.data(), req.size(), 1000), BusStatus::Ok);
  // id, event, x1, x2, y1, y2 = bits 0-3, 5, 6: 0xF6; size-x 11, 12: 0x18; confidence 21: 0x04.
  EXPECT_EQ(read_frame(bus), (Bytes{0xEE, 0x0E, 0xEF, 0x0C, 0x40, 0x02, 0x02, 0x00, 0x66, 0x06, 0x41, 0x04, 0x01, 0xF6,
                                    0x18, 0x04}));
}

TEST(ZforceModel, RecordsResolutionFrequencyAndReportedTouches) {
  Fixture f;
  f.model.advance_to(0);
  read_frame(f.bus);  // boot complete
  f.write({0xEE, 0x10, 0xEE, 0x0E, 0x40, 0x02, 0x02, 0x00, 0x69, 0x08, 0x80, 0x02, 0x0C, 0x80, 0x81, 0x02, 0x07, 0x80});
  read_frame(f.bus);
  f.write({0xEE, 0x0F, 0xEE, 0x0D, 0x40, 0x02, 0x00, 0x00, 0x68, 0x07, 0x80, 0x02, 0x00, 0xC8, 0x82, 0x01, 0x32});
  read_frame(f.bus);
  f.write({0xEE, 0x0B, 0xEE, 0x09, 0x40, 0x02, 0x02, 0x00, 0x73, 0x03, 0x86, 0x01, 0x02});
  read_frame(f.bus);
  EXPECT_EQ(f.model.resolution_x(), 3200);
  EXPECT_EQ(f.model.resolution_y(), 1920);
  EXPECT_EQ(f.model.finger_frequency(), 200);
  EXPECT_EQ(f.model.idle_frequency(), 50);
  EXPECT_EQ(f.model.reported_touches(), 2);
  EXPECT_EQ(f.model.requests_rejected(), 0u) << f.model.last_rejection();
}

TEST(ZforceModel, RejectsARequestWhileDrIsHigh) {
  Fixture f;
  f.model.advance_to(0);
  ASSERT_TRUE(f.model.asserted());  // boot complete unread
  f.write({0xEE, 0x08, 0xEE, 0x06, 0x40, 0x02, 0x02, 0x00, 0x66, 0x00});
  EXPECT_EQ(f.model.requests_rejected(), 1u);
}

TEST(ZforceModel, TurnsATraceIntoDownMoveUpFrames) {
  Fixture f;
  f.model.advance_to(0);
  read_frame(f.bus);
  f.enable();
  f.model.load_trace({{1000, 100.0f, 240.0f, true}, {6000, 101.0f, 240.0f, true}, {11000, 0.0f, 0.0f, false},
                      {16000, 0.0f, 0.0f, false}});
  f.model.advance_to(999);
  EXPECT_FALSE(f.model.asserted());
  uint32_t t = 0, edges = 0;
  ASSERT_TRUE(f.model.take_edge(t, edges));  // boot complete and the enable answer
  EXPECT_EQ(edges, 2u);
  f.model.advance_to(1200);
  ASSERT_TRUE(f.model.asserted());
  ASSERT_TRUE(f.model.take_edge(t, edges));
  EXPECT_EQ(t, 1000u);
  EXPECT_EQ(edges, 1u);
  // x 100 px = 400 units (0x0190), y 240 px = 960 (0x03C0), size 48, confidence 100,
  // timestamp 1000 us * 32768 Hz = 32 ticks.
  EXPECT_EQ(read_frame(f.bus), (Bytes{0xEE, 0x16, 0xF0, 0x14, 0x40, 0x02, 0x02, 0x00, 0xA0, 0x0B, 0x42, 0x09, 0x00,
                                      0x00, 0x01, 0x90, 0x03, 0xC0, 0x00, 0x30, 0x64, 0x58, 0x01, 0x20}));
  f.model.advance_to(6000);
  Bytes move = read_frame(f.bus);
  EXPECT_EQ(move[13], 1);                       // move
  EXPECT_EQ((move[14] << 8) | move[15], 404);  // 101 px
  f.model.advance_to(11000);
  Bytes up = read_frame(f.bus);
  EXPECT_EQ(up[13], 2);                         // up, at the last position
  EXPECT_EQ((up[14] << 8) | up[15], 404);
  f.model.advance_to(20000);
  EXPECT_FALSE(f.model.asserted());  // nothing for the second no-finger point
}

TEST(ZforceModel, AnEdgeWaitsForThePreviousMessageToBeRead) {
  Fixture f;
  f.model.advance_to(0);
  read_frame(f.bus);
  f.enable();
  f.model.load_trace({{1000, 100.0f, 240.0f, true}, {2000, 101.0f, 240.0f, true}});
  f.model.advance_to(3000);  // both due; the host reads only now
  uint32_t t = 0, edges = 0;
  ASSERT_TRUE(f.model.take_edge(t, edges));
  EXPECT_EQ(t, 1000u);
  read_frame(f.bus);
  ASSERT_TRUE(f.model.take_edge(t, edges));
  EXPECT_EQ(t, 3000u);  // DR rose again when the first was read
}

TEST(ZforceModel, DropsTouchesUntilEnabled) {
  Fixture f;
  f.model.load_trace({{1000, 100.0f, 240.0f, true}});
  f.model.advance_to(0);
  read_frame(f.bus);
  f.model.advance_to(2000);
  EXPECT_FALSE(f.model.asserted());
  EXPECT_EQ(f.model.touch_frames_dropped_disabled(), 1u);
}

TEST(ZforceModel, SecondFingerRidesAlongAndLiftsAfterItsWindow) {
  Fixture f;
  f.model.advance_to(0);
  read_frame(f.bus);
  f.enable();
  ZforceModel::SecondFinger second;
  second.from_us = 2000;
  second.to_us = 2000;
  second.x = 400.0f;
  second.y = 100.0f;
  f.model.load_trace({{1000, 100.0f, 240.0f, true}, {2000, 101.0f, 240.0f, true}, {3000, 102.0f, 240.0f, true}},
                     &second);
  f.model.advance_to(1000);
  EXPECT_EQ(read_frame(f.bus)[9], 0x0B);  // one touch
  f.model.advance_to(2000);
  Bytes two = read_frame(f.bus);
  ASSERT_EQ(two[9], 0x16);  // two touches
  EXPECT_EQ(two[23], 1);    // second id
  EXPECT_EQ(two[24], 0);    // down
  EXPECT_EQ((two[25] << 8) | two[26], 1600);
  f.model.advance_to(3000);
  Bytes after = read_frame(f.bus);
  ASSERT_EQ(after[9], 0x16);
  EXPECT_EQ(after[24], 2);  // second finger up
}

TEST(ZforceModel, FaultsAreWhatTheyClaim) {
  Fixture f;
  f.model.advance_to(0);
  read_frame(f.bus);
  f.enable();
  f.model.inject(1000, ZforceModel::Fault::BadHeader);
  f.model.inject(2000, ZforceModel::Fault::Truncated);
  f.model.inject(3000, ZforceModel::Fault::LengthOverMax);
  f.model.advance_to(1000);
  Bytes bad = read_frame(f.bus);
  EXPECT_EQ(bad[0], 0x00);
  f.model.advance_to(2000);
  Bytes cut = read_frame(f.bus);
  EXPECT_EQ(cut[1], cut.size() - 2);
  EXPECT_GT(cut[3], cut.size() - 4);  // the BER length promises more than there is
  f.model.advance_to(3000);
  Bytes h(2);
  f.bus.read(0x50, h.data(), 2, 1000);
  EXPECT_EQ(h[1], 200);
}

}  // namespace
}  // namespace ff::emulated
