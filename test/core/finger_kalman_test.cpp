// The tracker's Kalman filter (finger_kalman.hpp), its hand-expanded float
// covariance algebra, against a textbook Kalman filter written here with
// whole matrices in double: F P F^T + Q, K = P H^T / S, P - K H P. The
// tremor's step comes independently too: its transition from the matrix
// exponential's series, its noise by integrating the continuous model
// (Van Loan's integral, Simpson's rule), not from the stationary identity the
// core uses.
#include "frictionfield/core/finger_kalman.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "support/random.hpp"

namespace ff {
namespace {

constexpr int kN = 5;  // p, v, e, c, u (one axis)
using Matrix = double[kN][kN];

void multiply(const Matrix a, const Matrix b, Matrix out) {
  for (int i = 0; i < kN; ++i)
    for (int j = 0; j < kN; ++j) {
      out[i][j] = 0.0;
      for (int m = 0; m < kN; ++m) out[i][j] += a[i][m] * b[m][j];
    }
}

void transpose(const Matrix a, Matrix out) {
  for (int i = 0; i < kN; ++i)
    for (int j = 0; j < kN; ++j) out[i][j] = a[j][i];
}

// The tremor's continuous model x' = A x + (0, n), n white of intensity qc.
struct Oscillator {
  double w2, d, qc;
  // e^(A t) by its series (t small enough for 30 terms: w t < 2).
  void transition(double t, double r[2][2]) const {
    const double a[2][2] = {{0.0, 1.0}, {-w2, -2.0 * d}};
    double term[2][2] = {{1.0, 0.0}, {0.0, 1.0}};
    r[0][0] = r[1][1] = 1.0;
    r[0][1] = r[1][0] = 0.0;
    for (int k = 1; k < 30; ++k) {
      double next[2][2];
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) next[i][j] = (term[i][0] * a[0][j] + term[i][1] * a[1][j]) * t / k;
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) term[i][j] = next[i][j], r[i][j] += next[i][j];
    }
  }
  // Q = integral over s in [0, dt] of e^(A s) (0 0; 0 qc) e^(A s)^T.
  void noise(double dt, double q[2][2]) const {
    constexpr int kSteps = 400;  // Simpson, even
    q[0][0] = q[0][1] = q[1][0] = q[1][1] = 0.0;
    for (int k = 0; k <= kSteps; ++k) {
      double r[2][2];
      transition(dt * k / kSteps, r);
      const double weight = (k == 0 || k == kSteps) ? 1.0 : (k % 2 ? 4.0 : 2.0);
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) q[i][j] += weight * r[i][1] * r[j][1] * qc;
    }
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) q[i][j] *= dt / (3.0 * kSteps);
  }
};

struct Reference {
  double x[kN] = {};
  Matrix P = {};
  double white, wander, accel_q;
  bool has_wander, has_tremor;
  Oscillator tremor;

  void start(double z, double initial_speed, double tremor_variance) {
    x[0] = z;
    for (int i = 1; i < kN; ++i) x[i] = 0.0;
    for (auto& row : P)
      for (double& p : row) p = 0.0;
    P[0][0] = white + wander + tremor_variance;
    P[0][2] = P[2][0] = -wander;
    P[0][3] = P[3][0] = -tremor_variance;
    P[1][1] = initial_speed * initial_speed;
    P[2][2] = wander;
    P[3][3] = tremor_variance;
    P[4][4] = tremor_variance * tremor.w2;
  }
  // phi: the core's decay() (its own test: velocity_noise_test), not exp(),
  // so that what differs here is the algebra.
  void predict(double dt, double phi) {
    Matrix F = {}, Q = {};
    F[0][0] = F[1][1] = 1.0;
    F[0][1] = dt;
    Q[0][0] = accel_q * dt * dt * dt / 3.0;
    Q[0][1] = Q[1][0] = accel_q * dt * dt / 2.0;
    Q[1][1] = accel_q * dt;
    if (has_wander) {
      F[2][2] = phi;
      Q[2][2] = wander * (1.0 - phi * phi);
    }
    if (has_tremor) {
      double r[2][2], q[2][2];
      tremor.transition(dt, r);
      tremor.noise(dt, q);
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) F[3 + i][3 + j] = r[i][j], Q[3 + i][3 + j] = q[i][j];
    }
    double next[kN] = {};
    for (int i = 0; i < kN; ++i)
      for (int j = 0; j < kN; ++j) next[i] += F[i][j] * x[j];
    for (int i = 0; i < kN; ++i) x[i] = next[i];
    Matrix FP, Ft, FPFt;
    multiply(F, P, FP);
    transpose(F, Ft);
    multiply(FP, Ft, FPFt);
    for (int i = 0; i < kN; ++i)
      for (int j = 0; j < kN; ++j) P[i][j] = FPFt[i][j] + Q[i][j];
  }
  // The finger's variances times w, the wander's up to 100 times its
  // stationary variance at most, the tremor's own left alone.
  void widen(double w) {
    const double wander_factor = has_wander ? std::clamp(100.0 * wander / P[2][2], 1.0, w) : w;
    const double f[kN] = {w, w, wander_factor, 1.0, 1.0};
    for (int i = 0; i < kN; ++i)
      for (int j = 0; j < kN; ++j) P[i][j] *= std::sqrt(f[i] * f[j]);
  }
  void update(double z) {
    const double H[kN] = {1.0, 0.0, has_wander ? 1.0 : 0.0, has_tremor ? 1.0 : 0.0, 0.0};
    double PHt[kN] = {}, S = white, innovation = z;
    for (int i = 0; i < kN; ++i) {
      for (int j = 0; j < kN; ++j) PHt[i] += P[i][j] * H[j];
      innovation -= H[i] * x[i];
    }
    for (int i = 0; i < kN; ++i) S += H[i] * PHt[i];
    for (int i = 0; i < kN; ++i) x[i] += PHt[i] / S * innovation;
    for (int i = 0; i < kN; ++i)
      for (int j = 0; j < kN; ++j) P[i][j] -= PHt[i] * PHt[j] / S;
  }
};

