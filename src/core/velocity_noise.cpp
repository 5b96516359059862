#include "frictionfield/core/velocity_noise.hpp"

#include <cmath>
#include <complex>

#include "frictionfield/core/tick_math.hpp"

namespace ff {

namespace {

constexpr int kMaxIterations = 20000;  // reports until the filter has settled
constexpr float kSettled = 1e-6f;      // relative change of a gain per report
constexpr int kDoublings = 40;         // 2^40 reports: decades at 5 kHz
constexpr float kInitialSpeedPxS = 1000.0f;

bool settled(float now, float before) { return std::fabs(now - before) <= kSettled * std::fabs(now); }

using Complex = std::complex<float>;

Complex det3(const Complex a[3][3]) {
  return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
         a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
}

}  // namespace

SteadyStateFilter steady_state_filter(float q, const ReportNoise& noise, const SensorProfile& sensor) {
  SteadyStateFilter f;
  f.interval_s = 1.0f / sensor.report_rate_hz;
  f.wander_correlation = noise.correlation(f.interval_s);
  FingerKalman k;
  k.start({}, noise, kInitialSpeedPxS);
  for (int i = 0; i < kMaxIterations; ++i) {
    k.predict(f.interval_s, q, noise);
    const float inverse_s = k.inverse_innovation(noise);
    const FingerKalman::Gains g = k.gains(inverse_s);
    k.update({}, inverse_s);
    const bool done = settled(g.position, f.gains.position) && settled(g.velocity, f.gains.velocity);
    f.gains = g;
    f.velocity_variance = k.P11;
    if (done) break;
  }
  return f;
}

float resting_velocity_variance(const SteadyStateFilter& f, const SensorProfile& sensor) {
  const float T = f.interval_s, phi_f = f.wander_correlation;
  const float k0 = f.gains.position, k1 = f.gains.velocity, k2 = f.gains.wander;
  const float white = sensor.white_noise_px;
  const bool wander = sensor.correlated_noise_px > 0.0f && sensor.correlation_time_ms > 0.0f;
  const float phi = wander ? std::exp(-T / (1e-3f * sensor.correlation_time_ms)) : 0.0f;  // the sensor's, exact
  const float g = wander ? sensor.correlated_noise_px * std::sqrt(1.0f - phi * phi) : 0.0f;
  // One report at rest, state (p^, v^, e^ the filter's; e the sensor's wander):
  // e' = phi e + g n1, z = e' + white n2, then the filter's predict and update
  // with its settled gains: innovation = z - (p^ + T v^) - phi_f e^.
  constexpr int N = 4;
  const float A[N][N] = {{1.0f - k0, (1.0f - k0) * T, -k0 * phi_f, k0 * phi},
                         {-k1, 1.0f - k1 * T, -k1 * phi_f, k1 * phi},
                         {-k2, -k2 * T, (1.0f - k2) * phi_f, k2 * phi},
                         {0.0f, 0.0f, 0.0f, phi}};
  const float B[N][2] = {{k0 * g, k0 * white}, {k1 * g, k1 * white}, {k2 * g, k2 * white}, {g, 0.0f}};
  // The stationary covariance S = sum_i A^i Q A^iT by doubling (S += A S A^T,
  // A = A^2): 2^k reports after k steps, so that poles near 1 (a slow wander
  // at a high rate, an oscillating filter) converge as surely as fast ones.
  float S[N][N], An[N][N];
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) S[i][j] = B[i][0] * B[j][0] + B[i][1] * B[j][1], An[i][j] = A[i][j];
  for (int step = 0; step < kDoublings; ++step) {
    float AS[N][N], next[N][N], square[N][N];
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
    // with (I - M / z) X = K at z = e^(i w T), M the filter's own transition
    // (its rows of A above), solved by Cramer's rule.
    const float M[3][3] = {{A[0][0], A[0][1], A[0][2]}, {A[1][0], A[1][1], A[1][2]}, {A[2][0], A[2][1], A[2][2]}};
    const float K[3] = {k0, k1, k2};
    float worst = 0.0f;
    for (float hz = 8.0f; hz <= 12.0f; hz += 1.0f) {
      const SinCos w = sincos_turns(hz * T);
      const Complex inverse_z(w.cos, -w.sin);
      Complex a[3][3], b[3][3];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) a[i][j] = Complex(i == j ? 1.0f : 0.0f) - M[i][j] * inverse_z;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) b[i][j] = j == 1 ? Complex(K[i]) : a[i][j];
      const float gain2 = std::norm(det3(b) / det3(a));
      if (gain2 > worst) worst = gain2;
    }
    variance += 0.5f * sensor.tremor_px * sensor.tremor_px * worst;
  }
  return variance;
}

}  // namespace ff
