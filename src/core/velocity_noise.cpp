#include "frictionfield/core/velocity_noise.hpp"

#include <cmath>

#include "frictionfield/core/complex_solve.hpp"
#include "frictionfield/core/tick_math.hpp"

namespace ff {

namespace {

constexpr int kMaxIterations = 20000;  // reports until the filter has settled
constexpr float kSettled = 1e-6f;      // relative change of a gain per report
constexpr int kDoublings = 40;         // 2^40 reports: decades at 5 kHz
constexpr float kInitialSpeedPxS = 1000.0f;

bool settled(float now, float before) { return std::fabs(now - before) <= kSettled * std::fabs(now); }

}  // namespace

SteadyStateFilter steady_state_filter(float q, const ReportNoise& noise, const SensorProfile& sensor) {
  SteadyStateFilter f;
  f.interval_s = 1.0f / sensor.report_rate_hz;
  f.wander_correlation = noise.correlation(f.interval_s);
  f.tremor = noise.tremor.variance > 0.0f;
  if (f.tremor) f.tremor_step = noise.tremor.step(f.interval_s);
  FingerKalman k;
  k.start({}, noise, kInitialSpeedPxS);
  for (int i = 0; i < kMaxIterations; ++i) {
    k.predict(f.interval_s, q, noise);
    const float inverse_s = k.inverse_innovation(noise);
    const FingerKalman::Gains g = k.gains(inverse_s);
    k.update({}, inverse_s);
    const bool done = settled(g.position, f.gains.position) && settled(g.velocity, f.gains.velocity) &&
                      settled(g.tremor, f.gains.tremor) && settled(g.tremor_rate, f.gains.tremor_rate);
    f.gains = g;
    f.velocity_variance = k.P11;
    if (done) break;
  }
  return f;
}

float resting_velocity_variance(const SteadyStateFilter& f, const SensorProfile& sensor) {
  const float T = f.interval_s, phi_f = f.wander_correlation;
  const float white = sensor.white_noise_px;
  const bool wander = sensor.correlated_noise_px > 0.0f && sensor.correlation_time_ms > 0.0f;
  const float phi = wander ? std::exp(-T / (1e-3f * sensor.correlation_time_ms)) : 0.0f;  // the sensor's, exact
  const float g = wander ? sensor.correlated_noise_px * std::sqrt(1.0f - phi * phi) : 0.0f;
  // The filter's states (p, v, e[, c, u]) over one report at rest: predicted
  // by F, then updated with its settled gains K: x' = M x + K z, M = (I - K H) F,
  // H = [1 0 1 1 0]. The sensor: e_s' = phi e_s + g n1, z = e_s' + white n2.
  const int n = f.tremor ? 5 : 3, N = n + 1;
  const TremorModel::Step& r = f.tremor_step;
  float F[5][5] = {{1.0f, T}, {0.0f, 1.0f}, {0.0f, 0.0f, phi_f}, {0.0f, 0.0f, 0.0f, r.r00, r.r01},
                   {0.0f, 0.0f, 0.0f, r.r10, r.r11}};
  const float K[5] = {f.gains.position, f.gains.velocity, f.gains.wander, f.gains.tremor, f.gains.tremor_rate};
  float HF[5], M[5][5];
  for (int j = 0; j < n; ++j) HF[j] = F[0][j] + F[2][j] + (f.tremor ? F[3][j] : 0.0f);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) M[i][j] = F[i][j] - K[i] * HF[j];
  // Filter and sensor wander together: A (N x N), B the two draws per report.
  float A[6][6] = {}, B[6][2] = {};
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) A[i][j] = M[i][j];
    A[i][n] = K[i] * phi;
    B[i][0] = K[i] * g;
    B[i][1] = K[i] * white;
  }
  A[n][n] = phi;
  B[n][0] = g;
  // The stationary covariance S = sum_i A^i Q A^iT by doubling (S += A S A^T,
  // A = A^2): 2^k reports after k steps, so that poles near 1 (a slow wander
  // at a high rate, an oscillating filter) converge as surely as fast ones.
  float S[6][6], An[6][6];
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) S[i][j] = B[i][0] * B[j][0] + B[i][1] * B[j][1], An[i][j] = A[i][j];
  for (int step = 0; step < kDoublings; ++step) {
    float AS[6][6], next[6][6], square[6][6];
    for (int i = 0; i < N; ++i)
      for (int j = 0; j < N; ++j) {
        AS[i][j] = 0.0f;
        square[i][j] = 0.0f;
        for (int m = 0; m < N; ++m) AS[i][j] += An[i][m] * S[m][j], square[i][j] += An[i][m] * An[m][j];
      }
    for (int i = 0; i < N; ++i)
      for (int j = 0; j < N; ++j) {
        next[i][j] = S[i][j];
        for (int m = 0; m < N; ++m) next[i][j] += AS[i][m] * An[j][m];
      }
    for (int i = 0; i < N; ++i)
      for (int j = 0; j < N; ++j) S[i][j] = next[i][j], An[i][j] = square[i][j];
  }
  float variance = S[1][1];
  if (sensor.tremor_px > 0.0f) {
    // A sinusoid of peak a through the filter: velocity variance (a^2 / 2) |H_v|^2,
    // with (I - M / z) X = K at z = e^(i w T).
    const TremorBand band = TremorBand::of(sensor);
    float worst = 0.0f;
    for (int k = -2; k <= 2; ++k) {  // the band's edges, centre and quarters
      const SinCos w = sincos_turns((band.centre_hz + 0.5f * static_cast<float>(k) * band.half_width_hz) * T);
      const ComplexF inverse_z(w.cos, -w.sin);
      ComplexF a[kMaxComplexSolve][kMaxComplexSolve], x[kMaxComplexSolve];
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) a[i][j] = ComplexF(i == j ? 1.0f : 0.0f) - M[i][j] * inverse_z;
        x[i] = ComplexF(K[i]);
      }
      solve_in_place(a, x, n);
      const float gain2 = magnitude2(x[1]);
      if (gain2 > worst) worst = gain2;
    }
    variance += 0.5f * sensor.tremor_px * sensor.tremor_px * worst;
  }
  return variance;
}

}  // namespace ff
