#include "frictionfield/core/one_euro_filter.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "support/reference/reference_amplitude.hpp"
#include "support/reference/reference_scene.hpp"
#include "support/reference/reference_tracker.hpp"

namespace ff {
namespace {

// The double reference of appendix G (docs/spec.md#thesis-tracker), written
// independently of the core: test/support/reference/reference_tracker.hpp.
using reference::ReferenceOneEuro;

TEST(OneEuroFilter, HandDerivedFirstSteps) {
  OneEuroFilter f;
  f.configure(OneEuroConfig{});
  EXPECT_FLOAT_EQ(f.filter(0.0f), 0.0f);  // first sample passes through
  EXPECT_FLOAT_EQ(f.derivative(), 0.0f);
  // alpha_d = 1 / (1 + 2000 / (2 pi 25)) = 0.0728205; dx = 2000; dxhat = 145.641
  // fc = 20 + 0.0004 * 145.641 = 20.05826; alpha = 0.0592794
  EXPECT_NEAR(static_cast<double>(f.filter(1.0f)), 0.0592794, 1e-6);
  EXPECT_NEAR(static_cast<double>(f.derivative()), 145.641, 2e-3);
}

TEST(OneEuroFilter, BothVariantsMatchTheDoubleReference) {
  for (DerivativeFrom from : {DerivativeFrom::PreviousFiltered, DerivativeFrom::PreviousRaw}) {
    OneEuroConfig c;
    c.derivative_from = from;
    OneEuroFilter f;
    f.configure(c);
    ReferenceOneEuro ref;
    ref.from_filtered = from == DerivativeFrom::PreviousFiltered;
    std::mt19937 rng(7);
    std::normal_distribution<float> noise(0.0f, 1.5f);
    double worst = 0;
    for (int i = 0; i < 20000; ++i) {
      const float x = 400.0f + 200.0f * std::sin(static_cast<float>(i) * 0.002f) + noise(rng);
      worst = std::fmax(worst, std::fabs(static_cast<double>(f.filter(x)) - ref(static_cast<double>(x))));
    }
    EXPECT_LT(worst, 2e-3) << "px";
  }
}

TEST(OneEuroFilter, VariantsDifferOnlyAfterTheSecondSample) {
  OneEuroConfig raw;
  raw.derivative_from = DerivativeFrom::PreviousRaw;
  OneEuroFilter a, b;
  a.configure(OneEuroConfig{});
  b.configure(raw);
  a.filter(0.0f);
  b.filter(0.0f);
  EXPECT_FLOAT_EQ(a.filter(1.0f), b.filter(1.0f));  // previous raw == previous filtered == 0
  EXPECT_NE(a.filter(2.0f), b.filter(2.0f));
}

TEST(OneEuroFilter, ConfiguringStartsItAfresh) {
  // A new condition reconfigures the tracker's filters: the first value after
  // that passes through, as after a reset, instead of blending with the old one.
  OneEuroFilter f;
  f.configure(OneEuroConfig{});
  f.filter(0.0f);
  f.filter(10.0f);
  f.configure(OneEuroConfig{});
  EXPECT_FLOAT_EQ(f.filter(500.0f), 500.0f);
  EXPECT_FLOAT_EQ(f.derivative(), 0.0f);
}

TEST(OneEuroFilter, SettlesOnAConstant) {
  OneEuroFilter f;
  f.configure(OneEuroConfig{});
  f.filter(0.0f);
  float y = 0.0f;
  for (int i = 0; i < 2000; ++i) y = f.filter(100.0f);
  EXPECT_NEAR(static_cast<double>(y), 100.0, 1e-3);
  EXPECT_NEAR(static_cast<double>(f.derivative()), 0.0, 0.1);  // float rounding near 100 px, x2000
}

}  // namespace
}  // namespace ff
