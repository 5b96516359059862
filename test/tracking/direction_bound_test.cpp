// The direction bound's rotation filter against a batch solution written
// out independently, and the bound on generated traces against what it must
// lie under.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "class_report.hpp"
#include "direction_bound.hpp"
#include "lookahead_bound.hpp"
#include "support/models/motion.hpp"
#include "support/models/trace_classes.hpp"
#include "support/random.hpp"

namespace ff::bench {
namespace {

struct RotationReport {
  double t_s, ex, ey, dx, dy;
};

// The rotation's von Mises parameters from all reports at once: with the
// per-axis noise covariance C (wander sigma^2 exp(-|ti - tj| / tau) plus white
// on the diagonal, both axes alike and independent) and c free in the plane,
// the log likelihood is c^T b - c^T Lambda c / 2 with b = Dx^T C^-1 ex +
// Dy^T C^-1 ey, Dx = [dx, -dy], Dy = [dy, dx]; on the unit circle Lambda is
// isotropic, so (kappa cos mu, kappa sin mu) = b. C^-1 by Gauss-Jordan.
void batch_von_mises(const std::vector<RotationReport>& reports, const UnknownNoise& noise, double& kappa, double& mu) {
  const size_t n = reports.size();
  std::vector<double> m(n * 2 * n, 0.0);  // [C | I]
  for (size_t i = 0; i < n; ++i) {
    for (size_t j = 0; j < n; ++j) {
      double c = noise.wander_px * noise.wander_px *
                 (noise.wander_px > 0.0 ? std::exp(-std::fabs(reports[i].t_s - reports[j].t_s) / noise.wander_tau_s) : 0.0);
      if (i == j) c += noise.white_px * noise.white_px;
      m[i * 2 * n + j] = c;
    }
    m[i * 2 * n + n + i] = 1.0;
  }
  for (size_t col = 0; col < n; ++col) {  // C is positive definite: no pivoting needed
    const double pivot = m[col * 2 * n + col];
    for (size_t j = 0; j < 2 * n; ++j) m[col * 2 * n + j] /= pivot;
    for (size_t i = 0; i < n; ++i) {
      if (i == col) continue;
      const double f = m[i * 2 * n + col];
      for (size_t j = 0; j < 2 * n; ++j) m[i * 2 * n + j] -= f * m[col * 2 * n + j];
    }
  }
  double b0 = 0.0, b1 = 0.0;
  for (size_t i = 0; i < n; ++i) {
    for (size_t j = 0; j < n; ++j) {
      const double w = m[i * 2 * n + n + j];  // (C^-1)_ij
      const RotationReport& ri = reports[i];
      const RotationReport& rj = reports[j];
      b0 += w * (ri.dx * rj.ex + ri.dy * rj.ey);
      b1 += w * (-ri.dy * rj.ex + ri.dx * rj.ey);
    }
  }
  kappa = std::hypot(b0, b1);
  mu = std::atan2(b1, b0);
}

// 12 reports at rest (`rest_s`), then a 0.3 s minimum-jerk stroke of 60 px
// turned by `turn` (rad) from the direction the observer is told, every 5 ms
// with 1 ms of jitter; the noise drawn as the filter models it.
std::vector<RotationReport> stroke(double turn, const UnknownNoise& noise, uint64_t seed, double rest_s = 0.06) {
  support::Random rng(seed);
  const double a_dir = 0.4;  // the told direction
  std::vector<RotationReport> out;
  double gx = noise.wander_px * rng.gaussian(), gy = noise.wander_px * rng.gaussian(), t = 0.0;
  for (int k = 0; k < 72; ++k) {
    if (k > 0) {
      const double dt = 0.005 + 0.001 * (rng.uniform() - 0.5);
      const double a = noise.wander_px > 0.0 ? std::exp(-dt / noise.wander_tau_s) : 0.0;
      const double fresh = noise.wander_px * std::sqrt(1.0 - a * a);
      gx = a * gx + fresh * rng.gaussian();
      gy = a * gy + fresh * rng.gaussian();
      t += dt;
    }
    const double s = 60.0 * tracegen::min_jerk(std::clamp((t - rest_s) / 0.3, 0.0, 1.0));
    const double dx = s * std::cos(a_dir), dy = s * std::sin(a_dir);
    const double ex = s * std::cos(a_dir + turn) + gx + noise.white_px * rng.gaussian();
    const double ey = s * std::sin(a_dir + turn) + gy + noise.white_px * rng.gaussian();
    out.push_back({t, ex, ey, dx, dy});
  }
  return out;
}

void expect_filter_matches_batch(StrokeRotation& filter, const UnknownNoise& noise, double turn, double rest_s = 0.06) {
  const std::vector<RotationReport> reports = stroke(turn, noise, 7, rest_s);
  std::vector<RotationReport> seen;
  for (size_t k = 0; k < reports.size(); ++k) {
    if (k > 0) filter.predict(reports[k].t_s - reports[k - 1].t_s);
    filter.update(reports[k].ex, reports[k].ey, reports[k].dx, reports[k].dy);
    seen.push_back(reports[k]);
    double kappa = 0.0, mu = 0.0;
    batch_von_mises(seen, noise, kappa, mu);
    // The filter's prior on c is wide, not flat: it adds 1e-6 to Lambda.
    EXPECT_NEAR(filter.kappa(), kappa, 1e-6 * kappa + 1e-5) << "report " << k;
    if (kappa > 1.0) {
      EXPECT_NEAR(std::remainder(filter.mu() - mu, 2.0 * M_PI), 0.0, 1e-6) << "report " << k;
    }
  }
  // And the stroke told the turn: after 0.3 s of motion the posterior sits on it.
  EXPECT_GT(filter.kappa(), 1000.0);
  EXPECT_NEAR(std::remainder(filter.mu() - turn, 2.0 * M_PI), 0.0, 0.05);
}

TEST(DirectionBound, TheFilterIsTheBatchPosteriorWithWhiteNoise) {
  const UnknownNoise noise{1.0, 0.0, 0.03};
  StrokeRotation filter(noise);
  expect_filter_matches_batch(filter, noise, 0.5);
}

// Without a wander its correlation time means nothing, and may be 0: two
// reports scanned at once (dt 0) stay finite.
TEST(DirectionBound, WhiteNoiseNeedsNoCorrelationTime) {
  const UnknownNoise noise{1.0, 0.0, 0.0};
  StrokeRotation filter(noise);
  filter.update(0.0, 0.0, 0.0, 0.0);
  filter.predict(0.0);
  filter.update(4.0, 0.1, 4.0, 0.0);
  ASSERT_TRUE(std::isfinite(filter.kappa()));
  EXPECT_NEAR(filter.mu(), std::atan2(0.1, 4.0), 0.05);
  // The update's gain: two reports, the second 4 px along the told direction.
  double kappa = 0.0, mu = 0.0;
  batch_von_mises({{0.0, 0.0, 0.0, 0.0, 0.0}, {0.0, 4.0, 0.1, 4.0, 0.0}}, noise, kappa, mu);
  EXPECT_NEAR(filter.kappa(), kappa, 1e-6 * kappa + 1e-5);
}

TEST(DirectionBound, TheFilterIsTheBatchPosteriorWithTheWander) {
  const UnknownNoise noise{0.56, 1.5, 0.03};
  StrokeRotation filter(noise);
  expect_filter_matches_batch(filter, noise, -2.0);
}

// Moving from the first report, before the rest's reports could pin the
// wander down: the filter starts with the wander's stationary spread.
TEST(DirectionBound, TheFilterIsTheBatchPosteriorFromTheFirstReport) {
  const UnknownNoise noise{0.56, 1.5, 0.03};
  StrokeRotation filter(noise);
  expect_filter_matches_batch(filter, noise, 1.1, 0.0);
}

// A new touch forgets the last one: its turn, its wander and their covariances.
TEST(DirectionBound, ATouchDownStartsTheFilterAfresh) {
  const UnknownNoise noise{0.56, 1.5, 0.03};
  StrokeRotation filter(noise);
  for (const RotationReport& r : stroke(2.5, noise, 9, 0.0)) {
    filter.predict(0.005);
    filter.update(r.ex + 4.0, r.ey - 3.0, r.dx, r.dy);  // a wander far from 0 at the lift
  }
  filter.touch_down();
  expect_filter_matches_batch(filter, noise, 1.1, 0.0);
}

TEST(DirectionBound, AtRestTheReportsSayNothingOfTheTurn) {
  const UnknownNoise noise{1.0, 1.5, 0.03};
  StrokeRotation filter(noise);
  for (int k = 0; k < 20; ++k) {
    if (k > 0) filter.predict(0.005);
    filter.update(0.7 * std::sin(k), -0.4 * std::cos(k), 0.0, 0.0);
  }
  EXPECT_LT(filter.kappa(), 1e-9);
  filter.update(5.0, 0.0, 5.0, 0.0);  // one report of motion, along the told direction
  const double first = filter.kappa();
  EXPECT_GT(first, 0.5);
  EXPECT_NEAR(filter.mu(), 0.0, 0.5);
  filter.new_stroke();  // a new stroke forgets the turn
  EXPECT_EQ(filter.kappa(), 0.0);  // not merely small: nothing of the old turn is left
  // Nor is the new turn tied to the wander: a rest after the stroke, however
  // noisy, teaches it nothing.
  for (int k = 0; k < 10; ++k) {
    filter.predict(0.005);
    filter.update(3.0 * std::cos(k), 2.0 - std::sin(k), 0.0, 0.0);
  }
  EXPECT_EQ(filter.kappa(), 0.0);
}

// The observer's anchor, on reports written out: a stroke's reports are its
// path turned about where the finger touched down or last stood still, and
// the observer finds that turn only if it turns about the same point.
struct Observed {
  tracegen::TraceSample sample;
  tracegen::TrueState truth;
};

// `n` reports 5 ms apart from `from` to `to` (still if equal), reported
// turned by `turn` about `pivot`.
void move(std::vector<Observed>& out, tracegen::Point from, tracegen::Point to, int n, double turn,
          tracegen::Point pivot) {
  for (int k = 1; k <= n; ++k) {
    Observed o;
    o.sample.t_us = 1000000 + 5000 * out.size();
    o.sample.touch = true;
    o.truth.touching = true;
    o.truth.position = {from.x + (to.x - from.x) * k / n, from.y + (to.y - from.y) * k / n};
    o.truth.velocity = {(to.x - from.x) / (n * 0.005), (to.y - from.y) / (n * 0.005)};
    const double dx = o.truth.position.x - pivot.x, dy = o.truth.position.y - pivot.y;
    o.sample.x = pivot.x + dx * std::cos(turn) - dy * std::sin(turn);
    o.sample.y = pivot.y + dx * std::sin(turn) + dy * std::cos(turn);
    out.push_back(o);
  }
}

double observed_turn(const std::vector<Observed>& reports) {
  const tracegen::GeneratedTrace no_tremor;
  RotationObserver observer({0.01, 0.0, 0.03}, no_tremor);
  for (size_t k = 0; k < reports.size(); ++k)
    observer.report(reports[k].sample, reports[k].truth, reports[k].sample.t_us,
                    static_cast<double>(reports[k].sample.t_us) * 1e-6, k == 0);
  EXPECT_GT(observer.rotation().kappa(), 1e4);
  return observer.rotation().mu();
}

TEST(DirectionBound, AStrokeTurnsAboutWhereItTouchedDown) {
  std::vector<Observed> reports;
  const tracegen::Point touch{100.0, 80.0};
  // Moving from the first report, which is at `touch` (steps of 2, 0.5 px).
  move(reports, {touch.x - 2.0, touch.y - 0.5}, {touch.x + 38.0, touch.y + 9.5}, 20, 0.5, touch);
  EXPECT_NEAR(observed_turn(reports), 0.5, 1e-3);
}

TEST(DirectionBound, AStrokeTurnsAboutWhereTheFingerLastStoodStill) {
  std::vector<Observed> reports;
  const tracegen::Point touch{100.0, 80.0}, stop{140.0, 80.0};
  move(reports, touch, touch, 5, 0.0, touch);
  move(reports, touch, stop, 20, 0.0, touch);
  move(reports, stop, stop, 5, 0.0, touch);
  move(reports, stop, {stop.x, stop.y + 30.0}, 20, -0.7, stop);
  EXPECT_NEAR(observed_turn(reports), -0.7, 1e-3);
}

TEST(DirectionBound, ThePosteriorMeanIsTheVonMisesAverage) {
  // Against a plain Riemann sum over the whole circle, 2e5 steps (100 per
  // spread at kappa 1e5), with the density's peak divided out.
  const tracegen::TraceClass* white = tracegen::find_trace_class("white-200hz");
  ASSERT_NE(white, nullptr);
  const PreparedCase c = prepare_case(class_cases(*white, 2.0).front());
  int checked = 0;
  for (size_t k = 0; k < c.ticks.size() && checked < 4; k += 97) {
    const TickTruth& tick = c.ticks[k];
    if (!judged_moving(tick.state, 50.0) || std::fabs(tick.heightmap_ideal - 0.5f) < 0.05f) continue;
    ++checked;
    const Vec2 position = to_vec(tick.state.position), direction = true_direction(tick.state);
    for (double kappa : {0.0, 0.5, 3.0, 40.0, 2000.0, 1e5}) {
      for (double mu : {0.0, 0.3, -2.5}) {
        const int n = 200000;
        double sum = 0.0, weights = 0.0;
        for (int j = 0; j < n; ++j) {
          const double phi = 2.0 * M_PI * j / n;
          const double w = std::exp(kappa * (std::cos(phi - mu) - 1.0));
          const double x = static_cast<double>(direction.x), y = static_cast<double>(direction.y);
          const Vec2 turned{static_cast<float>(x * std::cos(phi) - y * std::sin(phi)),
                            static_cast<float>(x * std::sin(phi) + y * std::cos(phi))};
          sum += w * static_cast<double>(c.heightmap->amplitude(position, turned));
          weights += w;
        }
        EXPECT_NEAR(posterior_mean_amplitude(*c.heightmap, position, direction, kappa, mu), sum / weights, 1e-5)
            << "kappa " << kappa << " mu " << mu;
      }
    }
    // A certain heading, however it is told: its own direction's amplitude.
    const Vec2 at_mu{direction.x * std::cos(0.3f) - direction.y * std::sin(0.3f),
                     direction.x * std::sin(0.3f) + direction.y * std::cos(0.3f)};
    for (double kappa : {1e12, static_cast<double>(INFINITY)})
      EXPECT_NEAR(posterior_mean_amplitude(*c.heightmap, position, direction, kappa, 0.3),
                  static_cast<double>(c.heightmap->amplitude(position, at_mu)), 1e-6)
          << kappa;
  }
  EXPECT_EQ(checked, 4);
}

TEST(DirectionBound, UnknownNoiseCountsTheQuantumAsWhite) {
  tracegen::SensorOptions s;
  s.noise_px = 0.5;
  s.quantum_px = 0.5;
  s.correlated_noise_px = 1.5;
  s.correlated_noise_tau_s = 0.045;  // not UnknownNoise's default
  const UnknownNoise n = unknown_noise(s);
  EXPECT_NEAR(n.white_px, std::sqrt(0.25 + 0.25 / 12.0), 1e-12);
  EXPECT_EQ(n.wander_px, 1.5);
  EXPECT_EQ(n.wander_tau_s, 0.045);
}

TEST(DirectionBound, NoCasesNoError) {
  const tracegen::TraceClass* realistic = tracegen::find_trace_class("realistic-200hz");
  ASSERT_NE(realistic, nullptr);
  EXPECT_EQ(class_direction_bound(*realistic, {}, 2.0, kClassMovingSpeedPxS), 0.0);
}

TEST(DirectionBound, WithoutDriftOnlyTheDriftChanges) {
  const tracegen::TraceClass* realistic = tracegen::find_trace_class("realistic-200hz");
  ASSERT_NE(realistic, nullptr);
  const std::vector<TrackCase> with = class_cases(*realistic, 2.0);
  const std::vector<TrackCase> without = without_drift(with);
  ASSERT_GT(with.front().options.sensor.drift_px, 0.0);
  const tracegen::GeneratedTrace a = tracegen::generate_trace(with.front().options);
  const tracegen::GeneratedTrace b = tracegen::generate_trace(without.front().options);
  ASSERT_EQ(a.samples.size(), b.samples.size());
  double largest = 0.0;
  for (size_t k = 0; k < a.samples.size(); ++k) {
    EXPECT_EQ(a.samples[k].t_us, b.samples[k].t_us);
    if (a.samples[k].touch) {  // x_true is NaN while lifted
      EXPECT_EQ(a.samples[k].x_true, b.samples[k].x_true);
    }
    largest = std::max(largest, std::fabs(a.samples[k].x - b.samples[k].x));
  }
  EXPECT_GT(largest, 0.1);  // the drift was there, and is gone
}

TEST(DirectionBound, OnTracesItLiesUnderWhatTrackersReach) {
  const tracegen::TraceClass* white = tracegen::find_trace_class("white-200hz");
  ASSERT_NE(white, nullptr);
  std::vector<PreparedCase> cases;
  for (const TrackCase& c : class_cases(*white, 4.0)) cases.push_back(prepare_case(c));
  const UnknownNoise noise = unknown_noise(cases.front().spec.options.sensor);
  const double bound = direction_bound_heightmap_rms(cases, kClassMovingSpeedPxS, noise);
  EvalOptions options;
  options.moving_speed_px_s = kClassMovingSpeedPxS;
  options.lag = false;
  options.cost = false;
  const double shipping = evaluate(TrackerConfig::recommended(), cases, options).heightmap_rms;
  SmootherOptions cv;
  cv.measurement_noise_px = noise.white_px;
  cv.accel_noise_px2_s3 = 1e3;
  const double anchored =
      lookahead_heightmap_rms(cases, kClassMovingSpeedPxS, cv, 0.0, 0.0, BoundModel::AnchoredAtRest);
  EXPECT_GT(bound, 0.0);
  EXPECT_LT(bound, 0.9 * shipping);
  EXPECT_LT(bound, anchored);
  // Told a quieter sensor than the reports' it is overconfident and worse.
  UnknownNoise told_quiet = noise;
  told_quiet.white_px = 0.01 * noise.white_px;
  EXPECT_GT(direction_bound_heightmap_rms(cases, kClassMovingSpeedPxS, told_quiet), bound);
  // On reports of a hundredth of the noise (no quantum) it is nearly exact:
  // what is left is the first report of each stroke.
  std::vector<PreparedCase> quiet;
  for (TrackCase c : class_cases(*white, 4.0)) {
    c.options.sensor.noise_px = 0.01;
    c.options.sensor.quantum_px = 0.0;
    quiet.push_back(prepare_case(c));
  }
  EXPECT_LT(direction_bound_heightmap_rms(quiet, kClassMovingSpeedPxS, unknown_noise(quiet.front().spec.options.sensor)),
            0.3 * bound);
}

}  // namespace
}  // namespace ff::bench
