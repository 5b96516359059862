#include "direction_bound.hpp"

#include <algorithm>
#include <cmath>

#include "class_report.hpp"
#include "observer_replay.hpp"

namespace ff::bench {

namespace {

constexpr double kFlatVariance = 1e6;  // of each component of c, whose size is 1: no prior
constexpr int kQuadraturePoints = 61;
constexpr double kQuadratureSigmas = 6.0;  // of the von Mises' spread, each side of its mean
constexpr double kSharpKappa = 1e8;        // spread below 0.1 mrad: the mean direction alone

using Matrix4 = std::array<double, 16>;

double& at(Matrix4& m, int r, int c) { return m[static_cast<size_t>(r * 4 + c)]; }
double at(const Matrix4& m, int r, int c) { return m[static_cast<size_t>(r * 4 + c)]; }

}  // namespace

double posterior_mean_amplitude(const ScenePlan& heightmap, Vec2 position, Vec2 direction, double kappa, double mu) {
  const auto turned = [&](double phi) {
    const double c = std::cos(phi), s = std::sin(phi);
    const double x = static_cast<double>(direction.x), y = static_cast<double>(direction.y);
    return static_cast<double>(
        heightmap.amplitude(position, Vec2{static_cast<float>(x * c - y * s), static_cast<float>(x * s + y * c)}));
  };
  if (kappa >= kSharpKappa) return turned(mu);
  const double half = kappa > 0.0 ? std::min(M_PI, kQuadratureSigmas / std::sqrt(kappa)) : M_PI;
  const bool whole_circle = half >= M_PI;
  double sum = 0.0, weights = 0.0;
  // The whole circle: equal steps, the end left out (it is the start).
  const double step = whole_circle ? 2.0 * half / kQuadraturePoints : 2.0 * half / (kQuadraturePoints - 1);
  for (int j = 0; j < kQuadraturePoints; ++j) {
    const double offset = -half + step * j;
    const double w = std::exp(kappa * (std::cos(offset) - 1.0));
    sum += w * turned(mu + offset);
    weights += w;
  }
  return sum / weights;
}

UnknownNoise unknown_noise(const tracegen::SensorOptions& sensor) {
  UnknownNoise n;
  n.white_px = std::sqrt(sensor.noise_px * sensor.noise_px + sensor.quantum_px * sensor.quantum_px / 12.0);
  n.wander_px = sensor.correlated_noise_px;
  n.wander_tau_s = sensor.correlated_noise_tau_s;
  return n;
}

std::vector<TrackCase> without_drift(std::vector<TrackCase> cases) {
  for (TrackCase& c : cases) c.options.sensor.drift_px = 0.0;
  return cases;
}

StrokeRotation::StrokeRotation(const UnknownNoise& noise) : noise_(noise) { touch_down(); }

void StrokeRotation::touch_down() {
  x_ = {};
  p_ = {};
  for (int i : {2, 3}) at(p_, i, i) = noise_.wander_px * noise_.wander_px;
  new_stroke();
}

void StrokeRotation::new_stroke() {
  for (int i : {0, 1}) {
    x_[static_cast<size_t>(i)] = 0.0;
    for (int j = 0; j < 4; ++j) at(p_, i, j) = at(p_, j, i) = 0.0;
    at(p_, i, i) = kFlatVariance;
  }
}

void StrokeRotation::predict(double dt_s) {
  if (noise_.wander_px <= 0.0) return;
  const double a = std::exp(-std::max(dt_s, 0.0) / noise_.wander_tau_s);
  const double fresh = noise_.wander_px * noise_.wander_px * (1.0 - a * a);
  for (int i : {2, 3}) {
    x_[static_cast<size_t>(i)] *= a;
    for (int j = 0; j < 4; ++j) {  // row and column i by a: P_ii by a^2
      at(p_, i, j) *= a;
      at(p_, j, i) *= a;
    }
    at(p_, i, i) += fresh;
  }
}

void StrokeRotation::update(double ex, double ey, double dx, double dy) {
  // e = H x + w, H = [[dx, -dy, 1, 0], [dy, dx, 0, 1]]: R(phi) d = (dx c1 - dy c2, dy c1 + dx c2).
  const double h[2][4] = {{dx, -dy, 1.0, 0.0}, {dy, dx, 0.0, 1.0}};
  const double r = noise_.white_px * noise_.white_px;
  double ph[4][2] = {};  // P H^T
  for (int i = 0; i < 4; ++i)
    for (int m = 0; m < 2; ++m)
      for (int j = 0; j < 4; ++j) ph[i][m] += at(p_, i, j) * h[m][j];
  double s[2][2] = {};
  for (int m = 0; m < 2; ++m)
    for (int n = 0; n < 2; ++n) {
      for (int j = 0; j < 4; ++j) s[m][n] += h[m][j] * ph[j][n];
      if (m == n) s[m][n] += r;
    }
  const double det = s[0][0] * s[1][1] - s[0][1] * s[1][0];
  const double si[2][2] = {{s[1][1] / det, -s[0][1] / det}, {-s[1][0] / det, s[0][0] / det}};
  double k[4][2] = {};
  for (int i = 0; i < 4; ++i)
    for (int m = 0; m < 2; ++m)
      for (int n = 0; n < 2; ++n) k[i][m] += ph[i][n] * si[n][m];
  const double innovation[2] = {ex - (h[0][0] * x_[0] + h[0][1] * x_[1] + x_[2]),
                                ey - (h[1][0] * x_[0] + h[1][1] * x_[1] + x_[3])};
  for (int i = 0; i < 4; ++i) x_[static_cast<size_t>(i)] += k[i][0] * innovation[0] + k[i][1] * innovation[1];
  // Joseph form: (I - K H) P (I - K H)^T + K R K^T stays symmetric and
  // positive under the flat prior's large numbers.
  Matrix4 a{};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) at(a, i, j) = (i == j ? 1.0 : 0.0) - k[i][0] * h[0][j] - k[i][1] * h[1][j];
  Matrix4 ap{};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      for (int l = 0; l < 4; ++l) at(ap, i, j) += at(a, i, l) * at(p_, l, j);
  Matrix4 next{};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      double v = r * (k[i][0] * k[j][0] + k[i][1] * k[j][1]);
      for (int l = 0; l < 4; ++l) v += at(ap, i, l) * at(a, j, l);
      at(next, i, j) = v;
    }
  p_ = next;
}

