#include "support/reference/reference_scene.hpp"

#include <algorithm>
#include <cmath>

namespace ff::reference {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kMaxX = 799.0, kMaxY = 479.0;  // the screen's pixel centres

double d(float v) { return static_cast<double>(v); }
double sign_of(double v) { return v > 0.0 ? 1.0 : (v < 0.0 ? -1.0 : 0.0); }

// y = -2T/L^3 s^3 + 3T/L^2 s^2 + y0, s = x - x0 in [0, L]; flat (and exact) outside.
PathPoint cubic_at(double x0, double y0, double length, double rise, double x) {
  const double L = length, T = rise, s = x - x0;
  if (!(s > 0.0)) return {y0, 0.0};
  if (!(s < L)) return {y0 + T, 0.0};
  return {-2.0 * T / (L * L * L) * s * s * s + 3.0 * T / (L * L) * s * s + y0,
          -6.0 * T / (L * L * L) * s * s + 6.0 * T / (L * L) * s};
}

// |(1/a) atan(a u) - u| and its derivative in u (docs/spec.md#heightmap).
double valley_height(double u, double a) { return std::fabs(std::atan(a * u) / a - u); }
double valley_slope(double u, double a) {
  const double au2 = (a * u) * (a * u);
  return sign_of(u) * au2 / (1.0 + au2);
}
// Slippery band: 1 up to half_width, quintic feather to 0 over `feather`.
double band(double distance, double half_width, double feather) {
  return smootherstep((half_width + feather - distance) / feather);
}

double tunnel_width(const TunnelParams& t, double x) {
  const double f = std::min(1.0, std::max(0.0, (x - d(t.x_start)) / d(t.length)));
  return d(t.width_start) + (d(t.width_end) - d(t.width_start)) * f;
}

}  // namespace

double clamp01(double v) { return v < 0.0 ? 0.0 : (v > 1.0 ? 1.0 : v); }

double smootherstep(double t) {
  t = clamp01(t);
  return t * t * t * (t * (6.0 * t - 15.0) + 10.0);
}

PathPoint experiment_path_at(double x, double rise) { return cubic_at(100.0, 240.0, 600.0, rise, x); }

PathPoint path_at(const PathCurve& c, double x) {
  switch (c.kind) {
    case CurveKind::Cubic: return cubic_at(d(c.x0), d(c.y0), d(c.length), d(c.rise), x);
    case CurveKind::Sine: {
      const double k = 2.0 * kPi / d(c.wavelength), phase = k * (x - d(c.x0));
      return {d(c.y0) + d(c.amplitude) * std::sin(phase), d(c.amplitude) * k * std::cos(phase)};
    }
    case CurveKind::Polyline: {
      const int n = std::min<int>(c.count, kMaxPolylinePoints);
      if (n == 0) return {};
      if (x <= d(c.points[0].x)) return {d(c.points[0].y), 0.0};
      for (int i = 1; i < n; ++i) {
        const double x0 = d(c.points[i - 1].x), y0 = d(c.points[i - 1].y);
        const double x1 = d(c.points[i].x), y1 = d(c.points[i].y);
        if (x <= x1) {
          const double slope = (y1 - y0) / (x1 - x0);
          return {y0 + slope * (x - x0), slope};
        }
      }
      return {d(c.points[n - 1].y), 0.0};
    }
  }
  return {};
}

double element_height(const FieldElement& e, double x, double y) {
  const DVec c{d(e.point.centre.x), d(e.point.centre.y)};
  switch (e.kind) {
    case ElementKind::PointSink: return std::hypot(x - c.x, y - c.y);
    case ElementKind::PathSink: return valley_height(y - path_at(e.valley.curve, x).y, d(e.valley.a));
    case ElementKind::Tunnel:  // docs/spec.md#pilots: H = | w/s atan(s/w (y - y_c)) - (y - y_c) |
      return valley_height(y - d(e.tunnel.y_centre), d(e.tunnel.scale) / tunnel_width(e.tunnel, x));
    case ElementKind::Vortex: return 0.0;
    case ElementKind::Saddle: return 0.5 * ((x - c.x) * (x - c.x) - (y - c.y) * (y - c.y));
    case ElementKind::Texture:
      return d(e.texture.height) * std::sin(2.0 * kPi * x / d(e.texture.wavelength_x)) *
             std::sin(2.0 * kPi * y / d(e.texture.wavelength_y));
  }
  return 0.0;
}

DVec element_gradient(const FieldElement& e, double x, double y) {
  const DVec c{d(e.point.centre.x), d(e.point.centre.y)};
  switch (e.kind) {
    case ElementKind::PointSink: {
      const double dx = x - c.x, dy = y - c.y, r = std::hypot(dx, dy);
      return r > 0.0 ? DVec{dx / r, dy / r} : DVec{};  // the apex has no gradient
    }
    case ElementKind::PathSink: {
      const PathPoint p = path_at(e.valley.curve, x);
      const double dz = valley_slope(y - p.y, d(e.valley.a));
      return {-p.slope * dz, dz};  // grad u = (-y_path', 1)
    }
    case ElementKind::Tunnel: {
      // h(dy, w) = (w/s) atan(s dy / w) - dy; H = |h| = -sign(dy) h.
      const TunnelParams& t = e.tunnel;
      const double dy = y - d(t.y_centre), w = tunnel_width(t, x), k = d(t.scale) / w;
      const double dh_dw = std::atan(k * dy) / d(t.scale) - (dy / w) / (1.0 + k * dy * k * dy);
      const bool inside = x > d(t.x_start) && x < d(t.x_start) + d(t.length);
      const double dw_dx = inside ? (d(t.width_end) - d(t.width_start)) / d(t.length) : 0.0;
      return {-sign_of(dy) * dh_dw * dw_dx, valley_slope(dy, k)};
    }
    case ElementKind::Vortex: return {-(y - c.y), x - c.x};  // docs/spec.md#elements
    case ElementKind::Saddle: return {x - c.x, -(y - c.y)};
    case ElementKind::Texture: {
      const double kx = 2.0 * kPi / d(e.texture.wavelength_x), ky = 2.0 * kPi / d(e.texture.wavelength_y);
      const double h = d(e.texture.height);
      return {h * kx * std::cos(kx * x) * std::sin(ky * y), h * ky * std::sin(kx * x) * std::cos(ky * y)};
    }
  }
  return {};
}

