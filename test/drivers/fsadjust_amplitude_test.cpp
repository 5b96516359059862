// Amplitude through FSADJUST with increasing and decreasing calibrations,
// checked code by code on a gmock DAC.
#include "frictionfield/drivers/fsadjust_amplitude.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <limits>

namespace ff {
namespace {

using ::testing::InSequence;
using ::testing::Return;

class MockDac : public Dac12 {
 public:
  MOCK_METHOD(BusStatus, do_write, (uint16_t code), (override));
};

TEST(FsAdjustAmplitude, IncreasingCalibration) {
  MockDac dac;
  {
    InSequence order;
    EXPECT_CALL(dac, do_write(4095)).WillOnce(Return(BusStatus::Ok));
    EXPECT_CALL(dac, do_write(1024)).WillOnce(Return(BusStatus::Ok));  // 0.25 * 4095 = 1023.75
    EXPECT_CALL(dac, do_write(2048)).WillOnce(Return(BusStatus::Ok));  // 2047.5 rounds up
    EXPECT_CALL(dac, do_write(0)).Times(2).WillRepeatedly(Return(BusStatus::Ok));
  }
  FsAdjustAmplitude amp(dac, DacCalibration::linear());
  EXPECT_EQ(amp.set_amplitude(1.0f), BusStatus::Ok);
  EXPECT_EQ(amp.set_amplitude(0.25f), BusStatus::Ok);
  EXPECT_EQ(amp.set_amplitude(0.5f), BusStatus::Ok);
  EXPECT_EQ(amp.set_amplitude(std::numeric_limits<float>::quiet_NaN()), BusStatus::Ok);
  EXPECT_EQ(amp.silence(), BusStatus::Ok);
  EXPECT_EQ(amp.last_code(), 0);
}

TEST(FsAdjustAmplitude, DecreasingCalibrationAsInTheCircuitNote) {
  MockDac dac;
  {
    InSequence order;
    EXPECT_CALL(dac, do_write(0)).WillOnce(Return(BusStatus::Ok));     // full amplitude: no volts
    EXPECT_CALL(dac, do_write(3071)).WillOnce(Return(BusStatus::Ok));  // 4095 - 1023.75 = 3071.25
    EXPECT_CALL(dac, do_write(4095)).WillOnce(Return(BusStatus::Ok));  // silence: full volts
  }
  FsAdjustAmplitude amp(dac, DacCalibration::inverted());
  EXPECT_EQ(amp.set_amplitude(1.0f), BusStatus::Ok);
  EXPECT_EQ(amp.set_amplitude(0.25f), BusStatus::Ok);
  EXPECT_EQ(amp.silence(), BusStatus::Ok);
  EXPECT_FALSE(amp.calibration_repaired());
}

TEST(FsAdjustAmplitude, InvalidCalibrationFallsBackToLinear) {
  MockDac dac;
  EXPECT_CALL(dac, do_write(4095)).WillOnce(Return(BusStatus::Ok));
  DacCalibration bad;
  bad.count = 1;
  FsAdjustAmplitude amp(dac, bad);
  EXPECT_TRUE(amp.calibration_repaired());
  EXPECT_EQ(amp.set_amplitude(1.0f), BusStatus::Ok);
}

TEST(FsAdjustAmplitude, AnInvalidDecreasingCalibrationIsNotUsedAsItIs) {
  // Decreasing codes whose last amplitude is 0.5, not 1. Used as it is,
  // amplitude 1 would write code 0; repaired to linear: 4095, and 1024 for 0.25.
  MockDac dac;
  {
    InSequence order;
    EXPECT_CALL(dac, do_write(4095)).WillOnce(Return(BusStatus::Ok));
    EXPECT_CALL(dac, do_write(1024)).WillOnce(Return(BusStatus::Ok));
  }
  DacCalibration bad = DacCalibration::inverted();
  bad.amplitude[1] = 0.5f;
  FsAdjustAmplitude amp(dac, bad);
  EXPECT_TRUE(amp.calibration_repaired());
  EXPECT_EQ(amp.set_amplitude(1.0f), BusStatus::Ok);
  EXPECT_EQ(amp.set_amplitude(0.25f), BusStatus::Ok);
}

TEST(FsAdjustAmplitude, CountsDacFailuresAndKeepsTheLastGoodCode) {
  MockDac dac;
  EXPECT_CALL(dac, do_write(100)).WillOnce(Return(BusStatus::Ok));
  EXPECT_CALL(dac, do_write(200)).WillOnce(Return(BusStatus::BusError));
  FsAdjustAmplitude amp(dac, DacCalibration::linear());
  amp.write_code(100);
  EXPECT_EQ(amp.write_code(200), BusStatus::BusError);
  EXPECT_EQ(amp.write_code(5000), BusStatus::InvalidArgument);  // never reaches the DAC
  EXPECT_EQ(amp.last_code(), 100);
  EXPECT_EQ(amp.bus_errors(), 2u);
}

}  // namespace
}  // namespace ff
