// Load cells with hand-derived numbers: 1 count above the zero is
// 1.0712 * 9.81 = 10.508472 mN; averages over the last 5 readings.
#include "frictionfield/drivers/load_cells.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "frictionfield/emulated/scripted_adc.hpp"

namespace ff {
namespace {

using emulated::ScriptedAdc;

constexpr double kMnPerCount = 10.508472;
constexpr double kTol = 1e-3;

struct Rig {
  ScriptedAdc adc{4, 13};
  LoadCellMonitor cells{adc};
  uint32_t t = 0;
  Rig() {
    adc.set(0, 100);
    adc.set(1, 200);
    adc.set(2, 300);
    adc.set(3, 400);  // 1000 counts at rest
    cells.start(0);
  }
  LoadReading next(bool finger = false) {
    t += 30000;
    LoadReading r;
    EXPECT_TRUE(cells.step(t, finger, r)) << t;
    return r;
  }
  void tare() {
    for (int i = 0; i < 4; ++i) EXPECT_FALSE(next().tared);
    EXPECT_TRUE(next().tared);
  }
};

TEST(LoadCells, TaresOnTheFirstFiveReadingsThenAverages) {
  Rig rig;
  rig.tare();
  EXPECT_FLOAT_EQ(rig.cells.zero_counts(), 1000.0f);
  rig.adc.script(0, {110, 120, 150});  // +10, +20, +50 counts, then 150 stays
  LoadReading r = rig.next(true);
  EXPECT_NEAR(static_cast<double>(r.latest_mN), 10 * kMnPerCount, kTol);
  EXPECT_NEAR(static_cast<double>(r.force_mN), 10 * kMnPerCount, kTol);  // 105.08472
  r = rig.next(true);
  EXPECT_NEAR(static_cast<double>(r.latest_mN), 20 * kMnPerCount, kTol);
  EXPECT_NEAR(static_cast<double>(r.force_mN), 15 * kMnPerCount, kTol);  // 157.62708
  r = rig.next(true);
  EXPECT_NEAR(static_cast<double>(r.force_mN), 80.0 / 3.0 * kMnPerCount, kTol);  // 280.2259
  EXPECT_FALSE(r.over_force);
  r = rig.next(true);  // [10 20 50 50]
  EXPECT_NEAR(static_cast<double>(r.force_mN), 32.5 * kMnPerCount, kTol);
  r = rig.next(true);  // [10 20 50 50 50]
  EXPECT_NEAR(static_cast<double>(r.force_mN), 36 * kMnPerCount, kTol);
  r = rig.next(true);  // [20 50 50 50 50]
  EXPECT_NEAR(static_cast<double>(r.force_mN), 44 * kMnPerCount, kTol);  // 462.37
  EXPECT_FALSE(r.over_force);
  r = rig.next(true);  // [50 x 5]: 525.42 mN
  EXPECT_NEAR(static_cast<double>(r.force_mN), 50 * kMnPerCount, kTol);
  EXPECT_TRUE(r.over_force);
}

TEST(LoadCells, AConfigOfZeroesAndNaNsIsRepairedToTheDefaults) {
  ScriptedAdc adc{4, 13};
  for (uint8_t ch = 0; ch < 4; ++ch) adc.set(ch, 250);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  LoadCellConfig bad;
  bad.period_us = 0;
  bad.millinewton_per_count = nan;
  bad.over_force_mN = nan;
  bad.rezero_limit_mN = -1.0f;
  LoadCellMonitor cells(adc, bad);
  cells.start(0);
  LoadReading r;
  EXPECT_FALSE(cells.step(29999, false, r));  // every 30 ms
  uint32_t t = 0;
  for (int i = 0; i < 5; ++i) ASSERT_TRUE(cells.step(t += 30000, false, r));
  ASSERT_TRUE(r.tared);
  adc.set(0, 255);  // +5 counts of drift: re-zeroed (52.54 mN, under the 100 mN limit)
  for (int i = 0; i < 5; ++i) ASSERT_TRUE(cells.step(t += 30000, false, r));
  EXPECT_TRUE(r.rezeroed);
  adc.set(0, 305);  // +50 counts pressed: 525.42 mN, over 0.5 N
  for (int i = 0; i < 5; ++i) ASSERT_TRUE(cells.step(t += 30000, true, r));
  EXPECT_NEAR(static_cast<double>(r.force_mN), 50 * kMnPerCount, kTol);
  EXPECT_TRUE(r.over_force);
}

TEST(LoadCells, OverForceIsAboveHalfANewton) {
  for (uint16_t extra : {47, 48}) {  // 493.90 mN, 504.41 mN
    Rig rig;
    rig.tare();
    rig.adc.set(0, static_cast<uint16_t>(100 + extra));
    LoadReading r;
    for (int i = 0; i < 5; ++i) r = rig.next(true);
    EXPECT_NEAR(static_cast<double>(r.force_mN), extra * kMnPerCount, kTol);
    EXPECT_EQ(r.over_force, extra == 48);
  }
}

TEST(LoadCells, RezeroesSmallDriftOnceFiveFingerFreeReadingsAgree) {
  Rig rig;
  rig.tare();
  rig.adc.set(0, 105);  // +5 counts of drift: 52.54 mN
  for (int i = 0; i < 4; ++i) {
    const LoadReading r = rig.next();
    EXPECT_NEAR(static_cast<double>(r.force_mN), 5 * kMnPerCount, kTol);
    EXPECT_FALSE(r.rezeroed);
  }
  const LoadReading r = rig.next();
  EXPECT_TRUE(r.rezeroed);
  EXPECT_EQ(r.force_mN, 0.0f);
  EXPECT_FLOAT_EQ(rig.cells.zero_counts(), 1005.0f);
  rig.adc.set(0, 115);  // a press of 10 counts is still 105 mN
  EXPECT_NEAR(static_cast<double>(rig.next(true).latest_mN), 10 * kMnPerCount, kTol);
}

TEST(LoadCells, LargeOffsetsAreNotZeroedAway) {
  Rig rig;
  rig.tare();
  rig.adc.set(0, 120);  // 210 mN with no finger: something rests on the plate
  LoadReading r;
  for (int i = 0; i < 6; ++i) r = rig.next();
  EXPECT_FALSE(r.rezeroed);
  EXPECT_NEAR(static_cast<double>(r.force_mN), 20 * kMnPerCount, kTol);
  EXPECT_EQ(rig.cells.rezeros(), 0u);
  EXPECT_EQ(rig.cells.rezeros_refused(), 2u);
}

// A load put down over a second with no finger reported (a hand, an object)
// is no drift: +3 counts a reading for 32 readings (0.96 s) to +96 counts,
// 1008.81 mN. No window of 5 agrees while it rises (a spread of 12 counts,
// 126 mN, over the 100 mN limit), and once it rests it is 96 counts above the
// tare: the zero stays at the tare.
TEST(LoadCells, ALoadPutDownOverASecondIsNotZeroedAway) {
  Rig rig;
  rig.tare();
  LoadReading r;
  for (int k = 1; k <= 32; ++k) {
    rig.adc.set(0, static_cast<uint16_t>(100 + 3 * k));
    r = rig.next();
  }
  for (int k = 0; k < 10; ++k) r = rig.next();
  EXPECT_FLOAT_EQ(rig.cells.zero_counts(), 1000.0f);
  EXPECT_NEAR(static_cast<double>(r.force_mN), 96 * kMnPerCount, kTol);
  EXPECT_TRUE(r.over_force);
  EXPECT_EQ(rig.cells.rezeros(), 0u);
  EXPECT_GT(rig.cells.rezeros_refused(), 0u);
}

// Slower, +1 count a reading (a spread of 4 counts, 42 mN: the readings
// agree): the zero follows only while the window's mean is within 100 mN
// (9.516 counts) of the tare. The mean at reading k >= 5 is 1000 + k - 2, so
// the last zero taken is 1009 (k = 11); at rest at +96 the force is
// (1096 - 1009) counts = 914.24 mN.
TEST(LoadCells, ASlowlyRisingLoadMovesTheZeroNoFurtherThanTheLimitFromTheTare) {
  Rig rig;
  rig.tare();
  LoadReading r;
  for (int k = 1; k <= 96; ++k) {
    rig.adc.set(0, static_cast<uint16_t>(100 + k));
    r = rig.next();
  }
  for (int k = 0; k < 10; ++k) r = rig.next();
  EXPECT_FLOAT_EQ(rig.cells.zero_counts(), 1009.0f);
  EXPECT_EQ(rig.cells.rezeros(), 7u);  // k = 5 .. 11
  EXPECT_NEAR(static_cast<double>(r.force_mN), 87 * kMnPerCount, kTol);
  EXPECT_TRUE(r.over_force);
}

TEST(LoadCells, NoRezeroWhileAFingerReadingIsInTheWindow) {
  Rig rig;
  rig.tare();
  rig.adc.set(0, 105);
  for (int i = 6; i <= 12; ++i) EXPECT_FALSE(rig.next(i == 8).rezeroed) << i;  // 8 is in every window up to 12
  EXPECT_TRUE(rig.next().rezeroed);                                           // 9..13 are all free
}

TEST(LoadCells, AFingerDuringTheTareStartsItAgain) {
  Rig rig;
  EXPECT_FALSE(rig.next().tared);
  EXPECT_FALSE(rig.next().tared);
  EXPECT_FALSE(rig.next(true).tared);
  for (int i = 0; i < 4; ++i) EXPECT_FALSE(rig.next().tared);
  EXPECT_TRUE(rig.next().tared);  // the fifth finger-free reading after the touch
}

TEST(LoadCells, StartingAgainTaresAfresh) {
  Rig rig;
  rig.tare();
  rig.adc.set(0, 105);  // 5 counts more, then started again: the new zero is 1005
  rig.next(true);
  rig.cells.start(rig.t);
  EXPECT_FALSE(rig.cells.tared());
  EXPECT_EQ(rig.cells.zero_counts(), 0.0f);
  rig.tare();
  EXPECT_FLOAT_EQ(rig.cells.zero_counts(), 1005.0f);  // of the five readings since, not the window before
  EXPECT_NEAR(static_cast<double>(rig.next(true).force_mN), 0.0, kTol);
}

TEST(LoadCells, AReadingReusedByTheCallerSaysOnlyWhatHappenedThisTime) {
  Rig rig;
  rig.tare();
  rig.adc.set(0, 105);  // drift, re-zeroed at the fifth finger-free reading
  LoadReading r;
  uint32_t t = rig.t;
  for (int i = 0; i < 5; ++i) ASSERT_TRUE(rig.cells.step(t += 30000, false, r));
  ASSERT_TRUE(r.rezeroed);
  ASSERT_TRUE(rig.cells.step(t += 30000, true, r));
  EXPECT_FALSE(r.rezeroed);
  EXPECT_TRUE(r.tared);
  EXPECT_EQ(r.t_us, t);
}

TEST(LoadCells, AFailedConversionSkipsOneReading) {
  Rig rig;
  LoadReading r;
  EXPECT_TRUE(rig.cells.step(30000, false, r));
  rig.adc.fail_next(1);  // the second reading's first channel
  EXPECT_FALSE(rig.cells.step(60000, false, r));
  EXPECT_EQ(rig.cells.read_errors(), 1u);
  rig.t = 60000;
  for (int i = 0; i < 3; ++i) EXPECT_FALSE(rig.next().tared);
  EXPECT_TRUE(rig.next().tared);  // 5 good readings at 30, 90, 120, 150, 180 ms
  EXPECT_EQ(rig.t, 180000u);
}

TEST(LoadCells, KeepsTheCadenceAndSkipsWhenLate) {
  ScriptedAdc adc;
  LoadCellMonitor cells(adc);
  LoadReading r;
  EXPECT_FALSE(cells.step(0, false, r));  // not started
  const uint32_t t0 = 0xFFFFFFFFu - 10000u;  // across the clock wrap
  cells.start(t0);
  EXPECT_FALSE(cells.step(t0 + 29999, false, r));
  EXPECT_TRUE(cells.step(t0 + 30000, false, r));
  EXPECT_FALSE(cells.step(t0 + 30001, false, r));
  EXPECT_TRUE(cells.step(t0 + 60500, false, r));  // late by 0.5 ms: the next is still due at 90 ms
  EXPECT_TRUE(cells.step(t0 + 90000, false, r));
  EXPECT_TRUE(cells.step(t0 + 400000, false, r));  // 10 periods late: one reading, no burst
  EXPECT_EQ(cells.missed_periods(), 1u);
  EXPECT_FALSE(cells.step(t0 + 420000, false, r));
  EXPECT_TRUE(cells.step(t0 + 430000, false, r));
}

class MockAdc : public Adc {
 public:
  MOCK_METHOD(uint8_t, channel_count, (), (const, override));
  MOCK_METHOD(uint8_t, resolution_bits, (), (const, override));
  MOCK_METHOD(BusStatus, do_read, (uint8_t channel, uint16_t& value), (override));
};

TEST(LoadCells, ReadsTheConfiguredChannels) {
  using ::testing::_;
  using ::testing::DoAll;
  using ::testing::InSequence;
  using ::testing::Return;
  using ::testing::SetArgReferee;
  MockAdc adc;
  EXPECT_CALL(adc, channel_count()).WillRepeatedly(Return(8));
  {
    InSequence order;
    for (uint8_t ch : {7, 5, 3, 1}) {
      EXPECT_CALL(adc, do_read(ch, _)).WillOnce(DoAll(SetArgReferee<1>(ch * 10), Return(BusStatus::Ok)));
    }
  }
  LoadCellConfig config;
  const uint8_t channels[4] = {7, 5, 3, 1};
  for (int i = 0; i < 4; ++i) config.channels[i] = channels[i];
  LoadCellMonitor cells(adc, config);
  cells.start(0);
  LoadReading r;
  EXPECT_TRUE(cells.step(30000, false, r));
}

}  // namespace
}  // namespace ff