double element_profile(const FieldElement& e, double x, double y) {
  switch (e.kind) {
    case ElementKind::PointSink:
      return band(std::hypot(x - d(e.point.centre.x), y - d(e.point.centre.y)), d(e.point.radius), d(e.point.feather));
    case ElementKind::PathSink:
      return band(std::fabs(y - path_at(e.valley.curve, x).y), d(e.valley.band_half_width), d(e.valley.band_feather));
    case ElementKind::Tunnel: {
      // The tunnel's own walls: slippery inside w(x), a 10 px feather.
      const TunnelParams& t = e.tunnel;
      const bool inside = x >= d(t.x_start) && x <= d(t.x_start) + d(t.length);
      return inside ? band(std::fabs(y - d(t.y_centre)), 0.5 * tunnel_width(t, x), 10.0) : 0.0;
    }
    case ElementKind::Texture:
      return 0.5 + 0.5 * std::sin(2.0 * kPi * x / d(e.texture.wavelength_x)) *
                       std::sin(2.0 * kPi * y / d(e.texture.wavelength_y));
    case ElementKind::Vortex:
    case ElementKind::Saddle: return 0.0;
  }
  return 0.0;
}

ReferenceScene::ReferenceScene(const SceneDefinition& scene, const MaxGradientSearch& search) : scene_(scene) {
  scene_.element_count = static_cast<uint8_t>(std::min<int>(scene.element_count, kMaxSceneElements));
  if (scene_.rendering == Rendering::Directional) max_gradient_ = find_max_gradient(search);
}

double ReferenceScene::height(double x, double y) const {
  double z = 0.0;
  for (int i = 0; i < scene_.element_count; ++i) z += d(scene_.elements[i].weight) * element_height(scene_.elements[i], x, y);
  return z;
}

DVec ReferenceScene::field(double x, double y) const {
  DVec g;
  for (int i = 0; i < scene_.element_count; ++i) {
    const FieldElement& e = scene_.elements[i];
    const DVec ge = element_gradient(e, x, y);
    g.x += d(e.weight) * ge.x;
    g.y += d(e.weight) * ge.y;
  }
  return g;
}

double ReferenceScene::profile(double x, double y) const {
  double a = d(scene_.bias);
  for (int i = 0; i < scene_.element_count; ++i) a += d(scene_.elements[i].weight) * element_profile(scene_.elements[i], x, y);
  return clamp01(a);
}

double ReferenceScene::find_max_gradient(const MaxGradientSearch& search) const {
  auto magnitude = [&](double x, double y) {
    const DVec g = field(x, y);
    return std::hypot(g.x, g.y);
  };
  struct Node {
    double m, x, y;
  };
  std::vector<Node> nodes;
  const double step = search.scan_step_px;
  for (double y = 0.0;; y += step) {
    const double yy = std::min(y, kMaxY);
    for (double x = 0.0;; x += step) {
      const double xx = std::min(x, kMaxX);
      nodes.push_back({magnitude(xx, yy), xx, yy});
      if (x >= kMaxX) break;
    }
    if (y >= kMaxY) break;
  }
  const size_t starts = std::min(nodes.size(), static_cast<size_t>(std::max(1, search.starts)));
  std::partial_sort(nodes.begin(), nodes.begin() + static_cast<std::ptrdiff_t>(starts), nodes.end(),
                    [](const Node& a, const Node& b) { return a.m > b.m; });
  double best = 0.0;
  for (size_t c = 0; c < starts; ++c) {
    Node n = nodes[c];
    for (double h = step; h >= search.last_step_px;) {
      bool moved = false;
      for (int dx = -1; dx <= 1; ++dx) {
        for (int dy = -1; dy <= 1; ++dy) {
          const double qx = std::clamp(n.x + dx * h, 0.0, kMaxX), qy = std::clamp(n.y + dy * h, 0.0, kMaxY);
          const double mq = magnitude(qx, qy);
          if (mq > n.m) {
            n = {mq, qx, qy};
            moved = true;
          }
        }
      }
      if (!moved) h *= 0.5;
    }
    best = std::max(best, n.m);
  }
  return best;
}

double ReferenceScene::raw_amplitude(double px, double py, double dx, double dy) const {
  switch (scene_.rendering) {
    case Rendering::Constant: return clamp01(d(scene_.constant));
    case Rendering::PositionOnly: return profile(px, py);
    case Rendering::Directional: {
      if (!(max_gradient_ > 0.0) || !std::isfinite(max_gradient_)) return 0.5;
      // friction mu = 0.5 + d . G / (2 max|G|); amplitude A = 1 - mu.
      const DVec g = field(px, py);
      return clamp01(0.5 - (dx * g.x + dy * g.y) / (2.0 * max_gradient_));
    }
  }
  return 0.5;
}

}  // namespace ff::reference