struct Case {
  const char* name;
  float correlated_px, tremor_px;
  float tremor_hz = 0.0f;  // measured; 0: not (the model at 10 Hz)
};

class FingerKalmanAgainstReference : public ::testing::TestWithParam<Case> {};

TEST_P(FingerKalmanAgainstReference, StatesAndCovariancesAgree) {
  const Case& c = GetParam();
  SensorProfile sensor;
  sensor.white_noise_px = 0.8f;
  sensor.correlated_noise_px = c.correlated_px;
  sensor.correlation_time_ms = c.correlated_px > 0.0f ? 30.0f : 0.0f;
  sensor.tremor_px = c.tremor_px;
  sensor.tremor_hz = c.tremor_hz;
  const ReportNoise noise = ReportNoise::with_tremor(sensor);
  const float q = 45.0f * 45.0f;

  Reference ref;  // the x axis; ref_y (below) the y axis
  ref.white = 0.8 * 0.8;
  ref.wander = static_cast<double>(c.correlated_px) * static_cast<double>(c.correlated_px);
  ref.accel_q = static_cast<double>(q);
  ref.has_wander = c.correlated_px > 0.0f;
  ref.has_tremor = c.tremor_px > 0.0f;
  // Damped over 150 ms, at the measured frequency or at 10 Hz.
  const double w = 2.0 * M_PI * (c.tremor_hz > 0.0f ? static_cast<double>(c.tremor_hz) : 10.0);
  const double d = 1.0 / 0.15, s = 0.5 * static_cast<double>(c.tremor_px * c.tremor_px);
  ref.tremor = {w * w, d, 4.0 * d * w * w * s};  // stationary variance qc / (4 d w^2) = s
  Reference ref_y = ref;

  // A stroke at 200 Hz with jitter, a lost report, a trembling finger, noise.
  support::Random rng(11, support::Stream::Noise);
  FingerKalman k;
  double t = 0.0;
  auto finger = [&](double at) {
    const double stroke = at < 0.3 ? 0.0 : 300.0 * std::min(1.0, (at - 0.3) / 0.6);
    return 100.0 + stroke + static_cast<double>(c.tremor_px) * std::sin(2.0 * M_PI * 9.3 * at + 0.4) +
           0.8 * rng.gaussian();
  };
  // y: the same finger's other axis, a slower stroke the other way.
  auto finger_y = [&](double at) {
    const double stroke = at < 0.5 ? 0.0 : -120.0 * std::min(1.0, (at - 0.5) / 0.7);
    return 200.0 + stroke + static_cast<double>(c.tremor_px) * std::cos(2.0 * M_PI * 9.3 * at) +
           0.8 * rng.gaussian();
  };
  const double z0 = finger(t), z0_y = finger_y(t);
  k.start({static_cast<float>(z0), static_cast<float>(z0_y)}, noise, 1000.0f);
  ref.start(z0, 1000.0, ref.has_tremor ? s : 0.0);
  ref_y.start(z0_y, 1000.0, ref.has_tremor ? s : 0.0);
  for (int i = 1; i < 300; ++i) {
    const double dt = (i == 150 ? 0.010 : 0.005) + 150e-6 * rng.gaussian();
    t += dt;
    const double z = finger(t), z_y = finger_y(t);
    const double phi = static_cast<double>(noise.correlation(static_cast<float>(dt)));
    k.predict(static_cast<float>(dt), q, noise);
    ref.predict(dt, phi);
    ref_y.predict(dt, phi);
    if (i % 37 == 0) {  // a change of motion now and then
      k.widen(8.0f, noise);
      ref.widen(8.0);
      ref_y.widen(8.0);
    }
    k.update({static_cast<float>(z), static_cast<float>(z_y)}, k.inverse_innovation(noise));
    ref.update(z);
    ref_y.update(z_y);
    ASSERT_EQ(k.tremor, ref.has_tremor);
    const double got[kN] = {k.p.x, k.v.x, k.e.x, k.c.x, k.u.x};
    const double got_y[kN] = {k.p.y, k.v.y, k.e.y, k.c.y, k.u.y};
    const double scale[kN] = {1.0, 30.0, 0.1, 0.1, 5.0};  // px, px/s: what a tenth of a percent is measured against
    for (int j = 0; j < kN; ++j) {
      ASSERT_NEAR(got[j], ref.x[j], 1e-3 * (scale[j] + std::fabs(ref.x[j]))) << c.name << " report " << i << " state " << j;
      ASSERT_NEAR(got_y[j], ref_y.x[j], 1e-3 * (scale[j] + std::fabs(ref_y.x[j])))
          << c.name << " report " << i << " y state " << j;
    }
    const double cov[kN][kN] = {{k.P00, k.P01, k.P02, k.P03, k.P04},
                                {k.P01, k.P11, k.P12, k.P13, k.P14},
                                {k.P02, k.P12, k.P22, k.P23, k.P24},
                                {k.P03, k.P13, k.P23, k.P33, k.P34},
                                {k.P04, k.P14, k.P24, k.P34, k.P44}};
    for (int a = 0; a < kN; ++a)
      for (int b = a; b < kN; ++b) {
        const double tolerance = 2e-3 * std::sqrt(ref.P[a][a] * ref.P[b][b]) + 1e-9;
        ASSERT_NEAR(cov[a][b], ref.P[a][b], tolerance) << c.name << " report " << i << " P" << a << b;
      }
  }
  // The tremor state has learnt the tremor: its rate swings as w times its displacement.
  if (ref.has_tremor) {
    EXPECT_GT(std::fabs(k.c.x) + std::fabs(k.u.x) / static_cast<float>(w), 0.1f * c.tremor_px);
  }
}

