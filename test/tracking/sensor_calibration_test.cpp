// ff-track-bench --calibrate's estimator on generated resting fingers: each
// estimate against the generator's own parameters (closed forms: a stamp
// jitter s gives intervals of sigma s sqrt 2, a quantum q adds q^2 / 12 to the
// white variance), never against the estimator's earlier output.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>
#include <string>
#include <vector>

#include "sensor_calibration.hpp"
#include "support/models/sensor_model.hpp"
#include "support/models/trace_classes.hpp"
#include "support/random.hpp"

namespace ff::bench {
namespace {

using tracegen::TraceOptions;

TraceOptions resting(double duration_s, uint64_t seed = 5) {
  TraceOptions o;
  o.seed = seed;
  o.motion.rest_only = true;
  o.motion.duration_s = duration_s;
  return o;
}

TraceOptions resting_class(const char* name, double duration_s) {
  TraceOptions o = resting(duration_s);
  tracegen::find_trace_class(name)->apply(o);
  o.motion.rest_only = true;
  o.motion.duration_s = duration_s;
  return o;
}

std::vector<host::TraceRow> rows_of(const TraceOptions& o) {
  std::vector<host::TraceRow> rows;
  for (const tracegen::TraceSample& s : tracegen::generate_trace(o).samples)
    rows.push_back({s.t_us, static_cast<float>(s.x), static_cast<float>(s.y), s.touch});
  return rows;
}

Calibration calibrate(const TraceOptions& o, uint32_t latency_us = 0) {
  Calibration c;
  std::string error;
  EXPECT_TRUE(calibrate_from_rest(rows_of(o), CalibrationOptions{}, latency_us, c, error)) << error;
  return c;
}

std::string refusal(const std::vector<host::TraceRow>& rows) {
  Calibration c;
  std::string error;
  EXPECT_FALSE(calibrate_from_rest(rows, CalibrationOptions{}, 0, c, error));
  return error;
}

void expect_within(double estimate, double truth, double relative, const char* what) {
  EXPECT_NEAR(estimate, truth, relative * truth) << what;
}

// White noise only: correlated and tremor come out as nothing.
void expect_white_only(const Calibration& c, double sigma_px) {
  expect_within(c.profile.white_noise_px, sigma_px, 0.10, "white");
  EXPECT_EQ(c.profile.correlated_noise_px, 0.0f);
  EXPECT_EQ(c.profile.correlation_time_ms, 0.0f);
  EXPECT_EQ(c.profile.tremor_px, 0.0f);
  EXPECT_TRUE(is_valid(c.profile));
}

const double kSqrt2 = std::sqrt(2.0);

TEST(SensorCalibration, WhiteNoiseOfOnePixelAt200Hz) {
  const Calibration c = calibrate(resting(10.0));  // defaults: 200 Hz, 150 us stamp jitter, 1 px
  expect_white_only(c, 1.0);
  expect_within(c.profile.report_rate_hz, 200.0, 0.01, "rate");
  expect_within(c.profile.jitter_us, 150.0 * kSqrt2, 0.10, "jitter: two independent stamp errors per interval");
  EXPECT_EQ(c.reports, 2001u);
  EXPECT_NEAR(c.duration_s, 10.0, 0.01);
}

TEST(SensorCalibration, WhiteNoiseOfTwoAndAHalfPixels) {
  TraceOptions o = resting(10.0);
  o.sensor.noise_px = 2.5;
  expect_white_only(calibrate(o), 2.5);
}

TEST(SensorCalibration, QuantisationCountsAsWhiteNoise) {
  // 0.25 px noise rounded to the zForce's 0.5 px: 0.25^2 + 0.5^2 / 12 -> 0.289 px, 15 % above the noise alone.
  TraceOptions o = resting(20.0);
  o.sensor.noise_px = 0.25;
  o.sensor.quantum_px = tracegen::kZForceQuantumPx;
  expect_white_only(calibrate(o), std::sqrt(0.25 * 0.25 + 0.5 * 0.5 / 12.0));
}

TEST(SensorCalibration, CorrelatedNoiseClassOnTwentySeconds) {
  // 1.5 px Gauss-Markov (tau 30 ms) + 0.5 px white, 0.5 px quantum.
  const Calibration c = calibrate(resting_class("correlated-noise", 20.0));
  expect_within(c.profile.correlated_noise_px, 1.5, 0.20, "correlated");
  expect_within(c.profile.correlation_time_ms, 30.0, 0.25, "tau");
  expect_within(c.profile.white_noise_px, std::sqrt(0.5 * 0.5 + 0.5 * 0.5 / 12.0), 0.25, "white");
  EXPECT_EQ(c.profile.tremor_px, 0.0f);
  EXPECT_EQ(c.profile.tremor_hz, 0.0f);  // none found: not measured
}

TEST(SensorCalibration, TremorAtAKnownFrequency) {
  for (double hz : {10.0, 7.4}) {  // inside and outside physiological tremor's 8-12 Hz
    TraceOptions o = resting_class("tremor", 10.0);  // 1.5 px peak, 1 px white, 0.5 px quantum
    o.tremor.min_hz = o.tremor.max_hz = hz;
    const Calibration c = calibrate(o);
    expect_within(c.profile.tremor_px, 1.5, 0.10, "tremor");
    EXPECT_NEAR(c.tremor_hz, hz, 0.1);
    EXPECT_NEAR(c.profile.tremor_hz, hz, 0.1);  // the tracker is told it
  }
  TraceOptions o = resting_class("tremor", 10.0);
  o.tremor.min_hz = o.tremor.max_hz = 10.0;
  const Calibration c = calibrate(o);
  expect_within(c.profile.white_noise_px, std::sqrt(1.0 + 0.5 * 0.5 / 12.0), 0.10, "white");
  EXPECT_EQ(c.profile.correlated_noise_px, 0.0f);
}

// 1 px white noise at another rate: the rate, the jitter (a stamp jitter s gives s sqrt 2) and the noise.
void expect_white_at(double rate_hz, double stamp_jitter_us) {
  TraceOptions o = resting(10.0);
  o.sensor.rate_hz = rate_hz;
  o.sensor.jitter_us = stamp_jitter_us;
  const Calibration c = calibrate(o);
  expect_white_only(c, 1.0);
  expect_within(c.profile.report_rate_hz, rate_hz, 0.01, "rate");
  expect_within(c.profile.jitter_us, stamp_jitter_us * kSqrt2, 0.10, "jitter");
}

TEST(SensorCalibration, OneKilohertz) { expect_white_at(1000.0, 50.0); }  // 50 us: well inside the 30 % clip

TEST(SensorCalibration, OneHundredHertz) { expect_white_at(100.0, 150.0); }

TEST(SensorCalibration, PeriodJitterIsTheIntervalSigma) {
  TraceOptions o = resting(10.0);
  o.sensor.jitter_us = 0.0;
  o.sensor.period_jitter_us = 100.0;
  const Calibration c = calibrate(o);
  expect_within(c.profile.jitter_us, 100.0, 0.10, "jitter");
  expect_within(c.profile.report_rate_hz, 200.0, 0.01, "rate");
}

TEST(SensorCalibration, MissedReportsAreNotJitter) {
  TraceOptions o = resting(10.0);
  o.faults.missing = 6;  // gaps of 1-6 reports
  const Calibration c = calibrate(o);
  EXPECT_EQ(c.dropped_intervals, 6u);
  expect_within(c.profile.report_rate_hz, 200.0, 0.01, "rate");
  expect_within(c.profile.jitter_us, 150.0 * kSqrt2, 0.10, "jitter");
}

TEST(SensorCalibration, SensorFaultsAreSkippedLikeTheTraceReaderDoes) {
  TraceOptions o = resting(10.0);
  o.faults.non_finite = 3;
  o.faults.off_screen = 3;
  expect_white_only(calibrate(o), 1.0);
}

// A report from a second finger or a glitch (>= 150 px away) read as 19 px
// of correlated noise with three of them in 10 s. They are left out of the
// noise, counted (the generator's own labels say how many), and their stamps
// still count for the timing; the duplicates and the off-screen rows the
// trace reader would skip are counted too.
TEST(SensorCalibration, GlitchesAreLeftOutOfTheNoiseAndEverySkipIsCounted) {
  TraceOptions o = resting(10.0);
  o.faults.jumps = 3;
  o.faults.off_screen = 2;
  o.faults.duplicates = 3;  // an exact copy, one at the same time, one earlier: the last two not after
  const tracegen::GeneratedTrace trace = tracegen::generate_trace(o);
  const int jumps = trace.events[static_cast<int>(tracegen::SampleEvent::Jump)];
  ASSERT_GE(jumps, 3);
  const Calibration c = calibrate(o);
  EXPECT_EQ(c.glitches, static_cast<size_t>(jumps));
  EXPECT_GT(c.glitch_threshold_px, 20.0);
  EXPECT_LT(c.glitch_threshold_px, 150.0);
  EXPECT_EQ(c.off_screen, 2u);
  EXPECT_EQ(c.not_after, 3u);
  expect_white_only(c, 1.0);
  expect_within(c.profile.jitter_us, 150.0 * kSqrt2, 0.10, "jitter");
  // Without glitches none is found: the threshold leaves a resting finger's
  // wander and its noise alone, also a drift's.
  TraceOptions drifting = resting(10.0);
  drifting.sensor.drift_px = 3.0;
  drifting.sensor.noise_px = 2.5;
  EXPECT_EQ(calibrate(drifting).glitches, 0u);
}

// A sensor far noisier along one axis: its reports are not glitches. (Pooled
// over both axes, the robust sigma of a noiseless x and a y of 8 px sigma is
// near 0, and the 2.5-sigma tail of y, ~1 % of the reports, was left out.)
TEST(SensorCalibration, ANoisierAxisIsNotTakenForGlitches) {
  std::vector<host::TraceRow> rows;
  support::Random noise(11);
  for (uint64_t i = 0; i < 2000; ++i)
    rows.push_back({1'000'000 + 5000 * i, 400.0f, static_cast<float>(240.0 + 8.0 * noise.gaussian()), true});
  Calibration c;
  std::string error;
  ASSERT_TRUE(calibrate_from_rest(rows, CalibrationOptions{}, 0, c, error)) << error;
  EXPECT_EQ(c.glitches, 0u);
  // A glitch on the quiet axis is still one: 150 px is far beyond x's wander.
  rows[1000].x += 150.0f;
  ASSERT_TRUE(calibrate_from_rest(rows, CalibrationOptions{}, 0, c, error)) << error;
  EXPECT_EQ(c.glitches, 1u);
}

TEST(SensorCalibration, RestsAtSeveralPlacesAreRunsOfTheirOwn) {
  // Two rests 200 px apart with a lift between: each run loses its own mean.
  std::vector<host::TraceRow> rows = rows_of(resting(5.0, 1));
  const uint64_t later = rows.back().t_us + 300'000;
  for (host::TraceRow r : rows_of(resting(5.0, 2))) {
    r.t_us += later - 10'000'000;
    r.x += 200.0f;
    rows.push_back(r);
  }
  Calibration c;
  std::string error;
  ASSERT_TRUE(calibrate_from_rest(rows, CalibrationOptions{}, 0, c, error)) << error;
  EXPECT_EQ(c.runs, 2u);
  EXPECT_LT(c.range_px, 1.0);
  expect_white_only(c, 1.0);
}

TEST(SensorCalibration, EveryEffectAt200Hz) {
  // realistic-200hz: 1 px tremor, 1.5 px / 30 ms wander, 0.5 px white and quantum, 2 px drift (tau 10 s),
  // 150 us stamp jitter and 2 % = 100 us period jitter.
  const Calibration c = calibrate(resting_class("realistic-200hz", 20.0), 2000);
  expect_within(c.profile.tremor_px, 1.0, 0.15, "tremor");
  expect_within(c.profile.correlated_noise_px, 1.5, 0.20, "correlated");
  expect_within(c.profile.correlation_time_ms, 30.0, 0.35, "tau");  // 25-39 ms over 8 seeds
  expect_within(c.profile.jitter_us, std::sqrt(2.0 * 150.0 * 150.0 + 100.0 * 100.0), 0.10, "jitter");
  EXPECT_EQ(c.profile.latency_us, 2000u);  // as given: a recording cannot show it
  EXPECT_TRUE(is_valid(c.profile));
}

TEST(SensorCalibration, RefusesTooShortAMovingFingerAndNothing) {
  EXPECT_NE(refusal(rows_of(resting(0.5))).find("only 0.50 s"), std::string::npos);
  std::vector<host::TraceRow> few = rows_of(resting(10.0));
  few.resize(50);
  EXPECT_NE(refusal(few).find("only 50 usable touch reports"), std::string::npos);
  TraceOptions moving = resting(10.0);
  moving.motion.rest_only = false;
  EXPECT_NE(refusal(rows_of(moving)).find("not resting"), std::string::npos);
  EXPECT_NE(refusal({}).find("only 0 usable"), std::string::npos);
  std::vector<host::TraceRow> fast;  // 200 reports 100 us apart: 10 kHz
  for (uint64_t i = 0; i < 20000; ++i) fast.push_back({i * 100, 400.0f, 240.0f + 0.1f * static_cast<float>(i % 3), true});
  EXPECT_NE(refusal(fast).find("not a sensor"), std::string::npos);
  TraceOptions noisy = resting(10.0);
  noisy.sensor.noise_px = 60.0;  // beyond SensorProfileLimits::kMaxNoisePx; at 1 kHz its 1 s mean still rests
  noisy.sensor.rate_hz = 1000.0;
  EXPECT_NE(refusal(rows_of(noisy)).find("outside the profile's limits"), std::string::npos);
}

TEST(SensorCalibration, ReportsThatNeverVaryAreRefusedForWhatTheyAre) {
  std::vector<host::TraceRow> rows;
  for (uint64_t i = 0; i < 2000; ++i) rows.push_back({1'000'000 + 5000 * i, 400.0f, 240.0f, true});
  EXPECT_EQ(refusal(rows).rfind("the reports do not vary at all (0 px of noise)", 0), 0u) << refusal(rows);
}

TEST(SensorCalibration, RefusalsSayWhatWasLeftOut) {
  std::vector<host::TraceRow> faulty = {{1'000'000, 400.0f, 240.0f, true}};
  for (int i = 0; i < 60; ++i) faulty.push_back({1'000'000 + 5'000u * (i + 1u), NAN, 240.0f, true});
  for (int i = 0; i < 40; ++i) faulty.push_back({1'000'000, 401.0f, 240.0f, true});
  EXPECT_NE(refusal(faulty).find("only 1 usable touch report (at least 100"), std::string::npos) << refusal(faulty);
  EXPECT_NE(refusal(faulty).find("left out: 60 off the screen or not finite, 40 stamped at or before the one before"),
            std::string::npos)
      << refusal(faulty);
  std::vector<host::TraceRow> sparse;  // 150 reports a second apart: each its own run
  for (uint64_t i = 0; i < 150; ++i) sparse.push_back({i * 1'000'000, 400.0f, 240.0f, true});
  EXPECT_NE(refusal(sparse).find("no two of its 150 touch reports lie within 0.25 s"), std::string::npos)
      << refusal(sparse);
}

// A resting finger written out by hand, not by the generator: a report at
// each stamp, white noise of sigma px on both axes, and `x_extra(t)` on x.
std::vector<host::TraceRow> by_hand(const std::vector<uint64_t>& stamps_us, double sigma_px,
                                    const std::function<double(double)>& x_extra = nullptr, uint64_t seed = 3) {
  support::Random rng(seed, support::Stream::Noise);
  std::vector<host::TraceRow> rows;
  for (const uint64_t t : stamps_us) {
    const double t_s = static_cast<double>(t - stamps_us.front()) * 1e-6;
    const double x = 400.0 + sigma_px * rng.gaussian() + (x_extra ? x_extra(t_s) : 0.0);
    rows.push_back({t, static_cast<float>(x), static_cast<float>(240.0 + sigma_px * rng.gaussian()), true});
  }
  return rows;
}

std::vector<uint64_t> every_us(uint64_t period_us, size_t reports) {
  std::vector<uint64_t> stamps(reports);
  for (size_t i = 0; i < reports; ++i) stamps[i] = 1'000'000 + i * period_us;
  return stamps;
}

Calibration calibrate_rows(const std::vector<host::TraceRow>& rows, const CalibrationOptions& options = {}) {
  Calibration c;
  std::string error;
  EXPECT_TRUE(calibrate_from_rest(rows, options, 0, c, error)) << error;
  return c;
}

TEST(SensorCalibration, AStampBeforeTheFirstIsLeftOutNotTakenForTheFarFuture) {
  // Unsigned, a stamp before the first row was 2^64 us ahead (5.8e5 years,
  // which a double resolves to 4 ms): the first two rows swapped got the
  // whole recording refused, and a clock stepped back 6 s mid-way was taken
  // for 205.6 reports/s with 411 us of jitter.
  std::vector<host::TraceRow> swapped = by_hand(every_us(5000, 2000), 1.0);
  std::swap(swapped[0], swapped[1]);
  const Calibration a = calibrate_rows(swapped);
  EXPECT_NEAR(a.profile.report_rate_hz, 200.0, 0.01);
  EXPECT_EQ(a.profile.jitter_us, 0.0f);  // the other 1999 stamps are 5 ms apart exactly
  std::vector<host::TraceRow> stepped = by_hand(every_us(5000, 2000), 1.0);
  for (size_t i = 1000; i < stepped.size(); ++i) stepped[i].t_us -= 6'000'000;  // 1 s before the first stamp
  const Calibration b = calibrate_rows(stepped);
  EXPECT_NEAR(b.profile.report_rate_hz, 200.0, 0.01);
  EXPECT_EQ(b.profile.jitter_us, 0.0f);
}

TEST(SensorCalibration, ASteadyClockHasNoJitterAtAll) {
  const Calibration c = calibrate_rows(by_hand(every_us(5000, 2001), 1.0));
  EXPECT_EQ(c.profile.jitter_us, 0.0f);  // not a rounding error's 1e-10, which --profile-out would print
  EXPECT_EQ(c.profile.report_rate_hz, 200.0f);
}

TEST(SensorCalibration, TheMedianIntervalIsTheMiddleOneOrTheMeanOfTheMiddleTwo) {
  // Intervals of 4000 + k us, every k in 0..n-1 once, in a shuffled order:
  // their median is 4000 + (n - 1) / 2 exactly, whatever the order.
  for (const uint64_t n : {2001u, 2000u}) {
    std::vector<uint64_t> intervals(n);
    std::iota(intervals.begin(), intervals.end(), uint64_t{4000});
    support::Random rng(n, support::Stream::Single);
    for (size_t i = n - 1; i > 0; --i) std::swap(intervals[i], intervals[rng.next() % (i + 1)]);
    std::vector<uint64_t> stamps = {1'000'000};
    for (const uint64_t dt : intervals) stamps.push_back(stamps.back() + dt);
    const Calibration c = calibrate_rows(by_hand(stamps, 1.0));
    EXPECT_NEAR(c.median_interval_us, 4000.0 + (static_cast<double>(n) - 1.0) / 2.0, 1e-3) << n << " intervals";
    EXPECT_EQ(c.dropped_intervals, 0u);  // 4000-6000 us: within 0.5-1.5 x the median
  }
}

TEST(SensorCalibration, ASlowDriftIsNotNoise) {
  // 1 px white at 200 Hz with the resting point drifting 1.5 px/s (15 px over
  // the 10 s, inside the 20 px a rest may wander): the 1 s centred mean takes
  // a straight drift out wholly.
  const Calibration c = calibrate_rows(by_hand(every_us(5000, 2001), 1.0, [](double t) { return 1.5 * t; }));
  expect_white_only(c, 1.0);
  // The mean's range: at either end its window is half a second, centred
  // 0.25 s in, so 1.5 px/s x (9.75 - 0.25) s, and the noise of 100 reports' means.
  EXPECT_NEAR(c.range_px, 1.5 * 9.5, 0.5);
}

TEST(SensorCalibration, ATremorIsFoundOnEitherAxisInEitherPhase) {
  // 1 px at 9 Hz on one axis only, as a sine or a cosine of the report time:
  // the spectrum needs each of its four sums (x and y, cosine and sine).
  for (const bool on_x : {true, false}) {
    for (const double phase : {0.0, 0.5 * M_PI}) {
      std::vector<host::TraceRow> rows = by_hand(every_us(5000, 2001), 0.3);
      for (host::TraceRow& r : rows) {
        const double t_s = static_cast<double>(r.t_us) * 1e-6;  // the calibration's own clock starts at the first report
        (on_x ? r.x : r.y) += static_cast<float>(std::sin(2.0 * M_PI * 9.0 * (t_s - 1.0) + phase));
      }
      const Calibration c = calibrate_rows(rows);
      // 9 Hz is on the search's 0.02 Hz grid (6 - 1.5 Hz + 225 steps): a tone there peaks
      // there; with one of the four sums missing, the peak moves off it.
      EXPECT_NEAR(c.tremor_hz, 9.0, 0.005) << (on_x ? "x" : "y") << " phase " << phase;
      // The profile's tremor is per axis, averaged over the two: a peak of 1
      // px on one axis is a variance of 1/2 there and 1/4 on average, a peak of 1/sqrt(2).
      EXPECT_NEAR(c.profile.tremor_px, 1.0 / std::sqrt(2.0), 0.07) << (on_x ? "x" : "y") << " phase " << phase;
      EXPECT_GT(c.tremor_peak_ratio, CalibrationOptions{}.tremor_peak_ratio);
    }
  }
}

TEST(SensorCalibration, TheFitsDiagnosticsOnWhiteNoise) {
  // 1 px white at 200 Hz, 10 s.
  const Calibration c = calibrate_rows(by_hand(every_us(5000, 2001), 1.0));
  EXPECT_EQ(c.lag_bins, 40u);  // 200 ms of lags, one 5 ms interval each
  // C(0) of the residual: 1 px^2 less the 1 s mean's share (1 / 200 of it).
  EXPECT_NEAR(c.total_noise_px, 1.0, 0.05);
  // The parts add up to C(0) (the header's decomposition): white^2 + slow here.
  EXPECT_NEAR(std::pow(double{c.profile.white_noise_px}, 2) + c.slow_px2, std::pow(c.total_noise_px, 2), 1e-5);
  // Each lag bin's estimate of a covariance that is 0 scatters by C(0) / sqrt(pairs):
  // x and y over ~2000 reports, 4000 pairs a bin.
  EXPECT_GT(c.fit_rms_px2, 0.5 / std::sqrt(4000.0));
  EXPECT_LT(c.fit_rms_px2, 2.0 / std::sqrt(4000.0));
  // Without a tremor the strongest peak still has a ratio (2.4-9.7 on generated white noise).
  EXPECT_GT(c.tremor_peak_ratio, 1.0);
  EXPECT_LT(c.tremor_peak_ratio, CalibrationOptions{}.tremor_peak_ratio);
}

TEST(SensorCalibration, NoFitHasANegativeVariance) {
  // Told to take the exponential whenever it fits at all better, white noise
  // still gets no correlated part below 0: the fit's lags scatter both ways.
  CalibrationOptions eager;
  eager.correlated_improvement = -1.0;
  for (uint64_t seed = 1; seed <= 6; ++seed) {
    const Calibration c = calibrate_rows(by_hand(every_us(5000, 2001), 1.0, nullptr, seed), eager);
    EXPECT_GE(c.profile.correlated_noise_px, 0.0f) << seed;
    EXPECT_TRUE(is_valid(c.profile)) << seed;
  }
}

TEST(SensorCalibration, TooFewLagsForTheExponentialClaimNoCorrelation) {
  // Two lag bins (10 ms of lags at 200 Hz) fit the exponential and its
  // constant exactly; its three parameters are more than two bins can show.
  CalibrationOptions short_lags;
  short_lags.max_lag_s = 0.010;
  const Calibration c = calibrate_rows(rows_of(resting_class("correlated-noise", 10.0)), short_lags);
  EXPECT_EQ(c.lag_bins, 2u);
  EXPECT_EQ(c.profile.correlated_noise_px, 0.0f);
  EXPECT_TRUE(is_valid(c.profile));
}

}  // namespace
}  // namespace ff::bench