std::array<double, 2> StrokeRotation::information_times_mean() const {
  // Lambda c_hat = P_cc^-1 c_hat, the 2 x 2 inverse written out.
  const double det = at(p_, 0, 0) * at(p_, 1, 1) - at(p_, 0, 1) * at(p_, 1, 0);
  return {(at(p_, 1, 1) * x_[0] - at(p_, 0, 1) * x_[1]) / det, (-at(p_, 1, 0) * x_[0] + at(p_, 0, 0) * x_[1]) / det};
}

double StrokeRotation::kappa() const {
  const std::array<double, 2> m = information_times_mean();
  return std::hypot(m[0], m[1]);
}

double StrokeRotation::mu() const {
  const std::array<double, 2> m = information_times_mean();
  return std::atan2(m[1], m[0]);
}

void RotationObserver::report(const tracegen::TraceSample& s, const tracegen::TrueState& truth, uint64_t scanned_us,
                              double scan_s, bool touch_down) {
  if (touch_down) {
    rotation_.touch_down();
    anchor_ = truth.position;
  } else {
    rotation_.predict(scan_s - last_scan_s_);
  }
  if (standing_still(truth)) {
    rotation_.new_stroke();
    anchor_ = truth.position;
  }
  last_scan_s_ = scan_s;
  const tracegen::Point shake = trace_.tremor_at(scanned_us);
  rotation_.update(s.x - shake.x - anchor_.x, s.y - shake.y - anchor_.y, truth.position.x - anchor_.x,
                   truth.position.y - anchor_.y);
}

double RotationObserver::amplitude(const ScenePlan& heightmap, const TickTruth& tick) const {
  return posterior_mean_amplitude(heightmap, to_vec(tick.state.position), true_direction(tick.state),
                                  rotation_.kappa(), rotation_.mu());
}

double direction_bound_heightmap_rms(const std::vector<PreparedCase>& cases, double moving_speed_px_s,
                                     const UnknownNoise& noise) {
  return observer_errors(cases, moving_speed_px_s,
                         [&](const PreparedCase& c) { return RotationObserver(noise, c.trace); })
      .heightmap_rms;
}

double class_direction_bound(const tracegen::TraceClass& trace_class, const std::vector<PreparedCase>& cases,
                             double duration_s, double moving_speed_px_s) {
  if (cases.empty()) return 0.0;
  const UnknownNoise noise = unknown_noise(cases.front().spec.options.sensor);
  if (cases.front().spec.options.sensor.drift_px <= 0.0)
    return direction_bound_heightmap_rms(cases, moving_speed_px_s, noise);
  return direction_bound_heightmap_rms(prepare_cases(without_drift(class_cases(trace_class, duration_s))),
                                       moving_speed_px_s, noise);
}

}  // namespace ff::bench
