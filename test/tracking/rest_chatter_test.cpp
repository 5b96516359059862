// The chatter at rest split at each stop (tools/track_bench/rest_chatter.*),
// on hand-made rests whose figures are worked out by hand below.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "class_report.hpp"
#include "rest_chatter.hpp"
#include "tracking_evaluation.hpp"

namespace ff::bench {
namespace {

constexpr uint64_t kTick = 500;

// `n` resting ticks from t0 with the deviation `d(k)`.
template <typename F>
uint64_t rest_for(RestChatter& r, uint64_t t0, int n, F d) {
  for (int k = 0; k < n; ++k) r.resting(t0 + kTick * static_cast<uint64_t>(k), d(k));
  return t0 + kTick * static_cast<uint64_t>(n);
}

TEST(RestChatter, SplitsEachRestAtItsFirst100msAndTimesTheSettling) {
  ASSERT_EQ(kStopTransientUs, 100000u);
  RestChatter r;
  // 40 ticks (20 ms) at 0.2, then 360 at 0.01: in the band from 20 ms on,
  // for 180 ms, so settled after 20 ms; ticks 0-199 are the first 100 ms.
  rest_for(r, 1000, 400, [](int k) { return k < 40 ? 0.2 : -0.01; });
  r.not_resting();
  const double squares = 40 * 0.04 + 360 * 1e-4;
  EXPECT_EQ(r.ticks(), 400u);
  EXPECT_NEAR(r.rms(), std::sqrt(squares / 400.0), 1e-12);
  EXPECT_NEAR(r.steady_rms(), 0.01, 1e-12);
  EXPECT_NEAR(r.transient_share(), (1.6 + 160 * 1e-4) / squares, 1e-12);
  EXPECT_EQ(r.stops(), 1u);
  EXPECT_EQ(r.unsettled(), 0u);
  EXPECT_DOUBLE_EQ(r.settle_median_ms(), 20.0);
  EXPECT_DOUBLE_EQ(r.settle_max_ms(), 20.0);
}

TEST(RestChatter, AnExcursionBeforeTheHoldRestartsItOneAfterDoesNot) {
  RestChatter r;
  // In the band at once, out at 30 ms (one tick), in again from 30.5 ms:
  // 30 ms in the band is short of the 50 ms hold, so settled at 30.5 ms;
  // the excursion at 100 ms comes after and changes nothing.
  rest_for(r, 0, 400, [](int k) { return k == 60 || k == 200 ? 0.3 : 0.0; });
  r.not_resting();
  EXPECT_DOUBLE_EQ(r.settle_max_ms(), 30.5);
  // Only the excursion at 100 ms is past the first 100 ms: 0.09 over 200 ticks.
  EXPECT_NEAR(r.steady_rms(), std::sqrt(0.09 / 200.0), 1e-12);
  EXPECT_NEAR(r.transient_share(), 0.5, 1e-12);
}

TEST(RestChatter, RestsThatEndUnsettledAreCountedAndTheMedianIsOverTheOthers) {
  RestChatter r;
  uint64_t t = rest_for(r, 0, 100, [](int) { return 0.5; });  // never in the band
  r.not_resting();
  // In the band for its last 10 ms only: the rest ended in it, settled at 40 ms.
  t = rest_for(r, t + 1000000, 100, [](int k) { return k < 80 ? 0.1 : 0.0; });
  r.not_resting();
  r.not_resting();  // twice: still one rest
  t = rest_for(r, t + 1000000, 200, [](int k) { return k < 20 ? -0.06 : 0.0; });  // settled at 10 ms
  r.not_resting();
  rest_for(r, t + 1000000, 200, [](int) { return 0.0; });  // settled at once
  r.not_resting();
  EXPECT_EQ(r.stops(), 4u);
  EXPECT_EQ(r.unsettled(), 1u);
  EXPECT_DOUBLE_EQ(r.settle_median_ms(), 10.0);  // of 40, 10, 0
  EXPECT_DOUBLE_EQ(r.settle_max_ms(), 40.0);
}

TEST(RestChatter, NoRestNoFigures) {
  RestChatter r;
  r.not_resting();
  EXPECT_EQ(r.stops(), 0u);
  EXPECT_EQ(r.rms(), 0.0);
  EXPECT_EQ(r.steady_rms(), 0.0);
  EXPECT_EQ(r.transient_share(), 0.0);
  EXPECT_EQ(r.settle_median_ms(), 0.0);
}

// evaluate() counts a stop per rest of the generated traces (counted here
// from the truth); a pipeline without a fade (the thesis') chatters alike
// all through a rest, so the first 100 ms of each hold about their share of
// the rest's ticks, and it never settles for long.
TEST(RestChatter, EvaluateSplitsTheGeneratedRests) {
  std::vector<PreparedCase> cases;
  for (const TrackCase& c : standard_cases(1.0, 20.0)) {
    cases.push_back(prepare_case(c));
    if (cases.size() == 2) break;
  }
  size_t rests = 0;
  for (const PreparedCase& c : cases) {
    bool was = false;
    for (const TickTruth& t : c.ticks) {
      const bool now = t.state.touching && t.state.resting;
      rests += now && !was ? 1 : 0;
      was = now;
    }
  }
  ASSERT_GT(rests, 0u);
  EvalOptions options;
  options.cost = false;
  options.lag = false;
  const Metrics m = evaluate(TrackerConfig::recommended(), cases, options);
  EXPECT_EQ(m.stops, rests);
  EXPECT_EQ(m.unsettled_stops, 0u);
  EXPECT_LE(m.stop_settle_median_ms, m.stop_settle_max_ms);
  EXPECT_LT(m.heightmap_steady_rest_rms, 0.02);
  const Metrics thesis = evaluate(TrackerConfig::thesis(), cases, options);
  EXPECT_EQ(thesis.stops, rests);
  const double tick_share = static_cast<double>(rests * 200) / static_cast<double>(thesis.rest_ticks);
  EXPECT_GT(thesis.rest_transient_share, tick_share / 3.0);
  EXPECT_LT(thesis.rest_transient_share, tick_share * 3.0);
  EXPECT_NEAR(thesis.heightmap_steady_rest_rms, thesis.heightmap_rest_rms, 0.2 * thesis.heightmap_rest_rms);
  EXPECT_GE(thesis.unsettled_stops, rests / 2);
}

TEST(RestChatter, TheTableHoldsEveryRow) {
  ClassRow row{"white-200hz", "recommended(profile)", {}, 0.1};
  row.metrics.heightmap_rest_rms = 0.014;
  row.metrics.rest_transient_share = 0.83;
  row.metrics.heightmap_steady_rest_rms = 0.006;
  row.metrics.stops = 12;
  row.metrics.stop_settle_median_ms = 0.5;
  row.metrics.stop_settle_max_ms = 29.5;
  ClassRow never{"white-200hz", "thesis", {}, 0.1};
  never.metrics.stops = 3;
  never.metrics.unsettled_stops = 3;
  std::ostringstream out;
  write_rest_report(out, {never, row});
  EXPECT_NE(out.str().find("| white-200hz | recommended(profile) | 0.014 | 83 % | 0.006 | 12 | 0.5 | 29.5 | 0 |\n"),
            std::string::npos)
      << out.str();
  EXPECT_NE(out.str().find("| white-200hz | thesis | 0.000 | 0 % | 0.000 | 3 | - | - | 3 |\n"), std::string::npos)
      << out.str();
}

}  // namespace
}  // namespace ff::bench
