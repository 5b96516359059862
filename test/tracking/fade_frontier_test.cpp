// ff-track-bench --frontier: the grid, the Pareto front and the pick on
// hand-made points, and the sweep on generated traces against a direct
// evaluation and the fade's own order.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "class_report.hpp"
#include "fade_frontier.hpp"
#include "support/models/trace_classes.hpp"

namespace ff::bench {
namespace {

FrontierPoint point(float rest, float moving, double heightmap_ratio, double chatter) {
  return {{rest, moving}, heightmap_ratio, chatter};
}

TEST(FadeFrontier, TheGridKeepsABandOfOneSigmaAndHoldsTheShippingFade) {
  // Rest 0.5 and 1 take all seven full-length levels (2-9), 1.5 and 2 all
  // but 2, 2.5 and 3 all but 2 and 3, 4 all but 2-4: 7 + 7 + 6 + 6 + 5 + 5 + 4.
  const std::vector<FadeLevels> grid = frontier_grid();
  EXPECT_EQ(grid.size(), 40u);
  bool shipping = false;
  const TrackerConfig r = TrackerConfig::recommended();
  for (FadeLevels f : grid) {
    EXPECT_GE(f.moving_sigmas, f.rest_sigmas + 1.0f);
    shipping = shipping || (f.rest_sigmas == r.rest_sigmas && f.moving_sigmas == r.moving_sigmas);
  }
  EXPECT_TRUE(shipping);
}

TEST(FadeFrontier, TheFrontKeepsWhatNothingBeatsOnBoth) {
  const std::vector<FrontierPoint> points = {
      point(1, 2, 0.50, 0.010),   // a
      point(1, 3, 0.40, 0.020),   // b
      point(1, 4, 0.60, 0.005),   // c
      point(1, 5, 0.55, 0.020),   // beaten by b (lower heightmap, same chatter)
      point(1, 6, 0.50, 0.010),   // a tie with a: neither beats the other
      point(1, 7, 0.70, 0.030),   // beaten by all of a, b, c
  };
  const std::vector<FrontierPoint> front = pareto_front(points);
  ASSERT_EQ(front.size(), 4u);
  EXPECT_EQ(front[0].fade.moving_sigmas, 4.0f);  // by rising chatter: c, a and its tie, b
  EXPECT_EQ(front[1].chatter, 0.010);
  EXPECT_EQ(front[2].chatter, 0.010);
  EXPECT_EQ(front[3].fade.moving_sigmas, 3.0f);

  ASSERT_NE(best_within(points, 0.010), nullptr);
  EXPECT_EQ(best_within(points, 0.010)->heightmap_ratio, 0.50);  // the bound itself counts
  EXPECT_EQ(best_within(points, 0.009)->fade.moving_sigmas, 4.0f);
  EXPECT_EQ(best_within(points, 0.001), nullptr);
  EXPECT_EQ(best_within(points, INFINITY)->fade.moving_sigmas, 3.0f);
}

TEST(FadeFrontier, TheReportSaysWhetherAnyFadeMeetsBothGoals) {
  FrontierRow met{"slow-fingers", 0.45, 0.01, {2.5f, 5.0f}, {point(2.5f, 5, 0.44, 0.009), point(1, 3, 0.30, 0.05)}};
  FrontierRow missed{"realistic-200hz", 0.45, 0.01, {2.5f, 5.0f}, {point(2.5f, 5, 0.59, 0.0101), point(3, 5, 0.61, 0.007)}};
  std::ostringstream out;
  write_frontier_report(out, {met, missed}, 30.0);
  const std::string s = out.str();
  EXPECT_EQ(s.substr(0, s.find("| slow-fingers")),
            "| class | shipping fade | best at chatter ≤ goal | best at any chatter | heightmap goal | both goals by "
            "some fade |\n|---|--:|--:|--:|--:|---|\n");
  EXPECT_NE(s.find("| slow-fingers | 0.44× at 0.009 (2.5 / 5.0 σ) | 0.44× (2.5 / 5.0 σ) | 0.30× at 0.050 (1.0 / 3.0 σ) "
                   "| 0.45× | yes |"),
            std::string::npos)
      << s;
  // Its shipping fade chatters just over the goal: the best quiet one is another, and misses.
  EXPECT_NE(s.find("| realistic-200hz | 0.59× at 0.010 (2.5 / 5.0 σ) | 0.61× (3.0 / 5.0 σ) | 0.59× at 0.010 (2.5 / "
                   "5.0 σ) | 0.45× | no |"),
            std::string::npos)
      << s;
  // No fade quiet enough, and a shipping fade off the grid: both cells say so.
  FrontierRow loud{"tremor", 0.45, 0.01, {2.0f, 7.0f}, {point(2.5f, 5, 0.50, 0.02), point(1, 3, 0.40, 0.03)}};
  std::ostringstream none;
  write_frontier_report(none, {loud}, 30.0);
  EXPECT_NE(none.str().find("| tremor | none | none | 0.40× at 0.030 (1.0 / 3.0 σ) | 0.45× | no |"), std::string::npos)
      << none.str();
}

// The CSV: a row per point, on the front or not, the shipping fade marked,
// the goals on every row.
TEST(FadeFrontier, TheCsvHasEveryPointWithItsMarks) {
  FrontierRow row{"slow-fingers", 0.45, 0.01, {2.5f, 5.0f},
                  {point(2.5f, 5, 0.44, 0.009), point(1, 3, 0.30, 0.05), point(3, 5, 0.5, 0.02)}};
  std::ostringstream out;
  write_frontier_csv(out, {row});
  EXPECT_EQ(out.str(),
            "class,rest_sigmas,moving_sigmas,heightmap_vs_thesis,rest_rms,pareto,shipping,heightmap_goal,rest_goal\n"
            "slow-fingers,2.50,5.00,0.44,0.009,1,1,0.45,0.010\n"
            "slow-fingers,1.00,3.00,0.3,0.05,1,0,0.45,0.010\n"
            "slow-fingers,3.00,5.00,0.5,0.02,0,0,0.45,0.010\n");
}

class FadeFrontierOnTraces : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const tracegen::TraceClass* white = tracegen::find_trace_class("white-200hz");
    ASSERT_NE(white, nullptr);
    cases_ = new std::vector<PreparedCase>();
    for (const TrackCase& c : class_cases(*white, 4.0)) cases_->push_back(prepare_case(c));
    sensor_ = tracegen::nominal_profile(cases_->front().spec.options);
    options_.moving_speed_px_s = kClassMovingSpeedPxS;
    options_.lag = false;
    options_.cost = false;
    row_ = new FrontierRow(fade_frontier("white-200hz", *cases_, sensor_, recommended_constants(), options_));
  }
  static void TearDownTestSuite() {
    delete row_;
    delete cases_;
  }
  static const FrontierPoint& at(float rest, float moving) {
    for (const FrontierPoint& p : row_->points)
      if (p.fade.rest_sigmas == rest && p.fade.moving_sigmas == moving) return p;
    ADD_FAILURE() << rest << " / " << moving << " not in the grid";
    return row_->points.front();
  }
  static std::vector<PreparedCase>* cases_;
  static SensorProfile sensor_;
  static EvalOptions options_;
  static FrontierRow* row_;
};
std::vector<PreparedCase>* FadeFrontierOnTraces::cases_ = nullptr;
SensorProfile FadeFrontierOnTraces::sensor_;
EvalOptions FadeFrontierOnTraces::options_;
FrontierRow* FadeFrontierOnTraces::row_ = nullptr;

