// The bus interfaces' own rules: argument checks before the bus, wrap-safe
// time, the DR edge latch.
#include <gtest/gtest.h>

#include "frictionfield/bus/clock.hpp"
#include "frictionfield/bus/data_ready.hpp"
#include "frictionfield/emulated/replay_mocks.hpp"

namespace ff {
namespace {

using emulated::MockI2cInitiator;

TEST(Clock, DifferencesSurviveTheWrap) {
  EXPECT_EQ(elapsed_since(5u, 0xFFFFFFFBu), 10u);
  EXPECT_TRUE(deadline_reached(5u, 0xFFFFFFF0u));   // deadline just before the wrap, now just after
  EXPECT_FALSE(deadline_reached(0xFFFFFFF0u, 5u));  // deadline just after the wrap, now just before
  EXPECT_TRUE(deadline_reached(100u, 100u));
  EXPECT_FALSE(deadline_reached(99u, 100u));
}

TEST(EdgeLatch, HandsOutTheNewestEdgeAndHowManyThereWere) {
  EdgeLatch latch;
  uint32_t t = 0, n = 0;
  EXPECT_FALSE(latch.take(t, n));
  latch.on_edge(100);
  latch.on_edge(200);
  ASSERT_TRUE(latch.take(t, n));
  EXPECT_EQ(t, 200u);
  EXPECT_EQ(n, 2u);
  EXPECT_FALSE(latch.take(t, n));
  latch.on_edge(0xFFFFFFFFu);
  ASSERT_TRUE(latch.take(t, n));
  EXPECT_EQ(t, 0xFFFFFFFFu);
  EXPECT_EQ(n, 1u);
}

TEST(I2cInitiator, RejectsBadArgumentsWithoutTouchingTheBus) {
  MockI2cInitiator bus({});
  uint8_t b[2] = {};
  EXPECT_EQ(bus.read(0x80, b, 1, 100), BusStatus::InvalidArgument);      // 8-bit address
  EXPECT_EQ(bus.read(0x50, nullptr, 1, 100), BusStatus::InvalidArgument);
  EXPECT_EQ(bus.write(0x50, nullptr, 2, 100), BusStatus::InvalidArgument);
  EXPECT_EQ(bus.write_read(0x50, b, 0, b, 0, 100), BusStatus::InvalidArgument);  // nothing to do
  std::string why;
  EXPECT_TRUE(bus.finished(&why)) << why;
}

TEST(I2cDevice, BindsTheAddress) {
  MockI2cInitiator bus({emulated::expect_write_read(0x50, {0x01}, {0xAB, 0xCD})});
  I2cDevice dev(bus, 0x50);
  const uint8_t reg = 0x01;
  uint8_t rx[2] = {};
  EXPECT_EQ(dev.write_read(&reg, 1, rx, 2, 100), BusStatus::Ok);
  EXPECT_EQ(rx[1], 0xCD);
  std::string why;
  EXPECT_TRUE(bus.finished(&why)) << why;
}

TEST(BusStatus, HasNames) {
  EXPECT_STREQ(to_string(BusStatus::Timeout), "timeout");
  EXPECT_STREQ(to_string(BusStatus::Nack), "nack");
}

}  // namespace
}  // namespace ff
