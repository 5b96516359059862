// The start floor of ff-track-bench --classes on a hand-made stroke.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "class_report.hpp"

namespace ff::bench {
namespace {

TickTruth tick(double x, double vx, bool touching = true) {
  TickTruth t;
  t.state.touching = touching;
  t.state.position = {x, 100.0};
  t.state.velocity = {vx, 0.0};
  t.heightmap_ideal = 0.8f;  // 0.3 from rest everywhere
  return t;
}

TEST(StartFloor, RendersRestOnlyUntilTheFingerHasMovedTheDistance) {
  PreparedCase c;
  for (int k = 0; k < 10; ++k) c.ticks.push_back(tick(100.0, 0.0));  // standing: not moving ticks
  // 40 ticks at 100 px/s (0.05 px per tick): moved 0.05 .. 2.0 px; below
  // 0.98 px for the first 19.
  for (int k = 1; k <= 40; ++k) c.ticks.push_back(tick(100.0 + 0.05 * k, 100.0));
  c.ticks.push_back(tick(0.0, 0.0, false));  // lifted: not counted
  // Lands at 300 already moving: a start from where it lands, 10 ticks all
  // within 0.45 px of it.
  for (int k = 0; k < 10; ++k) c.ticks.push_back(tick(300.0 + 0.05 * k, 100.0));
  std::vector<PreparedCase> cases;
  cases.push_back(std::move(c));
  const double e = 0.8 - 0.5;
  EXPECT_NEAR(start_floor_rms(cases, 20.0, 0.98), std::sqrt((19 + 10) * e * e / 50.0), 1e-6);
  EXPECT_NEAR(start_floor_rms(cases, 20.0, 0.0), 0.0, 1e-12);
  EXPECT_NEAR(start_floor_rms(cases, 20.0, 1e9), e, 1e-6);  // never a direction
  EXPECT_NEAR(start_floor_rms(cases, 150.0, 0.98), 0.0, 1e-12);  // nothing moves fast enough
}

TEST(StartFloor, TheTableHoldsTheTrackerAndItsUnfadedErrorAgainstTheThesis) {
  StartFloorRow row{"white-200hz", 0.2, {0.02, 0.04, 0.08}};
  row.tracker_heightmap_rms = 0.09;
  row.unfaded_heightmap_rms = 0.1;
  std::ostringstream out;
  write_start_floor(out, {row});
  EXPECT_NE(out.str().find("| white-200hz | 0.200 | 0.020 (0.10×) | 0.040 (0.20×) | 0.080 (0.40×) | 0.090 (0.45×) | "
                           "0.100 (0.50×) |\n"),
            std::string::npos)
      << out.str();
}

}  // namespace
}  // namespace ff::bench
