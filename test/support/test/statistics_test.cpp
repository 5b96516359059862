// The benchmark's statistics against hand-derived values.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "support/statistics.hpp"

namespace ff::support {
namespace {

TEST(Rms, HandValues) {
  EXPECT_DOUBLE_EQ(rms({}), 0.0);
  EXPECT_DOUBLE_EQ(rms({3.0, 4.0}), std::sqrt(12.5));
  EXPECT_DOUBLE_EQ(rms({-2.0, 2.0, -2.0}), 2.0);
  EXPECT_DOUBLE_EQ(mean({1.0, 2.0, 6.0}), 3.0);
}

TEST(Percentile, LinearBetweenClosestRanksLikeNumpy) {
  std::vector<double> hundred;
  for (int i = 1; i <= 100; ++i) hundred.push_back(i);
  EXPECT_DOUBLE_EQ(percentile(hundred, 95.0), 95.05);  // numpy.percentile(range(1, 101), 95)
  EXPECT_DOUBLE_EQ(percentile({4.0, 1.0, 3.0, 2.0}, 50.0), 2.5);
  EXPECT_DOUBLE_EQ(percentile({4.0, 1.0, 3.0, 2.0}, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(percentile({4.0, 1.0, 3.0, 2.0}, 100.0), 4.0);
  EXPECT_DOUBLE_EQ(percentile({7.0}, 95.0), 7.0);
  EXPECT_DOUBLE_EQ(percentile({}, 95.0), 0.0);
}

TEST(AngleDeg, HandValues) {
  EXPECT_NEAR(angle_deg(1, 0, 0, 1), 90.0, 1e-12);
  EXPECT_NEAR(angle_deg(1, 0, -3, 0), 180.0, 1e-12);
  EXPECT_NEAR(angle_deg(2, 2, 1, 0), 45.0, 1e-12);
  EXPECT_NEAR(angle_deg(1, 1, 1, 1), 0.0, 1e-5);  // acos near 1: ~1e-6 deg of rounding
  EXPECT_DOUBLE_EQ(angle_deg(0, 0, 1, 0), 90.0);  // no direction: no information
  EXPECT_DOUBLE_EQ(angle_deg(1, 0, 0, 0), 90.0);
}

TEST(Minimise, FindsTheMinimumOfAParabolaAndOfAnAsymmetricValley) {
  EXPECT_NEAR(minimise([](double x) { return (x - 1.234) * (x - 1.234); }, -10.0, 30.0, 21, 1e-4), 1.234, 1e-4);
  EXPECT_NEAR(minimise([](double x) { return x < 7.5 ? 7.5 - x : 3.0 * (x - 7.5); }, -10.0, 30.0, 21, 1e-4), 7.5, 1e-4);
  // At the edge of the range.
  EXPECT_NEAR(minimise([](double x) { return x; }, -10.0, 30.0, 21, 1e-4), -10.0, 1e-4);
}

TEST(BestLag, RecoversAKnownDelayOfACircularMotion) {
  // The finger circles at 2 rad/s with radius 100 px; the estimate is the
  // true position 3.7 ms late.
  auto truth = [](double t) { return Position2{400.0 + 100.0 * std::cos(2.0 * t), 240.0 + 100.0 * std::sin(2.0 * t)}; };
  std::vector<TimedPosition> estimates;
  for (int k = 0; k < 4000; ++k) {
    const double t = 0.0005 * k;
    const Position2 p = truth(t - 0.0037);
    estimates.push_back({t, p.x, p.y});
  }
  EXPECT_NEAR(best_lag_ms(estimates, truth), 3.7, 0.02);
  // An estimate ahead of the finger has a negative lag.
  for (TimedPosition& e : estimates) {
    const Position2 p = truth(e.t_s + 0.002);
    e.x = p.x, e.y = p.y;
  }
  EXPECT_NEAR(best_lag_ms(estimates, truth), -2.0, 0.02);
}

}  // namespace
}  // namespace ff::support
