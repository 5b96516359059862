// sin, cos and atan of the tick path against libm in double (an independent
// implementation) and closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "frictionfield/core/tick_math.hpp"

namespace ff {
namespace {

constexpr double kUlpOfOne = 1.1920928955078125e-7;  // 2^-23

TEST(TickMath, SinCosReducedWithinTwoUlpOnAQuarterTurn) {
  double worst = 0.0;
  for (int i = -20000; i <= 20000; ++i) {
    const float r = static_cast<float>(i) * (0.78539816f / 20000.0f);
    const SinCos sc = sincos_reduced(r);
    const double rd = r;
    worst = std::fmax(worst, std::fabs(static_cast<double>(sc.sin) - std::sin(rd)));
    worst = std::fmax(worst, std::fabs(static_cast<double>(sc.cos) - std::cos(rd)));
  }
  EXPECT_LE(worst, 2.0 * kUlpOfOne);
  // Closed forms: sin 0 = 0 exactly, cos 0 = 1 exactly, sin(pi/6) = 1/2.
  EXPECT_EQ(sincos_reduced(0.0f).sin, 0.0f);
  EXPECT_EQ(sincos_reduced(0.0f).cos, 1.0f);
  EXPECT_NEAR(static_cast<double>(sincos_reduced(0.52359878f).sin), 0.5, 2 * kUlpOfOne);
}

TEST(TickMath, SinCosTurnsMatchesTheDoubleFormulaOnEveryQuadrant) {
  for (int i = -4000; i <= 4000; ++i) {
    const float turns = static_cast<float>(i) * (3.0f / 4000.0f) + 0.0001234f;  // +-3 turns, off the grid
    const SinCos sc = sincos_turns(turns);
    const double phase = 2.0 * M_PI * static_cast<double>(turns);
    // The reduction subtracts whole and quarter turns exactly; what is left is
    // the rounding of 2 pi r (|r| <= 1/8) and the kernels.
    EXPECT_NEAR(static_cast<double>(sc.sin), std::sin(phase), 4 * kUlpOfOne) << turns;
    EXPECT_NEAR(static_cast<double>(sc.cos), std::cos(phase), 4 * kUlpOfOne) << turns;
  }
  // Quarter turns land exactly on the axes.
  EXPECT_EQ(sincos_turns(0.25f).sin, 1.0f);
  EXPECT_EQ(sincos_turns(0.25f).cos, -0.0f);
  EXPECT_EQ(sincos_turns(-0.5f).cos, -1.0f);
  EXPECT_EQ(sincos_turns(2.0f).cos, 1.0f);
}

TEST(TickMath, SinCosTurnsOfANonFiniteTurnIsNaNNotUndefined) {
  // A sine valley or texture whose wavelength is so short that x / wavelength
  // overflows (a fuzzed condition: 3.85e-37 px): +-inf and NaN turns. Under
  // UBSan (the asan preset) the old float-to-int quadrant aborted here.
  for (float turns : {std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
                      std::numeric_limits<float>::quiet_NaN()}) {
    const SinCos sc = sincos_turns(turns);
    EXPECT_TRUE(std::isnan(sc.sin)) << turns;
    EXPECT_TRUE(std::isnan(sc.cos)) << turns;
  }
  // Finite but beyond 2^23 turns every float is a whole turn: sin 0, cos 1.
  EXPECT_EQ(sincos_turns(1e30f).sin, 0.0f);
  EXPECT_EQ(sincos_turns(-3e38f).cos, 1.0f);
}

TEST(TickMath, ArctanWithinTwoUlpEverywhere) {
  double worst_relative = 0.0;
  for (int i = -30000; i <= 30000; ++i) {
    // x = sinh-like spread from 1e-6 to 1e4, both signs, both branches of every reduction.
    const double u = static_cast<double>(i) / 3000.0;
    const float x = static_cast<float>(std::copysign(1e-6 * std::pow(10.0, std::fabs(u) * 1.0), u));
    const double exact = std::atan(static_cast<double>(x));
    worst_relative = std::fmax(worst_relative, std::fabs(static_cast<double>(arctan(x)) - exact) / std::fabs(exact));
  }
  EXPECT_LE(worst_relative, 2.0 * kUlpOfOne);
  // Closed forms: atan 1 = pi/4, atan sqrt 3 = pi/3, atan(1/sqrt 3) = pi/6, atan tan(pi/12) = pi/12.
  EXPECT_NEAR(static_cast<double>(arctan(1.0f)), M_PI / 4, 2 * kUlpOfOne);
  EXPECT_NEAR(static_cast<double>(arctan(1.7320508f)), M_PI / 3, 2 * kUlpOfOne);
  EXPECT_NEAR(static_cast<double>(arctan(0.57735027f)), M_PI / 6, 2 * kUlpOfOne);
  EXPECT_NEAR(static_cast<double>(arctan(0.26794919f)), M_PI / 12, kUlpOfOne);
  EXPECT_NEAR(static_cast<double>(arctan(-0.26794919f)), -M_PI / 12, kUlpOfOne);
  EXPECT_EQ(arctan(0.0f), 0.0f);
  EXPECT_NEAR(static_cast<double>(arctan(std::numeric_limits<float>::infinity())), M_PI / 2, kUlpOfOne);
  EXPECT_NEAR(static_cast<double>(arctan(-std::numeric_limits<float>::infinity())), -M_PI / 2, kUlpOfOne);
  EXPECT_NEAR(static_cast<double>(arctan(1e30f)), M_PI / 2, kUlpOfOne);
  EXPECT_EQ(arctan(1e-30f), 1e-30f);  // atan x = x - x^3/3: x^3 is far below an ulp
  EXPECT_TRUE(std::isnan(arctan(std::numeric_limits<float>::quiet_NaN())));
}

TEST(TickMath, NearestIntegerRoundsHalfAwayFromZero) {
  EXPECT_EQ(nearest_integer(2.5f), 3.0f);
  EXPECT_EQ(nearest_integer(-2.5f), -3.0f);
  EXPECT_EQ(nearest_integer(2.49f), 2.0f);
  EXPECT_EQ(nearest_integer(-0.4f), 0.0f);
  EXPECT_EQ(nearest_integer(16777216.0f), 16777216.0f);  // already an integer
}

// Beyond 2^23 every float is whole, and beyond 2^31 no int32 holds it: such
// values, infinities and NaN come back as they are, never through an int.
TEST(TickMath, NearestIntegerLeavesWholeAndNonFiniteValuesAlone) {
  EXPECT_EQ(nearest_integer(3e9f), 3e9f);
  EXPECT_EQ(nearest_integer(-1e30f), -1e30f);
  EXPECT_EQ(nearest_integer(INFINITY), INFINITY);
  EXPECT_EQ(nearest_integer(-INFINITY), -INFINITY);
  EXPECT_TRUE(std::isnan(nearest_integer(NAN)));
}

}  // namespace
}  // namespace ff
