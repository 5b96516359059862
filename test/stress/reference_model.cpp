#include "reference_model.hpp"

#include <algorithm>
#include <cmath>

namespace ff::stress {

namespace {

constexpr double kPiD = 3.14159265358979323846;
constexpr double kMaxX = 799.0, kMaxY = 479.0;

double sign_of(double v) { return v > 0.0 ? 1.0 : (v < 0.0 ? -1.0 : 0.0); }
double clamp01(double v) { return v < 0.0 ? 0.0 : (v > 1.0 ? 1.0 : v); }

// |(1/a) atan(a u) - u| and its derivative in u (docs/spec.md#heightmap).
double valley_height(double u, double a) { return std::fabs(std::atan(a * u) / a - u); }
double valley_slope(double u, double a) {
  const double au2 = (a * u) * (a * u);
  return sign_of(u) * au2 / (1.0 + au2);
}
// Slippery band: 1 up to half_width, quintic feather to 0 over `feather`.
double band(double distance, double half_width, double feather) {
  return ref_smootherstep((half_width + feather - distance) / feather);
}

}  // namespace

double ref_smootherstep(double t) {
  t = clamp01(t);
  return t * t * t * (t * (6.0 * t - 15.0) + 10.0);
}

namespace {

double d(float v) { return static_cast<double>(v); }

detail::DCurve widen(const PathCurve& c) {
  detail::DCurve o{c.kind, d(c.x0), d(c.y0), d(c.length), d(c.rise), d(c.amplitude), d(c.wavelength), c.count, {}, {}};
  for (int i = 0; i < c.count && i < kMaxPolylinePoints; ++i) {
    o.px[i] = d(c.points[i].x);
    o.py[i] = d(c.points[i].y);
  }
  return o;
}

detail::DElement widen(const FieldElement& e) {
  detail::DElement o;
  o.kind = e.kind;
  o.weight = d(e.weight);
  o.cx = d(e.point.centre.x);
  o.cy = d(e.point.centre.y);
  o.radius = d(e.point.radius);
  o.feather = d(e.point.feather);
  o.curve = widen(e.valley.curve);
  o.a = d(e.valley.a);
  o.band_half_width = d(e.valley.band_half_width);
  o.band_feather = d(e.valley.band_feather);
  o.t_x_start = d(e.tunnel.x_start);
  o.t_length = d(e.tunnel.length);
  o.t_w0 = d(e.tunnel.width_start);
  o.t_w1 = d(e.tunnel.width_end);
  o.t_scale = d(e.tunnel.scale);
  o.t_yc = d(e.tunnel.y_centre);
  o.lx = d(e.texture.wavelength_x);
  o.ly = d(e.texture.wavelength_y);
  o.height = d(e.texture.height);
  return o;
}

void curve_at(const detail::DCurve& c, double x, double& y, double& slope) {
  switch (c.kind) {
    case CurveKind::Cubic: {
      // docs/spec.md#paths: y = -2T/L^3 s^3 + 3T/L^2 s^2 + y0 on [x0, x0 + L], flat outside.
      const double L = c.length, T = c.rise;
      const double s = std::min(L, std::max(0.0, x - c.x0));
      y = -2.0 * T / (L * L * L) * s * s * s + 3.0 * T / (L * L) * s * s + c.y0;
      const bool inside = x > c.x0 && x < c.x0 + L;
      slope = inside ? -6.0 * T / (L * L * L) * s * s + 6.0 * T / (L * L) * s : 0.0;
      return;
    }
    case CurveKind::Sine: {
      const double k = 2.0 * kPiD / c.wavelength;
      y = c.y0 + c.amplitude * std::sin(k * (x - c.x0));
      slope = c.amplitude * k * std::cos(k * (x - c.x0));
      return;
    }
    case CurveKind::Polyline: {
      y = 0.0;
      slope = 0.0;
      if (c.count == 0) return;
      if (x <= c.px[0]) {
        y = c.py[0];
        return;
      }
      for (int i = 1; i < c.count; ++i) {
        if (x <= c.px[i]) {
          slope = (c.py[i] - c.py[i - 1]) / (c.px[i] - c.px[i - 1]);
          y = c.py[i - 1] + slope * (x - c.px[i - 1]);
          return;
        }
      }
      y = c.py[c.count - 1];
      return;
    }
  }
  y = 0.0;
  slope = 0.0;
}

double tunnel_width(const detail::DElement& t, double x) {
  const double f = std::min(1.0, std::max(0.0, (x - t.t_x_start) / t.t_length));
  return t.t_w0 + (t.t_w1 - t.t_w0) * f;
}

double height_of(const detail::DElement& e, double x, double y) {
  switch (e.kind) {
    case ElementKind::PointSink:
      return std::hypot(x - e.cx, y - e.cy);
    case ElementKind::PathSink: {
      double yc, slope;
      curve_at(e.curve, x, yc, slope);
      return valley_height(y - yc, e.a);
    }
    case ElementKind::Tunnel:  // docs/spec.md#pilots: H = | w/s atan(s/w (y - y_c)) - (y - y_c) |
      return valley_height(y - e.t_yc, e.t_scale / tunnel_width(e, x));
    case ElementKind::Vortex:
      return 0.0;
    case ElementKind::Saddle:
      return 0.5 * ((x - e.cx) * (x - e.cx) - (y - e.cy) * (y - e.cy));
    case ElementKind::Texture:
      return e.height * std::sin(2.0 * kPiD * x / e.lx) * std::sin(2.0 * kPiD * y / e.ly);
  }
  return 0.0;
}

DVec gradient_of(const detail::DElement& e, double x, double y) {
  switch (e.kind) {
    case ElementKind::PointSink: {
      const double dx = x - e.cx, dy = y - e.cy;
      const double r = std::hypot(dx, dy);
      return r > 0.0 ? DVec{dx / r, dy / r} : DVec{};  // the apex has no gradient
    }
    case ElementKind::PathSink: {
      double yc, slope;
      curve_at(e.curve, x, yc, slope);
      const double dz = valley_slope(y - yc, e.a);
      return {-slope * dz, dz};  // grad u = (-y_path', 1)
    }
    case ElementKind::Tunnel: {
      // h(dy, w) = (w/s) atan(s dy / w) - dy; H = |h| = -sign(dy) h.
      const double dy = y - e.t_yc;
      const double w = tunnel_width(e, x);
      const double k = e.t_scale / w;
      const double dh_dw = std::atan(k * dy) / e.t_scale - (dy / w) / (1.0 + k * dy * k * dy);
      const bool inside = x > e.t_x_start && x < e.t_x_start + e.t_length;
      const double dw_dx = inside ? (e.t_w1 - e.t_w0) / e.t_length : 0.0;
      return {-sign_of(dy) * dh_dw * dw_dx, valley_slope(dy, k)};
    }
    case ElementKind::Vortex:  // docs/spec.md#elements: G = (-(y - yc), x - xc)
      return {-(y - e.cy), x - e.cx};
    case ElementKind::Saddle:
      return {x - e.cx, -(y - e.cy)};
    case ElementKind::Texture: {
      const double kx = 2.0 * kPiD / e.lx, ky = 2.0 * kPiD / e.ly;
      return {e.height * kx * std::cos(kx * x) * std::sin(ky * y), e.height * ky * std::sin(kx * x) * std::cos(ky * y)};
    }
  }
  return {};
}

double profile_of(const detail::DElement& e, double x, double y) {
  switch (e.kind) {
    case ElementKind::PointSink:
      return band(std::hypot(x - e.cx, y - e.cy), e.radius, e.feather);
    case ElementKind::PathSink: {
      double yc, slope;
      curve_at(e.curve, x, yc, slope);
      return band(std::fabs(y - yc), e.band_half_width, e.band_feather);
    }
    case ElementKind::Tunnel: {
      // The tunnel's own walls: slippery inside w(x), a 10 px feather.
      const bool inside = x >= e.t_x_start && x <= e.t_x_start + e.t_length;
      return inside ? band(std::fabs(y - e.t_yc), 0.5 * tunnel_width(e, x), 10.0) : 0.0;
    }
    case ElementKind::Texture:
      return 0.5 + 0.5 * std::sin(2.0 * kPiD * x / e.lx) * std::sin(2.0 * kPiD * y / e.ly);
    case ElementKind::Vortex:
    case ElementKind::Saddle:
      return 0.0;
  }
  return 0.0;
}

}  // namespace

void ref_curve(const PathCurve& c, double x, double& y, double& slope) { curve_at(widen(c), x, y, slope); }
double ref_height(const FieldElement& e, double x, double y) { return height_of(widen(e), x, y); }
DVec ref_gradient(const FieldElement& e, double x, double y) { return gradient_of(widen(e), x, y); }
double ref_profile(const FieldElement& e, double x, double y) { return profile_of(widen(e), x, y); }

ReferenceScene::ReferenceScene(const SceneDefinition& scene) : scene_(scene) {
  for (int i = 0; i < scene.element_count && i < kMaxSceneElements; ++i) elements_.push_back(widen(scene.elements[i]));
  if (scene_.rendering == Rendering::Directional) max_gradient_ = find_max_gradient();
}

DVec ReferenceScene::field(double x, double y) const {
  DVec g;
  for (const detail::DElement& e : elements_) {
    const DVec d = gradient_of(e, x, y);
    g.x += e.weight * d.x;
    g.y += e.weight * d.y;
  }
  return g;
}

double ReferenceScene::profile(double x, double y) const {
  double a = static_cast<double>(scene_.bias);
  for (const detail::DElement& e : elements_) a += e.weight * profile_of(e, x, y);
  return clamp01(a);
}

double ReferenceScene::find_max_gradient() const {
  auto mag = [&](double x, double y) {
    const DVec g = field(std::min(kMaxX, std::max(0.0, x)), std::min(kMaxY, std::max(0.0, y)));
    return std::hypot(g.x, g.y);
  };
  constexpr int kKeep = 8;
  double best_m[kKeep];
  DVec best_p[kKeep];
  for (double& m : best_m) m = -1.0;
  auto consider = [&](double x, double y) {
    const double m = mag(x, y);
    int worst = 0;
    for (int i = 1; i < kKeep; ++i) worst = best_m[i] < best_m[worst] ? i : worst;
    if (m > best_m[worst]) {
      best_m[worst] = m;
      best_p[worst] = {x, y};
    }
  };
  const double step = 4.0;
  for (double y = 0.0;; y += step) {
    const double yy = std::min(y, kMaxY);
    for (double x = 0.0;; x += step) {
      consider(std::min(x, kMaxX), yy);
      if (x >= kMaxX) break;
    }
    if (y >= kMaxY) break;
  }
  double best = 0.0;
  for (int c = 0; c < kKeep; ++c) {
    double x = best_p[c].x, y = best_p[c].y, m = best_m[c];
    for (double h = step; h >= 1e-4;) {
      bool moved = false;
      for (int dx = -1; dx <= 1; ++dx) {
        for (int dy = -1; dy <= 1; ++dy) {
          const double qx = std::min(kMaxX, std::max(0.0, x + dx * h));
          const double qy = std::min(kMaxY, std::max(0.0, y + dy * h));
          const double mq = mag(qx, qy);
          if (mq > m) {
            m = mq;
            x = qx;
            y = qy;
            moved = true;
          }
        }
      }
      if (!moved) h *= 0.5;
    }
    best = std::max(best, m);
  }
  return best;
}

double ReferenceScene::raw_amplitude(double px, double py, double dx, double dy) const {
  switch (scene_.rendering) {
    case Rendering::Constant:
      return clamp01(static_cast<double>(scene_.constant));
    case Rendering::PositionOnly:
      return profile(px, py);
    case Rendering::Directional: {
      if (!(max_gradient_ > 0.0) || !std::isfinite(max_gradient_)) return 0.5;
      const DVec g = field(px, py);
      return clamp01(0.5 - (dx * g.x + dy * g.y) / (2.0 * max_gradient_));
    }
  }
  return 0.5;
}

ReferenceAmplitude::ReferenceAmplitude(const AmplitudeSettings& s, bool calibration_valid) {
  const double st = s.strength;
  strength_ = std::isnan(st) ? 0.0 : clamp01(st);
  s_curve_ = std::isnan(s.s_curve) ? 0.0 : clamp01(s.s_curve);
  idle_ = std::isnan(s.idle_amplitude) ? 0.0 : clamp01(s.idle_amplitude);
  if (calibration_valid) {
    for (int i = 0; i < s.calibration.count; ++i) {
      amps_.push_back(s.calibration.amplitude[i]);
      codes_.push_back(s.calibration.code[i]);
    }
  } else {  // docs/spec.md#amplitude default: code = round(A * 4095)
    amps_ = {0.0, 1.0};
    codes_ = {0.0, 4095.0};
  }
}

double ReferenceAmplitude::scale(double raw) const {
  double a = std::isnan(raw) ? 0.5 : clamp01(raw);
  a += s_curve_ * (ref_smootherstep(a) - a);
  return 0.5 + strength_ * (a - 0.5);
}

int ReferenceAmplitude::dac(double a, bool* near_tie) const {
  a = std::isnan(a) ? 0.0 : clamp01(a);
  size_t i = 1;
  while (i + 1 < amps_.size() && a > amps_[i]) ++i;
  const double t = (a - amps_[i - 1]) / (amps_[i] - amps_[i - 1]);
  const double c = codes_[i - 1] + t * (codes_[i] - codes_[i - 1]);
  if (near_tie != nullptr) *near_tie = std::fabs(c - std::floor(c) - 0.5) < 1e-3;
  return static_cast<int>(std::min(4095.0, std::max(0.0, std::floor(c + 0.5))));
}

double ReferenceOneEuro::operator()(double x) {
  auto alpha = [&](double fc) { return 1.0 / (1.0 + rate_hz / (2.0 * kPiD * fc)); };
  if (!init) {
    init = true;
    xhat = xprev = x;
    dxhat = 0.0;
    return x;
  }
  const double dx = (x - (from_filtered ? xhat : xprev)) * rate_hz;
  dxhat = alpha(derivative_cutoff_hz) * dx + (1.0 - alpha(derivative_cutoff_hz)) * dxhat;
  const double a = alpha(min_cutoff_hz + beta * std::fabs(dxhat));
  xhat = a * x + (1.0 - a) * xhat;
  xprev = x;
  return xhat;
}

void ReferenceThesisTracker::on_sample(const SensorSample& s) {
  if (!s.touch) return;
  if (have_) {
    const double dt = static_cast<double>(static_cast<int32_t>(s.t_us - t_));
    vx_ = (static_cast<double>(s.x) - x_) / dt;
    vy_ = (static_cast<double>(s.y) - y_) / dt;
  }
  have_ = true;
  x_ = s.x;
  y_ = s.y;
  t_ = s.t_us;
  n_ = 0;
}

double ReferenceThesisTracker::filtered_speed() const { return std::hypot(ex_.dxhat, ey_.dxhat); }

void ReferenceThesisTracker::on_tick(DVec& position, DVec& direction) {
  const double h = static_cast<double>(n_) * 500.0;
  ++n_;
  position = {ex_(x_ + vx_ * h), ey_(y_ + vy_ * h)};
  const double speed = std::hypot(ex_.dxhat, ey_.dxhat);
  direction = speed > 0.0 ? DVec{ex_.dxhat / speed, ey_.dxhat / speed} : DVec{};
}

}  // namespace ff::stress
