// The true motion: minimum-jerk profile, the paths of docs/spec.md#paths, strokes and holds.
#include <gtest/gtest.h>

#include <cmath>

#include "support/models/motion.hpp"

namespace ff::tracegen {
namespace {

TEST(MinJerk, ProfileEndsAndMiddle) {
  EXPECT_DOUBLE_EQ(min_jerk(0.0), 0.0);
  EXPECT_DOUBLE_EQ(min_jerk(1.0), 1.0);
  EXPECT_DOUBLE_EQ(min_jerk(0.5), 0.5);
  EXPECT_DOUBLE_EQ(min_jerk(-1.0), 0.0);  // clamped outside the stroke
  EXPECT_DOUBLE_EQ(min_jerk(2.0), 1.0);
  // 10/8 - 15/16 + 6/32 = 0.5 at the middle; 10 t^3 - 15 t^4 + 6 t^5 at 0.25:
  EXPECT_NEAR(min_jerk(0.25), 10.0 / 64 - 15.0 / 256 + 6.0 / 1024, 1e-15);
}

TEST(MinJerk, RateIsTheDerivativeAndPeaksAt1875) {
  EXPECT_DOUBLE_EQ(min_jerk_rate(0.5), kMinJerkPeakRate);
  EXPECT_DOUBLE_EQ(min_jerk_rate(0.0), 0.0);
  EXPECT_DOUBLE_EQ(min_jerk_rate(1.0), 0.0);
  for (double tau = 0.05; tau < 1.0; tau += 0.1) {
    const double h = 1e-6;
    EXPECT_NEAR(min_jerk_rate(tau), (min_jerk(tau + h) - min_jerk(tau - h)) / (2 * h), 1e-6) << tau;
  }
}

TEST(Paths, MatchSpec) {
  // Flat at 240 before x = 100, at 240 + T after x = 700, half way at x = 400.
  for (double rise : {-200.0, 0.0, 200.0}) {
    EXPECT_DOUBLE_EQ(path_y(50.0, rise), 240.0);
    EXPECT_DOUBLE_EQ(path_y(100.0, rise), 240.0);
    EXPECT_DOUBLE_EQ(path_y(700.0, rise), 240.0 + rise);
    EXPECT_DOUBLE_EQ(path_y(750.0, rise), 240.0 + rise);
    EXPECT_NEAR(path_y(400.0, rise), 240.0 + rise / 2.0, 1e-12);
    EXPECT_DOUBLE_EQ(path_slope(100.0, rise), 0.0);
    EXPECT_NEAR(path_slope(700.0 - 1e-9, rise), 0.0, 1e-9);
    // Slope at the middle: 6T/L^2 * 300 - 6T/L^3 * 300^2 = T / 400.
    EXPECT_NEAR(path_slope(400.0, rise), rise / 400.0, 1e-12);
  }
}

TEST(Motion, StraightStrokeTimedForItsPeakSpeed) {
  Motion m({100.0, 100.0});
  m.stroke_to({400.0, 100.0}, 1000.0);
  // Peak speed 1.875 L / T: T = 1.875 * 300 / 1000.
  ASSERT_EQ(m.segments().size(), 1u);
  EXPECT_NEAR(m.duration_s(), 0.5625, 1e-12);
  const TrueState mid = m.at(0.5625 / 2);
  EXPECT_TRUE(mid.touching);
  EXPECT_NEAR(mid.position.x, 250.0, 1e-9);
  EXPECT_NEAR(mid.position.y, 100.0, 1e-9);
  EXPECT_NEAR(mid.velocity.x, 1000.0, 1e-9);
  EXPECT_NEAR(mid.velocity.y, 0.0, 1e-9);
  const TrueState end = m.at(10.0);
  EXPECT_NEAR(end.position.x, 400.0, 1e-9);
  EXPECT_DOUBLE_EQ(end.velocity.x, 0.0);
}

TEST(Motion, AStrokeTimedByItsDurationRecordsTheSpeedItPeaksAt) {
  Motion m({100.0, 100.0});
  m.stroke_for({100.0, 400.0}, 0.75);
  // 1.875 L / T = 1.875 * 300 / 0.75.
  ASSERT_EQ(m.segments().size(), 1u);
  EXPECT_NEAR(m.segments().front().peak_speed_px_s, 750.0, 1e-9);
  EXPECT_NEAR(m.at(0.375).velocity.y, 750.0, 1e-9);
  EXPECT_NEAR(m.at(0.375).velocity.x, 0.0, 1e-9);
}

TEST(Motion, VelocityIsTheDerivativeOfPositionOnEveryShape) {
  Motion m({120.0, 240.0});
  m.stroke_to({300.0, 400.0}, 800.0, 25.0);          // bowed
  m.hold(0.05, false);
  m.stroke_along_path(650.0, -200.0, 8.0, 1500.0);   // along the top path
  const double h = 1e-6;
  for (double t = 0.01; t < m.duration_s(); t += 0.013) {
    const TrueState s = m.at(t);
    const TrueState a = m.at(t - h), b = m.at(t + h);
    EXPECT_NEAR(s.velocity.x, (b.position.x - a.position.x) / (2 * h), 1e-3 * (1.0 + std::fabs(s.velocity.x))) << t;
    EXPECT_NEAR(s.velocity.y, (b.position.y - a.position.y) / (2 * h), 1e-3 * (1.0 + std::fabs(s.velocity.y))) << t;
  }
}

TEST(Motion, AlongPathStaysOnThePathPlusTheOffset) {
  Motion m({100.0, 245.0});  // 5 px below the start of every path
  m.stroke_along_path(700.0, 200.0, -5.0, 1000.0);
  const Segment& s = m.segments().front();
  EXPECT_DOUBLE_EQ(s.u0, 5.0);
  for (double t = 0.0; t <= m.duration_s(); t += m.duration_s() / 20) {
    const TrueState st = m.at(t);
    const double sigma = (st.position.x - 100.0) / 600.0;
    EXPECT_NEAR(st.position.y - path_y(st.position.x, 200.0), 5.0 - 10.0 * sigma, 1e-9);
  }
  EXPECT_NEAR(m.position().y, 435.0, 1e-9);
}

TEST(Motion, HoldsRestsAndLifts) {
  Motion m({200.0, 200.0});
  m.hold(0.5, true);
  m.lift(0.2, {500.0, 300.0});
  m.hold(0.1, false);
  EXPECT_DOUBLE_EQ(m.duration_s(), 0.8);
  EXPECT_TRUE(m.at(0.25).resting);
  EXPECT_TRUE(m.at(0.25).touching);
  EXPECT_FALSE(m.at(0.6).touching);
  EXPECT_TRUE(m.at(0.75).touching);
  EXPECT_FALSE(m.at(0.75).resting);
  EXPECT_DOUBLE_EQ(m.at(0.75).position.x, 500.0);
}

TEST(Motion, WithNoSegmentsTheFingerIsDownWhereItStarted) {
  const Motion m({120.0, 340.0});
  const TrueState s = m.at(1.0);
  EXPECT_TRUE(s.touching);
  EXPECT_FALSE(s.resting);
  EXPECT_DOUBLE_EQ(s.position.x, 120.0);
  EXPECT_DOUBLE_EQ(s.position.y, 340.0);
}

TEST(Motion, AHoldOfNoTimeIsNoSegment) {
  Motion m({200.0, 200.0});
  m.hold(0.0, false);
  m.hold(-0.1, true);
  EXPECT_TRUE(m.segments().empty());
  EXPECT_DOUBLE_EQ(m.duration_s(), 0.0);
}

TEST(Motion, AfterALastLiftTheFingerIsDownWhereItLanded) {
  Motion m({200.0, 200.0});
  m.lift(0.2, {500.0, 300.0});
  EXPECT_FALSE(m.at(0.1).touching);
  EXPECT_DOUBLE_EQ(m.at(0.1).position.x, 200.0);  // off the screen where it left
  const TrueState landed = m.at(0.3);
  EXPECT_TRUE(landed.touching);
  EXPECT_DOUBLE_EQ(landed.position.x, 500.0);
  EXPECT_DOUBLE_EQ(landed.position.y, 300.0);
  EXPECT_DOUBLE_EQ(m.position().x, 500.0);
}

}  // namespace
}  // namespace ff::tracegen