TEST_F(FadeFrontierOnTraces, TheShippingPointIsWhatTheClassTableMeasures) {
  ASSERT_EQ(row_->points.size(), frontier_grid().size());
  const FrontierPoint* shipping = shipping_point(*row_);
  ASSERT_NE(shipping, nullptr);
  const Metrics thesis = evaluate(TrackerConfig::thesis(), *cases_, options_);
  const Metrics ships = evaluate(TrackerConfig::recommended(sensor_), *cases_, options_);
  EXPECT_DOUBLE_EQ(shipping->heightmap_ratio, ships.heightmap_rms / thesis.heightmap_rms);
  EXPECT_DOUBLE_EQ(shipping->chatter, ships.heightmap_rest_rms);
  EXPECT_DOUBLE_EQ(row_->heightmap_goal, kClassMaxHeightmapRatioWhite);
  // And two points off the shipping fade, each level of them its own: the
  // tracker evaluated directly with those levels.
  for (FadeLevels fade : {FadeLevels{0.5f, 2.0f}, FadeLevels{4.0f, 9.0f}}) {
    ProposedConstants constants = recommended_constants();
    constants.rest_sigmas = fade.rest_sigmas;
    constants.moving_sigmas = fade.moving_sigmas;
    const Metrics m = evaluate([&](const PreparedCase& c) { return proposed_tracker(constants, nominal_profile(c)); },
                               *cases_, options_);
    EXPECT_DOUBLE_EQ(at(fade.rest_sigmas, fade.moving_sigmas).heightmap_ratio, m.heightmap_rms / thesis.heightmap_rms);
    EXPECT_DOUBLE_EQ(at(fade.rest_sigmas, fade.moving_sigmas).chatter, m.heightmap_rest_rms);
  }
}

TEST_F(FadeFrontierOnTraces, ARaisedLevelFadesMoreAtEveryTick) {
  // The fade is smoothstep((snr^2 - rest^2) / (moving^2 - rest^2)), with snr
  // the velocity's size in sigmas of its noise: for snr <= moving its
  // derivative in rest^2 is (snr^2 - moving^2) / span^2 <= 0, in moving^2
  // -(snr^2 - rest^2) / span^2 <= 0, and the filters never read it; so a
  // raised level shortens the direction at every tick, and the chatter at
  // rest (|A - 0.5| grows with the direction's length) cannot rise.
  for (FadeLevels lighter : frontier_grid()) {
    for (FadeLevels heavier : frontier_grid()) {
      const bool raised = (heavier.rest_sigmas == lighter.rest_sigmas && heavier.moving_sigmas > lighter.moving_sigmas) ||
                          (heavier.moving_sigmas == lighter.moving_sigmas && heavier.rest_sigmas > lighter.rest_sigmas);
      if (raised) {
        EXPECT_LE(at(heavier.rest_sigmas, heavier.moving_sigmas).chatter,
                  at(lighter.rest_sigmas, lighter.moving_sigmas).chatter)
            << heavier.rest_sigmas << " / " << heavier.moving_sigmas << " against " << lighter.rest_sigmas << " / "
            << lighter.moving_sigmas;
      }
    }
  }
  // And the trade is real at the grid's corners: the lightest fade chatters
  // more and errs less while moving than the heaviest.
  EXPECT_GT(at(0.5f, 2.0f).chatter, 3.0 * at(4.0f, 9.0f).chatter);
  EXPECT_LT(at(0.5f, 2.0f).heightmap_ratio, at(4.0f, 9.0f).heightmap_ratio - 0.05);
}

}  // namespace
}  // namespace ff::bench
