// The sensor effects of issue 14, each against its closed form: correlated
// noise (variance and autocorrelation of a Gauss-Markov process), stamp
// latency, report rate and period jitter, drift. (All off, the bundled
// traces are still reproduced bit for bit: trace_writer_test.cpp.)
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "support/models/sensor_model.hpp"
#include "support/models/trace_classes.hpp"

namespace ff::tracegen {
namespace {

// A long, quiet trace: no white noise, no quantisation, no jitter, so that an
// effect switched on is all that separates a report from the truth.
TraceOptions quiet(double duration_s, double rate_hz = 200.0) {
  TraceOptions o;
  o.seed = 21;
  o.motion.strategy = Strategy::Mixed;
  o.motion.duration_s = duration_s;
  o.sensor.rate_hz = rate_hz;
  o.sensor.jitter_us = 0.0;
  o.sensor.noise_px = 0.0;
  o.sensor.quantum_px = 0.0;
  return o;
}

std::vector<double> touch_errors_x(const GeneratedTrace& t) {
  std::vector<double> e;
  for (const TraceSample& s : t.samples)
    if (s.touch) e.push_back(s.x - s.x_true);
  return e;
}

// The stamp intervals between reports of the same touch (us).
std::vector<double> touch_intervals(const GeneratedTrace& t) {
  std::vector<double> intervals;
  for (size_t i = 1; i < t.samples.size(); ++i)
    if (t.samples[i].touch && t.samples[i - 1].touch)
      intervals.push_back(static_cast<double>(t.samples[i].t_us - t.samples[i - 1].t_us));
  return intervals;
}

double mean_of(const std::vector<double>& v) {
  double sum = 0.0;
  for (double x : v) sum += x;
  return sum / static_cast<double>(v.size());
}

double variance_of(const std::vector<double>& v) {
  const double m = mean_of(v);
  double sum = 0.0;
  for (double x : v) sum += (x - m) * (x - m);
  return sum / static_cast<double>(v.size() - 1);
}

// Sample autocorrelation at `lag` (biased estimator, as usual).
double autocorrelation(const std::vector<double>& v, size_t lag) {
  const double m = mean_of(v);
  double num = 0.0, den = 0.0;
  for (size_t i = 0; i < v.size(); ++i) {
    den += (v[i] - m) * (v[i] - m);
    if (i + lag < v.size()) num += (v[i] - m) * (v[i + lag] - m);
  }
  return num / den;
}

TEST(CorrelatedNoise, VarianceAndAutocorrelationAreThoseOfAFirstOrderGaussMarkovProcess) {
  // E[e(t) e(t + dt)] = sigma^2 exp(-dt / tau): at 200 Hz, lag 1 is 5 ms.
  constexpr double kSigma = 1.5, kTau = 0.03;
  TraceOptions o = quiet(300.0);
  o.sensor.correlated_noise_px = kSigma;
  o.sensor.correlated_noise_tau_s = kTau;
  const std::vector<double> e = touch_errors_x(generate_trace(o));
  ASSERT_GT(e.size(), 55000u);
  // ~60000 reports, but correlated: ~60000 (1 - rho) / (1 + rho) ~ 5000
  // effective ones, so the variance is known to ~2 % (1 sigma); 10 % is 5 sigma.
  EXPECT_NEAR(variance_of(e), kSigma * kSigma, 0.10 * kSigma * kSigma);
  EXPECT_NEAR(autocorrelation(e, 1), std::exp(-0.005 / kTau), 0.02);
  EXPECT_NEAR(autocorrelation(e, 10), std::exp(-0.050 / kTau), 0.05);
  EXPECT_NEAR(mean_of(e), 0.0, 0.15);
}

TEST(CorrelatedNoise, CorrelationTimeIsInSecondsNotReportsAtAnyRate) {
  // At 1 kHz lag 1 is 1 ms: exp(-1/30) = 0.967, lag 5 the same 5 ms as lag 1 at 200 Hz.
  TraceOptions o = quiet(60.0, 1000.0);
  o.sensor.correlated_noise_px = 2.0;
  o.sensor.correlated_noise_tau_s = 0.03;
  const std::vector<double> e = touch_errors_x(generate_trace(o));
  EXPECT_NEAR(autocorrelation(e, 1), std::exp(-1.0 / 30.0), 0.01);
  EXPECT_NEAR(autocorrelation(e, 5), std::exp(-5.0 / 30.0), 0.02);
}

TEST(CorrelatedNoise, AddsToTheWhiteNoiseWithoutChangingItsDraws) {
  // Own random stream: the reports with correlated noise minus those without
  // are exactly the correlated process (no quantisation).
  TraceOptions o = quiet(300.0);
  o.sensor.noise_px = 1.0;
  const GeneratedTrace white = generate_trace(o);
  o.sensor.correlated_noise_px = 1.5;
  const GeneratedTrace both = generate_trace(o);
  ASSERT_EQ(white.samples.size(), both.samples.size());
  std::vector<double> difference;
  for (size_t i = 0; i < white.samples.size(); ++i) {
    ASSERT_EQ(white.samples[i].t_us, both.samples[i].t_us);
    if (white.samples[i].touch) difference.push_back(both.samples[i].x - white.samples[i].x);
  }
  EXPECT_NEAR(variance_of(difference), 1.5 * 1.5, 0.10 * 1.5 * 1.5);
  EXPECT_NEAR(autocorrelation(difference, 1), std::exp(-0.005 / 0.03), 0.02);
}

TEST(Latency, EachReportIsTheFingerItsLatencyBeforeTheStamp) {
  TraceOptions o = quiet(20.0);
  o.sensor.latency_us = 1000.0;
  o.sensor.latency_spread_us = 2000.0;
  const GeneratedTrace t = generate_trace(o);
  std::vector<double> latencies;
  for (const TraceSample& s : t.samples) {
    if (!s.touch) continue;
    ASSERT_GE(s.latency_us, 1000.0);
    ASSERT_LE(s.latency_us, 3000.0);
    latencies.push_back(s.latency_us);
    const double scan_s = (static_cast<double>(s.t_us - t.start_us) - s.latency_us) * 1e-6;
    const TrueState then = t.motion.at(scan_s);
    ASSERT_NEAR(s.x, then.position.x, 1e-9) << s.t_us;
    ASSERT_NEAR(s.y, then.position.y, 1e-9) << s.t_us;
  }
  // Uniform on [1, 3] ms: mean 2 ms, standard deviation 2 / sqrt(12) ms.
  ASSERT_GT(latencies.size(), 3000u);
  EXPECT_NEAR(mean_of(latencies), 2000.0, 4.0 * 577.0 / std::sqrt(static_cast<double>(latencies.size())));
  EXPECT_NEAR(std::sqrt(variance_of(latencies)), 2000.0 / std::sqrt(12.0), 20.0);
}

TEST(Latency, AReportScannedBeforeTheFingerLandedIsNotMade) {
  // The stamp said the finger was down, the scan 1-3 ms earlier fell in the
  // lift: the report showed the finger where it had left the screen (up to
  // 599 px from it; 37 of 41 touch-downs at 1 kHz).
  TraceOptions o = quiet(60.0);
  o.sensor.rate_hz = 1000.0;
  o.sensor.latency_us = 1000.0;
  o.sensor.latency_spread_us = 2000.0;
  o.motion.lifts = 20;
  const GeneratedTrace t = generate_trace(o);
  size_t touch_downs = 0;
  for (const TraceSample& s : t.samples) {
    if (!s.touch) continue;
    const double scan_s = (static_cast<double>(s.t_us - t.start_us) - s.latency_us) * 1e-6;
    ASSERT_TRUE(t.motion.at(scan_s).touching) << s.t_us;
    touch_downs += s.event == SampleEvent::TouchDown;
  }
  EXPECT_EQ(touch_downs, 21u);  // the first landing and one after each lift
}

TEST(Latency, AFixedLatencyIsTheSameForEveryReport) {
  TraceOptions o = quiet(5.0);
  o.sensor.latency_us = 2000.0;
  for (const TraceSample& s : generate_trace(o).samples) {
    if (s.touch) {
      ASSERT_EQ(s.latency_us, 2000.0);
    }
  }
}

TEST(ReportRate, MeanIntervalIsThePeriodAtEveryRateAndPeriodJitterIsItsSpread) {
  for (double rate : {100.0, 200.0, 1000.0}) {
    const double period_us = 1e6 / rate;
    TraceOptions o = quiet(60.0, rate);
    o.sensor.period_jitter_us = 0.02 * period_us;
    const std::vector<double> intervals = touch_intervals(generate_trace(o));
    ASSERT_GT(intervals.size(), static_cast<size_t>(50.0 * rate)) << rate;
    // Zero-mean, independent interval errors: the mean is the period within
    // sigma / sqrt(n) (4 of those, plus the rounding of the stamps to 1 us).
    const double sigma = 0.02 * period_us;
    const double n = static_cast<double>(intervals.size());
    EXPECT_NEAR(mean_of(intervals), period_us, 4.0 * sigma / std::sqrt(n) + 0.5) << rate;
    // Stamps are whole microseconds: rounding adds 1/6 us^2 to the variance of an interval.
    EXPECT_NEAR(std::sqrt(variance_of(intervals)), std::sqrt(sigma * sigma + 1.0 / 6.0), 0.05 * sigma + 0.1) << rate;
  }
}

TEST(ReportRate, TheNominalJitterIsTheSpreadOfTheClippedIntervals) {
  // At 1 kHz the 150 us stamp jitter is clipped at 300 us = 2 sigma. By hand:
  // a clamped N(0,1) at 2 has variance erf(√2) - 2 √(2/π) e^-2 + 4 erfc(√2)
  // = 0.954500 - 0.215963 + 0.182001 = 0.920538; with 20 us of period jitter
  // (not clipped at 15 sigma) an interval spreads sqrt(2 * 150² * 0.920538 + 20²)
  // = 204.51 us, not the unclipped 213.07.
  TraceOptions o = quiet(60.0, 1000.0);
  o.sensor.jitter_us = 150.0;
  o.sensor.period_jitter_us = 20.0;
  const double nominal = nominal_profile(o).jitter_us;
  EXPECT_NEAR(nominal, 204.51, 0.01);
  // And the generator's own intervals (independently: measured, 1/6 us² of rounding aside).
  const std::vector<double> intervals = touch_intervals(generate_trace(o));
  ASSERT_GT(intervals.size(), 50000u);
  EXPECT_NEAR(std::sqrt(variance_of(intervals) - 1.0 / 6.0), nominal, 0.015 * nominal);
}

TEST(ReportRate, StampJitterAloneKeepsTheGrid) {
  // jitter_us scatters stamps around n * period: the n-th stamp never wanders further than the clip.
  TraceOptions o = quiet(60.0);
  o.sensor.jitter_us = 150.0;
  const GeneratedTrace t = generate_trace(o);
  for (const TraceSample& s : t.samples) {
    if (!s.touch) continue;
    const double rel = static_cast<double>(s.t_us - t.start_us);
    const double off_grid = rel - 5000.0 * std::round(rel / 5000.0);
    ASSERT_LE(std::fabs(off_grid), 0.3 * 5000.0 + 1.0);
  }
}

TEST(Drift, StepsBetweenReportsAreThoseOfASlowGaussMarkovProcess) {
  // Var(e(t + dt) - e(t)) = 2 sigma^2 (1 - exp(-dt / tau)).
  constexpr double kSigma = 2.0, kTau = 10.0;
  TraceOptions o = quiet(300.0);
  o.sensor.drift_px = kSigma;
  o.sensor.drift_tau_s = kTau;
  const std::vector<double> e = touch_errors_x(generate_trace(o));
  std::vector<double> steps;
  for (size_t i = 1; i < e.size(); ++i) steps.push_back(e[i] - e[i - 1]);
  const double expected = kSigma * std::sqrt(2.0 * (1.0 - std::exp(-0.005 / kTau)));
  EXPECT_NEAR(std::sqrt(variance_of(steps)), expected, 0.03 * expected);
  for (double x : e) ASSERT_LT(std::fabs(x), 6.0 * kSigma);
}

TEST(SensorEffects, LeaveTheMotionAndTheTimingAlone) {
  TraceOptions o = quiet(20.0);
  o.sensor.jitter_us = 150.0;
  const GeneratedTrace plain = generate_trace(o);
  o.sensor.correlated_noise_px = 1.0;
  o.sensor.drift_px = 1.0;
  o.sensor.latency_spread_us = 1000.0;
  o.tremor.amplitude_px = 1.0;
  const GeneratedTrace rich = generate_trace(o);
  ASSERT_EQ(plain.samples.size(), rich.samples.size());
  for (size_t i = 0; i < plain.samples.size(); ++i) {
    ASSERT_EQ(plain.samples[i].t_us, rich.samples[i].t_us);
    ASSERT_TRUE(plain.samples[i].x_true == rich.samples[i].x_true ||
                (std::isnan(plain.samples[i].x_true) && std::isnan(rich.samples[i].x_true)));
  }
}

}  // namespace
}  // namespace ff::tracegen