INSTANTIATE_TEST_SUITE_P(Noise, FingerKalmanAgainstReference,
                         ::testing::Values(Case{"white", 0.0f, 0.0f}, Case{"wander", 1.5f, 0.0f},
                                           Case{"tremor", 0.0f, 1.2f}, Case{"wander_and_tremor", 1.5f, 1.2f},
                                           Case{"measured_tremor", 1.5f, 1.2f, 9.3f}),
                         [](const ::testing::TestParamInfo<Case>& info) { return std::string(info.param.name); });

// Widened, the wander's variance stops at 100 times its stationary value
// (here 4 px^2: at most 400), its covariances by the square roots of the
// factors; the finger's variances take the whole factor.
TEST(FingerKalman, TheWanderIsWidenedUpTo100TimesItsStationaryVarianceAtMost) {
  SensorProfile wandering;
  wandering.white_noise_px = 0.5f;
  wandering.correlated_noise_px = 2.0f;
  wandering.correlation_time_ms = 5000.0f;
  const ReportNoise n = ReportNoise::with_tremor(wandering);
  FingerKalman k;
  k.start({0.0f, 0.0f}, n, 100.0f);
  k.P00 = 3.0f, k.P01 = 1.0f, k.P11 = 50.0f, k.P02 = -2.0f, k.P12 = 0.5f, k.P22 = 2.0f;
  k.widen(10.0f, n);  // 20 of at most 400: the whole factor
  EXPECT_FLOAT_EQ(k.P22, 20.0f);
  EXPECT_FLOAT_EQ(k.P02, -20.0f);
  EXPECT_FLOAT_EQ(k.P12, 5.0f);
  k.widen(100.0f, n);  // 2,000 would be over 400: the wander's factor is 20, sqrt(100 x 20) its covariances'
  EXPECT_FLOAT_EQ(k.P22, 400.0f);
  EXPECT_NEAR(k.P02, -20.0f * std::sqrt(2000.0f), 1e-3f);
  EXPECT_NEAR(k.P12, 5.0f * std::sqrt(2000.0f), 1e-4f);
  EXPECT_FLOAT_EQ(k.P00, 3000.0f);
  EXPECT_FLOAT_EQ(k.P01, 1000.0f);
  EXPECT_FLOAT_EQ(k.P11, 50000.0f);
  k.widen(100.0f, n);  // at the cap: the wander stays
  EXPECT_FLOAT_EQ(k.P22, 400.0f);
  EXPECT_NEAR(k.P02, -200.0f * std::sqrt(2000.0f), 1e-2f);
  EXPECT_FLOAT_EQ(k.P00, 300000.0f);
}

