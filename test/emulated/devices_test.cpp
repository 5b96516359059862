// The small emulated devices and the replay mocks.
#include <gtest/gtest.h>

#include "frictionfield/emulated/i2c_bus.hpp"
#include "frictionfield/emulated/manual_clock.hpp"
#include "frictionfield/emulated/recording_dac.hpp"
#include "frictionfield/emulated/replay_mocks.hpp"
#include "frictionfield/emulated/scripted_adc.hpp"

namespace ff::emulated {
namespace {

TEST(ScriptedAdc, PlaysEachChannelsScriptThenRepeatsTheLast) {
  ScriptedAdc adc(4, 12);
  adc.script(1, {10, 20});
  adc.set(2, 5000);  // above 12 bits: clipped to 4095
  uint16_t v = 0;
  EXPECT_EQ(adc.read(1, v), BusStatus::Ok);
  EXPECT_EQ(v, 10);
  adc.read(1, v);
  EXPECT_EQ(v, 20);
  adc.read(1, v);
  EXPECT_EQ(v, 20);
  adc.read(2, v);
  EXPECT_EQ(v, 4095);
  EXPECT_EQ(adc.read(4, v), BusStatus::InvalidArgument);  // no such channel: never reaches the device
  EXPECT_EQ(adc.reads(), 4u);
}

TEST(ScriptedAdc, FailsTheNextReads) {
  ScriptedAdc adc;
  uint16_t v = 0;
  EXPECT_EQ(adc.read(0, v), BusStatus::Ok);
  adc.fail_next(2, BusStatus::Timeout);
  EXPECT_EQ(adc.read(0, v), BusStatus::Timeout);
  EXPECT_EQ(adc.read(1, v), BusStatus::Timeout);
  EXPECT_EQ(adc.read(0, v), BusStatus::Ok);
}

TEST(RecordingDac, RecordsCodesWithTimesAndRejectsAbove12Bits) {
  ManualClock clock(100);
  RecordingDac dac(&clock);
  EXPECT_EQ(dac.write(7), BusStatus::Ok);
  clock.advance(500);
  EXPECT_EQ(dac.write(4095), BusStatus::Ok);
  EXPECT_EQ(dac.write(4096), BusStatus::InvalidArgument);
  ASSERT_EQ(dac.writes().size(), 2u);
  EXPECT_EQ(dac.writes()[1].t_us, 600u);
  EXPECT_EQ(dac.codes(), (std::vector<uint16_t>{7, 4095}));
  dac.fail_next(1);
  EXPECT_EQ(dac.write(1), BusStatus::BusError);
  EXPECT_EQ(dac.last(), 4095);
}

TEST(EmulatedI2cBus, NacksAnAbsentAddressAndInjectsFailures) {
  EmulatedI2cBus bus;
  uint8_t b = 0;
  EXPECT_EQ(bus.read(0x50, &b, 1, 100), BusStatus::Nack);
  EXPECT_EQ(bus.read(0x80, &b, 1, 100), BusStatus::InvalidArgument);  // not a 7-bit address
  bus.fail_next(1, BusStatus::Timeout);
  EXPECT_EQ(bus.read(0x50, &b, 1, 100), BusStatus::Timeout);
}

TEST(MockI2cInitiator, ReplaysAndFlagsTheFirstMismatch) {
  MockI2cInitiator ok({expect_write(0x50, {1, 2}), expect_read(0x50, {9, 8})});
  const uint8_t tx[] = {1, 2};
  uint8_t rx[2] = {};
  EXPECT_EQ(ok.write(0x50, tx, 2, 100), BusStatus::Ok);
  EXPECT_EQ(ok.read(0x50, rx, 2, 100), BusStatus::Ok);
  EXPECT_EQ(rx[0], 9);
  std::string why;
  EXPECT_TRUE(ok.finished(&why)) << why;

  MockI2cInitiator bad({expect_write(0x50, {1, 3}), expect_read(0x50, {0})});
  EXPECT_EQ(bad.write(0x50, tx, 2, 100), BusStatus::BusError);
  EXPECT_FALSE(bad.finished(&why));
  EXPECT_NE(why.find("expected"), std::string::npos);
}

TEST(MockSpiBus16, ChecksModeChipSelectAndWords) {
  MockSpiBus16 spi({{SpiMode::Mode2, 1, {0x2100, 0x2000}, BusStatus::Ok}});
  const uint16_t w[] = {0x2100, 0x2000};
  EXPECT_EQ(spi.write({SpiMode::Mode0, 1000}, 1, w, 2), BusStatus::BusError);
  std::string why;
  EXPECT_FALSE(spi.finished(&why));
  MockSpiBus16 good({{SpiMode::Mode2, 1, {0x2100, 0x2000}, BusStatus::Ok}});
  EXPECT_EQ(good.write({SpiMode::Mode2, 1000}, 1, w, 2), BusStatus::Ok);
  EXPECT_TRUE(good.finished(&why)) << why;
}

}  // namespace
}  // namespace ff::emulated
