#include "frictionfield/core/amplitude_map.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace ff {
namespace {

AmplitudeMap with_strength(float s) {
  AmplitudeMap m;
  AmplitudeSettings a;
  a.strength = s;
  m.configure(a);
  return m;
}

TEST(AmplitudeMap, StrengthEndpointsGiveTheExperimentsDriveRanges) {
  // Drive 0..100 V maps linearly to 0..4095: [0, 100], [17, 83], [33.5, 66.5] V.
  struct Case { float s; uint16_t lo, hi; };
  for (const Case c : {Case{1.0f, 0, 4095}, Case{0.66f, 696, 3399}, Case{0.33f, 1372, 2723}}) {
    const AmplitudeMap m = with_strength(c.s);
    EXPECT_EQ(m.dac_code(m.scale(0.0f)), c.lo) << c.s;
    EXPECT_EQ(m.dac_code(m.scale(1.0f)), c.hi) << c.s;
    EXPECT_EQ(m.dac_code(m.scale(0.5f)), 2048) << c.s;  // round(0.5 * 4095) = 2048
  }
  EXPECT_NEAR(static_cast<double>(with_strength(0.66f).scale(0.0f)) * 100.0, 17.0, 1e-4);
  EXPECT_NEAR(static_cast<double>(with_strength(0.33f).scale(1.0f)) * 100.0, 66.5, 1e-4);
}

TEST(AmplitudeMap, BadStrengthIsRepairedAndReported) {
  AmplitudeMap m;
  AmplitudeSettings a;
  for (float s : {NAN, -1.0f, 0.0f, -INFINITY}) {
    a.strength = s;
    EXPECT_FALSE(m.configure(a)) << s;
    EXPECT_FLOAT_EQ(m.scale(1.0f), 0.5f) << s;  // no modulation: the plate sits at 0.5
  }
  for (float s : {3.0f, INFINITY}) {
    a.strength = s;
    EXPECT_FALSE(m.configure(a));
    EXPECT_FLOAT_EQ(m.scale(1.0f), 1.0f);  // clamped to 1
  }
}

TEST(AmplitudeMap, OutputStaysInsideTheStrengthRangeForAnyInput) {
  const AmplitudeMap m = with_strength(0.33f);
  for (float raw : {NAN, INFINITY, -INFINITY, -5.0f, 0.0f, 0.3f, 1.0f, 7.0f, 1e-40f}) {
    const float a = m.scale(raw);
    EXPECT_TRUE(std::isfinite(a));
    EXPECT_GE(a, 0.335f - 1e-6f);
    EXPECT_LE(a, 0.665f + 1e-6f);
  }
  EXPECT_FLOAT_EQ(m.scale(NAN), 0.5f);
}

TEST(DacCalibration, InvertedMapsFullVibrationToCodeZero) {
  const DacCalibration inv = DacCalibration::inverted();
  EXPECT_TRUE(inv.valid());
  EXPECT_EQ(inv.code_for(1.0f), 0);
  EXPECT_EQ(inv.code_for(0.0f), 4095);
  EXPECT_EQ(inv.code_for(0.5f), 2048);  // 2047.5 rounds up
  EXPECT_EQ(inv.code_for(NAN), 4095);   // NaN is treated as amplitude 0: plate rests
}

TEST(DacCalibration, PiecewiseLinearAndValidated) {
  const float a[] = {0.0f, 0.5f, 1.0f};
  const float c[] = {100.0f, 1000.0f, 4000.0f};
  DacCalibration cal;
  ASSERT_TRUE(DacCalibration::from_points(a, c, 3, cal));
  EXPECT_EQ(cal.code_for(0.25f), 550);
  EXPECT_EQ(cal.code_for(0.75f), 2500);
  const float bad_codes[] = {100.0f, 5000.0f, 4000.0f};
  EXPECT_FALSE(DacCalibration::from_points(a, bad_codes, 3, cal));
  EXPECT_EQ(cal.code_for(1.0f), 4095);  // fell back to linear
  const float non_monotonic[] = {100.0f, 3000.0f, 2000.0f};
  EXPECT_FALSE(DacCalibration::from_points(a, non_monotonic, 3, cal));
  const float no_end[] = {0.0f, 0.5f, 0.9f};
  EXPECT_FALSE(DacCalibration::from_points(no_end, c, 3, cal));
}

TEST(DacCalibration, CodesOutsideTheDacAreRefusedEvenInOrder) {
  const float a[] = {0.0f, 0.5f, 1.0f};
  const float above[] = {100.0f, 1000.0f, 4096.0f};  // the DAC's codes are 0..4095
  const float below[] = {-1.0f, 1000.0f, 4000.0f};
  const float inf[] = {100.0f, 1000.0f, INFINITY};
  const float nan[] = {NAN, 1000.0f, 4000.0f};
  const float nan_decreasing[] = {4000.0f, 1000.0f, NAN};
  for (const float* codes : {above, below, inf, nan, nan_decreasing}) {
    DacCalibration cal;
    EXPECT_FALSE(DacCalibration::from_points(a, codes, 3, cal)) << codes[0] << " " << codes[2];
  }
  const float edges[] = {0.0f, 1000.0f, 4095.0f};
  DacCalibration cal;
  EXPECT_TRUE(DacCalibration::from_points(a, edges, 3, cal));
}

TEST(DacCalibration, AmplitudesMustRiseStrictly) {
  const float c[] = {0.0f, 1000.0f, 2000.0f, 4095.0f};
  const float back[] = {0.0f, 0.6f, 0.4f, 1.0f};
  const float flat[] = {0.0f, 0.5f, 0.5f, 1.0f};  // a step: code_for would divide by zero
  const float nan[] = {0.0f, NAN, 0.5f, 1.0f};
  const float inf[] = {0.0f, INFINITY, 0.5f, 1.0f};
  for (const float* a : {back, flat, nan, inf}) {
    DacCalibration cal;
    EXPECT_FALSE(DacCalibration::from_points(a, c, 4, cal)) << a[1] << " " << a[2];
  }
  const float rising[] = {0.0f, 0.4f, 0.6f, 1.0f};
  DacCalibration cal;
  EXPECT_TRUE(DacCalibration::from_points(rising, c, 4, cal));
}

// valid() reads the first and the count-th point: a count outside 2..16 is
// refused before anything is read (the sanitizer build checks the bounds).
TEST(DacCalibration, ACountOutsideTheTableIsInvalid) {
  for (const int count : {0, 1, kMaxCalibrationPoints + 1, 255}) {
    DacCalibration cal;
    cal.count = static_cast<uint8_t>(count);
    EXPECT_FALSE(cal.valid()) << count;
  }
  DacCalibration full;
  full.count = kMaxCalibrationPoints;
  for (int i = 0; i < kMaxCalibrationPoints; ++i) {
    full.amplitude[i] = static_cast<float>(i) / (kMaxCalibrationPoints - 1);
    full.code[i] = 273.0f * static_cast<float>(i);  // 0 .. 4095
  }
  EXPECT_TRUE(full.valid());
}

TEST(AmplitudeMap, SCurveIsMonotonicAndKeepsEndpointsAndCentre) {
  AmplitudeMap m;
  AmplitudeSettings a;
  a.s_curve = 1.0f;
  ASSERT_TRUE(m.configure(a));
  EXPECT_FLOAT_EQ(m.scale(0.0f), 0.0f);
  EXPECT_FLOAT_EQ(m.scale(0.5f), 0.5f);
  EXPECT_FLOAT_EQ(m.scale(1.0f), 1.0f);
  float prev = -1.0f;
  for (int i = 0; i <= 100; ++i) {
    const float v = m.scale(static_cast<float>(i) / 100.0f);
    EXPECT_GE(v, prev);
    prev = v;
  }
}

TEST(AmplitudeMap, SCurveValuesByHand) {
  // S5(1/4) = 6/4^5 - 15/4^4 + 10/4^3 = 0.005859375 - 0.05859375 + 0.15625
  //         = 0.103515625 (exact in float). S5(3/4) = 1 - S5(1/4).
  AmplitudeMap m;
  AmplitudeSettings a;
  a.s_curve = 1.0f;
  ASSERT_TRUE(m.configure(a));
  EXPECT_FLOAT_EQ(m.scale(0.25f), 0.103515625f);
  EXPECT_FLOAT_EQ(m.scale(0.75f), 0.896484375f);
  a.s_curve = 0.5f;  // halfway: 0.25 + 0.5 (0.103515625 - 0.25)
  ASSERT_TRUE(m.configure(a));
  EXPECT_FLOAT_EQ(m.scale(0.25f), 0.1767578125f);
  a.s_curve = 1.0f;
  a.strength = 0.5f;  // then strength: 0.5 + 0.5 (0.103515625 - 0.5)
  ASSERT_TRUE(m.configure(a));
  EXPECT_FLOAT_EQ(m.scale(0.25f), 0.3017578125f);
  a.s_curve = 0.0f;  // off: the identity before strength
  a.strength = 1.0f;
  ASSERT_TRUE(m.configure(a));
  EXPECT_FLOAT_EQ(m.scale(0.25f), 0.25f);
}

TEST(AmplitudeMap, ABadSCurveIsRepairedAndReported) {
  AmplitudeMap m;
  AmplitudeSettings a;
  a.s_curve = 2.0f;  // clamped to the full curve: S5(1/4) = 0.103515625, as by hand above
  EXPECT_FALSE(m.configure(a));
  EXPECT_EQ(m.settings().s_curve, 1.0f);
  EXPECT_FLOAT_EQ(m.scale(0.25f), 0.103515625f);
  for (float c : {-0.5f, NAN, -INFINITY}) {  // no curve
    a.s_curve = c;
    EXPECT_FALSE(m.configure(a)) << c;
    EXPECT_EQ(m.settings().s_curve, 0.0f) << c;
    EXPECT_FLOAT_EQ(m.scale(0.25f), 0.25f) << c;
  }
}

TEST(AmplitudeMap, IdleCodeFollowsTheCalibration) {
  AmplitudeMap m;
  AmplitudeSettings a;
  a.calibration = DacCalibration::inverted();
  ASSERT_TRUE(m.configure(a));
  EXPECT_EQ(m.idle_code(), 4095);  // idle amplitude 0 on an inverted board
  a.idle_amplitude = NAN;
  EXPECT_FALSE(m.configure(a));
  EXPECT_FLOAT_EQ(m.idle_amplitude(), 0.0f);
}

}  // namespace
}  // namespace ff