// Every field of the filter, for comparing two of them exactly.
std::vector<float> fields_of(const FingerKalman& k) {
  return {k.p.x,  k.p.y,  k.v.x,  k.v.y,  k.e.x,  k.e.y,  k.c.x,  k.c.y,  k.u.x,  k.u.y,
          k.P00,  k.P01,  k.P02,  k.P11,  k.P12,  k.P22,  k.P03,  k.P04,  k.P13,  k.P14,
          k.P23,  k.P24,  k.P33,  k.P34,  k.P44,  k.wander ? 1.0f : 0.0f, k.tremor ? 1.0f : 0.0f};
}

// The tracker starts its filters again at every new touch: whatever the last
// touch left (its wander, its tremor's phase, their covariances) must go.
TEST(FingerKalman, StartedAgainItIsAFreshFilter) {
  SensorProfile trembling;
  trembling.white_noise_px = 0.8f;
  trembling.correlated_noise_px = 1.5f;
  trembling.correlation_time_ms = 30.0f;
  trembling.tremor_px = 1.2f;
  SensorProfile white;
  white.white_noise_px = 0.8f;
  for (const SensorProfile& next : {trembling, white}) {
    const ReportNoise used = ReportNoise::with_tremor(trembling), fresh_noise = ReportNoise::with_tremor(next);
    FingerKalman k;
    k.start({10.0f, 20.0f}, used, 1000.0f);
    support::Random rng(5, support::Stream::Noise);
    for (int i = 1; i < 40; ++i) {  // a stroke that leaves every state and covariance non-zero
      k.predict(0.005f, 2025.0f, used);
      if (i % 9 == 0) k.widen(8.0f, used);
      const Vec2 z{10.0f + 2.0f * i + 0.8f * static_cast<float>(rng.gaussian()),
                   20.0f - 1.0f * i + 0.8f * static_cast<float>(rng.gaussian())};
      k.update(z, k.inverse_innovation(used));
    }
    for (float f : {k.e.x, k.c.x, k.u.x, k.P04, k.P13, k.P14, k.P23, k.P24, k.P34, k.P12}) ASSERT_NE(f, 0.0f);

    k.start({50.0f, 60.0f}, fresh_noise, 700.0f);
    FingerKalman fresh;
    fresh.start({50.0f, 60.0f}, fresh_noise, 700.0f);
    EXPECT_EQ(fields_of(k), fields_of(fresh)) << "restarted with wander " << next.correlated_noise_px;
  }
}

TEST(TremorBand, MeasuredOrPhysiological) {
  SensorProfile sensor;
  sensor.tremor_px = 1.0f;
  const TremorBand unmeasured = TremorBand::of(sensor);
  EXPECT_EQ(unmeasured.centre_hz - unmeasured.half_width_hz, 8.0f);  // physiological tremor's 8-12 Hz
  EXPECT_EQ(unmeasured.centre_hz + unmeasured.half_width_hz, 12.0f);
  sensor.tremor_hz = 6.5f;
  const TremorBand measured = TremorBand::of(sensor);
  EXPECT_EQ(measured.centre_hz - measured.half_width_hz, 5.0f);
  EXPECT_EQ(measured.centre_hz + measured.half_width_hz, 8.0f);
  // The model resonates at the measured frequency: w^2 = (2 pi 6.5)^2, as broadly as ever (150 ms).
  EXPECT_NEAR(ReportNoise::with_tremor(sensor).tremor.omega2, std::pow(2.0 * M_PI * 6.5, 2.0), 1e-3 * 1668.0);
  EXPECT_FLOAT_EQ(ReportNoise::with_tremor(sensor).tremor.damping, 1.0f / 0.15f);
}

TEST(TremorModel, NoTremorNoState) {
  SensorProfile sensor;
  EXPECT_EQ(ReportNoise::with_tremor(sensor).tremor.variance, 0.0f);
  sensor.tremor_px = 1.0f;
  EXPECT_EQ(ReportNoise::of(sensor).tremor.variance, 0.0f);  // the position filter's: none
  EXPECT_FLOAT_EQ(ReportNoise::with_tremor(sensor).tremor.variance, 0.5f);  // a sinusoid of peak 1
  // A size no validation let through is no tremor either, never a tremor
  // of size squared (-1 px) or NaN, nor a floor under the white noise.
  for (float bad : {-1.0f, NAN, -INFINITY}) {
    sensor.tremor_px = bad;
    const ReportNoise n = ReportNoise::with_tremor(sensor);
    EXPECT_EQ(n.tremor.variance, 0.0f) << bad;
    EXPECT_EQ(n.white_variance, ReportNoise::of(sensor).white_variance) << bad;
  }
}

}  // namespace
}  // namespace ff
