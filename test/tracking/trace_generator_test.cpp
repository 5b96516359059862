// The generated traces: deterministic, realistic timing, noise and speeds,
// and every fault exactly where and how it was asked for.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "support/models/sensor_model.hpp"

namespace ff::tracegen {
namespace {

constexpr uint64_t kWrap = uint64_t{1} << 32;

TraceOptions clean(Strategy strategy, uint64_t seed, double duration_s = 20.0) {
  TraceOptions o;
  o.seed = seed;
  o.motion.strategy = strategy;
  o.motion.duration_s = duration_s;
  return o;
}

bool same(const TraceSample& a, const TraceSample& b) {
  auto eq = [](double x, double y) { return (std::isnan(x) && std::isnan(y)) || x == y; };
  return a.t_us == b.t_us && eq(a.x, b.x) && eq(a.y, b.y) && a.touch == b.touch && eq(a.x_true, b.x_true) &&
         eq(a.y_true, b.y_true) && a.event == b.event;
}

TEST(TraceGenerator, SameSeedSameTraceOtherSeedOtherTrace) {
  TraceOptions o = clean(Strategy::Mixed, 7);
  o.faults.jumps = 3;
  o.faults.duplicates = 3;
  const GeneratedTrace a = generate_trace(o), b = generate_trace(o);
  ASSERT_EQ(a.samples.size(), b.samples.size());
  for (size_t i = 0; i < a.samples.size(); ++i) ASSERT_TRUE(same(a.samples[i], b.samples[i])) << i;
  o.seed = 8;
  const GeneratedTrace c = generate_trace(o);
  EXPECT_NE(c.samples[10].x_true, a.samples[10].x_true);
}

TEST(TraceGenerator, NoiseLevelDoesNotChangeTheMotionOrTheTiming) {
  TraceOptions o = clean(Strategy::Across, 3);
  o.sensor.noise_px = kNoiseLowPx;
  const GeneratedTrace low = generate_trace(o);
  o.sensor.noise_px = kNoiseHighPx;
  const GeneratedTrace high = generate_trace(o);
  ASSERT_EQ(low.samples.size(), high.samples.size());
  for (size_t i = 0; i < low.samples.size(); ++i) {
    EXPECT_EQ(low.samples[i].t_us, high.samples[i].t_us);
    EXPECT_TRUE(low.samples[i].x_true == high.samples[i].x_true ||
                (std::isnan(low.samples[i].x_true) && std::isnan(high.samples[i].x_true)));
  }
}

TEST(TraceGenerator, ReportsAt200HzWithBoundedJitter) {
  TraceOptions o = clean(Strategy::Along, 11);
  o.sensor.jitter_us = 150.0;
  const GeneratedTrace t = generate_trace(o);
  ASSERT_GT(t.samples.size(), 3000u);
  EXPECT_EQ(t.samples.front().t_us, o.faults.start_us);
  EXPECT_EQ(t.samples.front().event, SampleEvent::TouchDown);
  EXPECT_EQ(t.samples.back().event, SampleEvent::LiftReport);
  double sum = 0.0, sum2 = 0.0;
  size_t n = 0;
  for (size_t i = 1; i + 1 < t.samples.size(); ++i) {
    const double dt = static_cast<double>(t.samples[i].t_us - t.samples[i - 1].t_us);
    ASSERT_GE(dt, 5000.0 - 2 * 1500.0);  // jitter is clipped to 30 % of the period
    ASSERT_LE(dt, 5000.0 + 2 * 1500.0);
    sum += dt;
    sum2 += dt * dt;
    ++n;
  }
  const double mean = sum / static_cast<double>(n);
  const double sd = std::sqrt(sum2 / static_cast<double>(n) - mean * mean);
  EXPECT_NEAR(mean, 5000.0, 5.0);
  // Differences of independent jitters: sqrt(2) * 150 us.
  EXPECT_NEAR(sd, std::sqrt(2.0) * 150.0, 0.05 * std::sqrt(2.0) * 150.0);
}

TEST(TraceGenerator, NoiseHasTheRequestedSigmaAndNoBias) {
  for (double sigma : {kNoiseLowPx, kNoiseHighPx}) {
    TraceOptions o = clean(Strategy::Mixed, 5, 30.0);
    o.sensor.noise_px = sigma;
    const GeneratedTrace t = generate_trace(o);
    double sum = 0.0, sum2 = 0.0;
    size_t n = 0;
    for (const TraceSample& s : t.samples) {
      if (!s.touch) continue;
      for (double e : {s.x - s.x_true, s.y - s.y_true}) {
        sum += e;
        sum2 += e * e;
        ++n;
      }
    }
    const double mean = sum / static_cast<double>(n);
    const double sd = std::sqrt(sum2 / static_cast<double>(n));
    EXPECT_NEAR(mean, 0.0, 4.0 * sigma / std::sqrt(static_cast<double>(n)));
    EXPECT_NEAR(sd, sigma, 0.03 * sigma);  // n ~ 12000: the estimate's own spread is ~0.7 %
  }
}

TEST(TraceGenerator, Quantisation) {
  TraceOptions o = clean(Strategy::Along, 2, 5.0);
  o.sensor.quantum_px = 1.0;
  for (const TraceSample& s : generate_trace(o).samples) {
    EXPECT_EQ(s.x, std::round(s.x));
    EXPECT_EQ(s.y, std::round(s.y));
  }
  o.sensor.quantum_px = kZForceQuantumPx;
  size_t halves = 0;
  for (const TraceSample& s : generate_trace(o).samples) {
    EXPECT_EQ(2.0 * s.x, std::round(2.0 * s.x));
    halves += 2.0 * s.x != 2.0 * std::round(s.x) ? 1 : 0;
  }
  EXPECT_GT(halves, 100u);  // the half steps are used
}

TEST(TraceGenerator, StrokePeakSpeedsAreHuman) {
  for (Strategy strategy : {Strategy::Along, Strategy::Across, Strategy::Mixed}) {
    TraceOptions o = clean(strategy, 21, 60.0);
    const GeneratedTrace t = generate_trace(o);
    int strokes = 0;
    for (const Segment& s : t.motion.segments()) {
      if (s.kind != SegmentKind::Stroke) continue;
      ++strokes;
      EXPECT_GE(s.peak_speed_px_s, 50.0 * kPxPerMm);
      EXPECT_LE(s.peak_speed_px_s, 400.0 * kPxPerMm);
      // The realised peak is the planned one within the path's curvature.
      double peak = 0.0;
      for (int i = 0; i <= 200; ++i) {
        const TrueState st = t.motion.at(s.t_start_s + s.duration_s * i / 200.0);
        peak = std::max(peak, std::hypot(st.velocity.x, st.velocity.y));
      }
      EXPECT_NEAR(peak, s.peak_speed_px_s, 0.25 * s.peak_speed_px_s);
    }
    EXPECT_GT(strokes, 20) << to_string(strategy);
  }
}

TEST(TraceGenerator, StaysOnTheScreen) {
  for (Strategy strategy : {Strategy::Along, Strategy::Across, Strategy::Mixed}) {
    TraceOptions o = clean(strategy, 33, 120.0);
    o.motion.lifts = 5;
    for (const TraceSample& s : generate_trace(o).samples) {
      if (!s.touch) continue;
      EXPECT_GE(s.x_true, 0.0);
      EXPECT_LE(s.x_true, 799.0);
      EXPECT_GE(s.y_true, 0.0);
      EXPECT_LE(s.y_true, 479.0);
    }
  }
}

TEST(TraceGenerator, AlongStrategyFollowsThePaths) {
  TraceOptions o = clean(Strategy::Along, 4, 30.0);
  o.motion.paths = PathChoice::Bottom;
  const GeneratedTrace t = generate_trace(o);
  for (const TraceSample& s : t.samples) {
    if (!s.touch) continue;
    EXPECT_LE(std::fabs(s.y_true - path_y(s.x_true, 200.0)), 25.0) << s.t_us;
  }
}

TEST(TraceGenerator, RestsAndLifts) {
  TraceOptions o = clean(Strategy::Mixed, 9, 30.0);
  o.motion.rests = 3;
  o.motion.lifts = 2;
  const GeneratedTrace t = generate_trace(o);
  int rests = 0, lifts = 0;
  for (const Segment& s : t.motion.segments()) {
    if (s.kind == SegmentKind::Hold && s.rest) {
      ++rests;
      EXPECT_GE(s.duration_s, 0.6);
      EXPECT_LE(s.duration_s, 2.0);
    }
    if (s.kind == SegmentKind::Lifted) ++lifts;
  }
  EXPECT_EQ(rests, 3);
  EXPECT_EQ(lifts, 2);
  // One touch = 0 report per lift and one at the end; a touch-down after each lift.
  EXPECT_EQ(t.events[static_cast<int>(SampleEvent::LiftReport)], 3);
  EXPECT_EQ(t.events[static_cast<int>(SampleEvent::TouchDown)], 3);
  for (size_t i = 0; i < t.samples.size(); ++i) {
    const TraceSample& s = t.samples[i];
    if (s.event != SampleEvent::LiftReport) continue;
    EXPECT_FALSE(s.touch);
    EXPECT_TRUE(std::isnan(s.x_true));
    if (i + 1 < t.samples.size()) {
      EXPECT_EQ(t.samples[i + 1].event, SampleEvent::TouchDown);
      EXPECT_GE(t.samples[i + 1].t_us - s.t_us, 150000u - 5000u);  // lifted for at least 0.15 s
    }
  }
}

TEST(TraceGenerator, ATraceNeverEndsInTheAir) {
  // More lifts than strokes fit: the last event handled is a lift, after
  // which the finger lands and makes one more stroke, in either strategy.
  for (Strategy strategy : {Strategy::Along, Strategy::Across}) {
    for (uint64_t seed = 1; seed <= 4; ++seed) {
      TraceOptions o = clean(strategy, seed, 1.0);
      o.motion.lifts = 12;
      const GeneratedTrace t = generate_trace(o);
      EXPECT_EQ(t.motion.segments().back().kind, SegmentKind::Stroke) << to_string(strategy) << " seed " << seed;
      EXPECT_EQ(t.events[static_cast<int>(SampleEvent::TouchDown)], 13);
    }
  }
}

class Faults : public ::testing::Test {
 protected:
  static GeneratedTrace make() {
    TraceOptions o = clean(Strategy::Mixed, 13, 30.0);
    o.faults.missing = 4;
    o.faults.late = 4;
    o.faults.jumps = 4;
    o.faults.duplicates = 6;
    o.faults.non_finite = 5;
    o.faults.off_screen = 4;
    return generate_trace(o);
  }
  static int count(const GeneratedTrace& t, SampleEvent e) { return t.events[static_cast<int>(e)]; }
};

TEST_F(Faults, EachRequestedCountIsInserted) {
  const GeneratedTrace t = make();
  EXPECT_EQ(count(t, SampleEvent::AfterGap), 4);
  EXPECT_EQ(count(t, SampleEvent::Late), 4);
  EXPECT_GE(count(t, SampleEvent::Jump), 4);  // runs of 1-3
  EXPECT_LE(count(t, SampleEvent::Jump), 12);
  EXPECT_EQ(count(t, SampleEvent::Duplicate), 2);
  EXPECT_EQ(count(t, SampleEvent::SameTime), 2);
  EXPECT_EQ(count(t, SampleEvent::Earlier), 2);
  EXPECT_EQ(count(t, SampleEvent::NaN) + count(t, SampleEvent::Infinite), 5);
  EXPECT_EQ(count(t, SampleEvent::OffScreen), 4);
}

TEST_F(Faults, EachFaultLooksLikeItsName) {
  const GeneratedTrace t = make();
  for (size_t i = 1; i < t.samples.size(); ++i) {
    const TraceSample& s = t.samples[i];
    const TraceSample& prev = t.samples[i - 1];
    switch (s.event) {
      case SampleEvent::Duplicate:
        EXPECT_EQ(s.t_us, prev.t_us);
        EXPECT_EQ(s.x, prev.x);
        EXPECT_EQ(s.y, prev.y);
        break;
      case SampleEvent::SameTime:
        EXPECT_EQ(s.t_us, prev.t_us);
        EXPECT_TRUE(s.x != prev.x || s.y != prev.y);
        break;
      case SampleEvent::Earlier:
        EXPECT_LT(s.t_us, prev.t_us);
        EXPECT_GT(s.t_us, t.samples[i - 2].t_us);
        break;
      case SampleEvent::AfterGap:
        EXPECT_GE(s.t_us - prev.t_us, 2 * 5000u - 3000u);  // at least one report missing
        EXPECT_LE(s.t_us - prev.t_us, 7 * 5000u + 3000u);  // at most six
        break;
      case SampleEvent::Late:
        // Stamped 1-12 ms after its scan: the interval to the previous report grows.
        EXPECT_GE(s.t_us - prev.t_us, 5000u + 1000u - 3000u);
        EXPECT_LT(t.samples[i + 1].t_us, s.t_us + 5000u + 1500u + 300u);
        EXPECT_GT(t.samples[i + 1].t_us, s.t_us);
        break;
      case SampleEvent::Jump:
        EXPECT_GE(std::hypot(s.x - s.x_true, s.y - s.y_true), 150.0 - 15.0);
        break;
      case SampleEvent::NaN:
        EXPECT_TRUE(std::isnan(s.x) || std::isnan(s.y));
        break;
      case SampleEvent::Infinite:
        EXPECT_TRUE(std::isinf(s.x) || std::isinf(s.y));
        break;
      case SampleEvent::OffScreen:
        EXPECT_TRUE(s.x < -100.0 || s.x > 850.0 || s.y < -100.0 || s.y > 600.0);
        break;
      default:
        break;
    }
  }
}

TEST_F(Faults, NonFiniteAndOffScreenReportsTakeEveryKindInTurn) {
  const GeneratedTrace t = make();  // 5 non-finite, 4 off-screen: each kind once
  int x_nan = 0, y_nan = 0, both_nan = 0, x_inf = 0, y_minus_inf = 0;
  int left = 0, below = 0, no_value = 0, right = 0;
  for (const TraceSample& s : t.samples) {
    if (s.event == SampleEvent::NaN) {
      const bool xn = std::isnan(s.x), yn = std::isnan(s.y);
      x_nan += xn && !yn;
      y_nan += yn && !xn;
      both_nan += xn && yn;
    } else if (s.event == SampleEvent::Infinite) {
      x_inf += std::isinf(s.x) && s.x > 0.0 && std::isfinite(s.y);
      y_minus_inf += std::isinf(s.y) && s.y < 0.0 && std::isfinite(s.x);
    } else if (s.event == SampleEvent::OffScreen) {
      left += s.x == -300.0 && s.y != 900.0;
      below += s.y == 900.0 && s.x != -300.0;
      no_value += s.x == 65535.0 && s.y == 65535.0;
      right += s.x == 880.0;
    }
  }
  EXPECT_EQ(x_nan, 1);
  EXPECT_EQ(y_nan, 1);
  EXPECT_EQ(both_nan, 1);
  EXPECT_EQ(x_inf, 1);
  EXPECT_EQ(y_minus_inf, 1);
  EXPECT_EQ(left, 1);
  EXPECT_EQ(below, 1);
  EXPECT_EQ(no_value, 1);
  EXPECT_EQ(right, 1);
}

TEST_F(Faults, ALateReportsLatencyIncludesHowLateItWasRead) {
  TraceOptions o = clean(Strategy::Mixed, 13, 10.0);
  o.sensor.noise_px = 0.0;
  o.faults.late = 6;
  const GeneratedTrace t = generate_trace(o);
  int late = 0;
  for (const TraceSample& s : t.samples) {
    if (!s.touch) continue;
    if (s.event != SampleEvent::Late) {
      EXPECT_EQ(s.latency_us, 0.0);
      continue;
    }
    ++late;
    EXPECT_GE(s.latency_us, 1000.0);
    EXPECT_LE(s.latency_us, 12000.0);
    // What it reports is the finger at its scan, latency_us before its stamp.
    const TrueState scanned = t.truth_at(s.t_us - static_cast<uint64_t>(s.latency_us));
    EXPECT_NEAR(s.x, scanned.position.x, 1e-9);
    EXPECT_NEAR(s.y, scanned.position.y, 1e-9);
  }
  EXPECT_EQ(late, 6);
}

TEST_F(Faults, InACrowdedTraceEachFaultStillHasOrdinaryReportsAroundIt) {
  // 40 late reads asked of 2 s (~400 reports): far more sites are tried than
  // fit, at both ends of the trace too.
  TraceOptions o = clean(Strategy::Mixed, 5, 2.0);
  o.faults.late = 40;
  const GeneratedTrace t = generate_trace(o);
  const int n = static_cast<int>(t.samples.size());
  int late = 0;
  for (int i = 0; i < n; ++i) {
    if (t.samples[static_cast<size_t>(i)].event != SampleEvent::Late) continue;
    ++late;
    // 8 ordinary reports before it; after it 8, less the up to 3 its late
    // stamp supersedes.
    ASSERT_GE(i, 8);
    ASSERT_LT(i + 5, n);
    for (int k = i - 8; k <= i + 5; ++k) {
      if (k == i) continue;
      EXPECT_EQ(t.samples[static_cast<size_t>(k)].event, SampleEvent::Normal) << "row " << k;
    }
  }
  EXPECT_GE(late, 10);
}

TEST_F(Faults, WithoutAFastStrokeTheClockWrapsAtTheMiddleReport) {
  TraceOptions o = clean(Strategy::Along, 17, 10.0);
  o.motion.speed_min_mm_s = 10.0;  // peaks of 50-100 px/s: never the 200 px/s a wrap looks for
  o.motion.speed_max_mm_s = 20.0;
  o.faults.wrap = true;
  const GeneratedTrace t = generate_trace(o);
  EXPECT_EQ(t.samples[t.samples.size() / 2].t_us, kWrap);
}

TEST_F(Faults, ClockWrapsBetweenTwoReportsInMidStroke) {
  TraceOptions o = clean(Strategy::Along, 17, 10.0);
  o.faults.wrap = true;
  const GeneratedTrace t = generate_trace(o);
  EXPECT_LT(t.samples.front().t_us, kWrap);
  EXPECT_GT(t.end_us(), kWrap);
  int crossings = 0;
  for (size_t i = 1; i < t.samples.size(); ++i) {
    const TraceSample& a = t.samples[i - 1];
    const TraceSample& b = t.samples[i];
    if (a.t_us < kWrap && b.t_us >= kWrap) {
      ++crossings;
      EXPECT_NE(b.t_us, kWrap);  // strictly between two reports
      const TrueState s = t.truth_at(kWrap);
      EXPECT_GT(std::hypot(s.velocity.x, s.velocity.y), 200.0);
      // Near the middle of the trace.
      EXPECT_NEAR(static_cast<double>(i) / static_cast<double>(t.samples.size()), 0.5, 0.2);
    }
  }
  EXPECT_EQ(crossings, 1);
}

TEST(TraceGenerator, LatencyShiftsWhatTheSensorSees) {
  TraceOptions o = clean(Strategy::Across, 6, 5.0);
  o.sensor.noise_px = 0.0;
  o.sensor.latency_us = 8000.0;
  const GeneratedTrace t = generate_trace(o);
  for (const TraceSample& s : t.samples) {
    if (!s.touch || s.t_us < t.start_us + 8000) continue;
    const TrueState seen = t.truth_at(s.t_us - 8000);
    if (!seen.touching) continue;
    EXPECT_NEAR(s.x, seen.position.x, 1e-9);
    EXPECT_NEAR(s.y, seen.position.y, 1e-9);
  }
}

}  // namespace
}  // namespace ff::tracegen
