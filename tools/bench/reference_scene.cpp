#include "reference_scene.hpp"

#include <algorithm>
#include <cmath>

namespace ff::bench::reference {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kMaxX = 799.0, kMaxY = 479.0;  // the screen's pixel centres

double sign(double v) { return v > 0.0 ? 1.0 : (v < 0.0 ? -1.0 : 0.0); }

// S5(t) = 6t^5 - 15t^4 + 10t^3 on t clamped to [0, 1].
double smootherstep(double t) {
  t = std::clamp(t, 0.0, 1.0);
  return t * t * t * (10.0 - 15.0 * t + 6.0 * t * t);
}

double tunnel_width(const Term& t, double x) {
  const double f = std::clamp((x - t.tunnel_x0) / t.tunnel_length, 0.0, 1.0);
  return t.width_start + (t.width_end - t.width_start) * f;
}

Term valley(const Curve& c, double a, double weight) {
  Term t;
  t.kind = TermKind::Valley;
  t.curve = c;
  t.a = a;
  t.weight = weight;
  return t;
}

Term point_term(TermKind kind, Vec2d centre, double weight) {
  Term t;
  t.kind = kind;
  t.centre = centre;
  t.weight = weight;
  return t;
}

Curve cubic(double rise) {
  Curve c;
  c.rise = rise;
  return c;
}

Term tunnel(double scale, double weight) {
  Term t;  // pilot geometry: x 100..500, width 60 -> 20, centre 240
  t.kind = TermKind::Tunnel;
  t.scale = scale;
  t.weight = weight;
  return t;
}

Term bumps(double weight) {
  Term t;  // 160 px wavelength, 20 px high: the familiarisation bump map
  t.kind = TermKind::Bumps;
  t.weight = weight;
  return t;
}

}  // namespace

double Curve::y(double x) const {
  if (kind == CurveKind::Sine) return y0 + amplitude * std::sin(2.0 * kPi * (x - x0) / wavelength);
  // y = -2T/L^3 s^3 + 3T/L^2 s^2 + y0, s = x - x0 in [0, L]; flat outside.
  const double s = std::clamp(x - x0, 0.0, length);
  const double L = length, T = rise;
  return -2.0 * T / (L * L * L) * s * s * s + 3.0 * T / (L * L) * s * s + y0;
}

double Curve::slope(double x) const {
  if (kind == CurveKind::Sine) {
    const double k = 2.0 * kPi / wavelength;
    return amplitude * k * std::cos(k * (x - x0));
  }
  if (x < x0 || x > x0 + length) return 0.0;
  const double s = x - x0, L = length, T = rise;
  return -6.0 * T / (L * L * L) * s * s + 6.0 * T / (L * L) * s;
}

Scene scene_for(SceneId id) {
  Scene s;
  s.rendering = Rendering::Directional;
  switch (id) {
    case SceneId::Neutral:
      s.rendering = Rendering::Constant;
      s.constant = 0.5;
      break;
    case SceneId::FrictionmapTop:
      s.rendering = Rendering::Profile;  // A = S5((30 - |u|) / 20)
      s.terms.push_back(valley(cubic(-200.0), 0.2, 1.0));
      break;
    case SceneId::HeightmapTop:
    case SceneId::HeightmapMiddle:
    case SceneId::HeightmapBottom: {
      // Z = 1/2 Z_path + 1/2 Z_cone, a = 1/5, target (700, 240 + T).
      const double T = id == SceneId::HeightmapTop ? -200.0 : (id == SceneId::HeightmapBottom ? 200.0 : 0.0);
      s.terms.push_back(valley(cubic(T), 0.2, 0.5));
      s.terms.push_back(point_term(TermKind::Cone, {700.0, 240.0 + T}, 0.5));
      break;
    }
    case SceneId::TunnelPilotA: s.terms.push_back(tunnel(1.0, 1.0)); break;
    case SceneId::TunnelPilotB: s.terms.push_back(tunnel(10.0, 1.0)); break;
    case SceneId::PilotCTop: s.terms.push_back(valley(cubic(-200.0), 0.5, 1.0)); break;  // |2 atan(u/2) - u|
    case SceneId::BumpMap: s.terms.push_back(bumps(1.0)); break;
    case SceneId::Vortex: s.terms.push_back(point_term(TermKind::Vortex, {400.0, 240.0}, 1.0)); break;
    case SceneId::FamiliarisationPath: {
      s.rendering = Rendering::Profile;
      Curve c;
      c.kind = CurveKind::Sine;
      c.x0 = 0.0;
      c.y0 = 240.0;
      c.amplitude = 120.0;
      c.wavelength = 400.0;
      s.terms.push_back(valley(c, 0.2, 1.0));
      break;
    }
    case SceneId::General1:
    case SceneId::General3:
    case SceneId::General6:
      // The bench's general scenes (bench_cases.cpp): same kinds, places and weights.
      s.terms.push_back(valley(cubic(-200.0), 0.2, 1.0));
      if (id != SceneId::General1) {
        s.terms.push_back(point_term(TermKind::Cone, {700.0, 40.0}, 0.5));
        s.terms.push_back(point_term(TermKind::Saddle, {400.0, 240.0}, 0.002));
      }
      if (id == SceneId::General6) {
        s.terms.push_back(tunnel(1.0, 0.5));
        s.terms.push_back(bumps(0.3));
        s.terms.push_back(point_term(TermKind::Vortex, {400.0, 240.0}, 0.002));
      }
      break;
    case SceneId::kCount: break;
  }
  return s;
}

double height(const Term& t, Vec2d p) {
  switch (t.kind) {
    case TermKind::Cone: return std::hypot(p.x - t.centre.x, p.y - t.centre.y);
    case TermKind::Valley: {
      const double u = p.y - t.curve.y(p.x);
      return std::fabs(std::atan(t.a * u) / t.a - u);
    }
    case TermKind::Tunnel: {
      const double w = tunnel_width(t, p.x), d = p.y - t.y_centre;
      return std::fabs(w / t.scale * std::atan(t.scale / w * d) - d);
    }
    case TermKind::Vortex: return 0.0;
    case TermKind::Saddle: {
      const double dx = p.x - t.centre.x, dy = p.y - t.centre.y;
      return 0.5 * (dx * dx - dy * dy);
    }
    case TermKind::Bumps:
      return t.bump_height * std::sin(2.0 * kPi * p.x / t.wavelength_x) *
             std::sin(2.0 * kPi * p.y / t.wavelength_y);
  }
  return 0.0;
}

Vec2d gradient(const Term& t, Vec2d p) {
  switch (t.kind) {
    case TermKind::Cone: {
      const double dx = p.x - t.centre.x, dy = p.y - t.centre.y, r = std::hypot(dx, dy);
      return r > 0.0 ? Vec2d{dx / r, dy / r} : Vec2d{};
    }
    case TermKind::Valley: {
      // d|g|/du = sign(u) a^2 u^2 / (1 + a^2 u^2), grad u = (-y_path'(x), 1).
      const double u = p.y - t.curve.y(p.x), au2 = t.a * t.a * u * u;
      const double dz_du = sign(u) * au2 / (1.0 + au2);
      return {-t.curve.slope(p.x) * dz_du, dz_du};
    }
    case TermKind::Tunnel: {
      // h = (w/s) atan(s d / w) - d has the sign of -d; H = |h|.
      const double w = tunnel_width(t, p.x), d = p.y - t.y_centre, k = t.scale / w, kd = k * d;
      const double dh_dd = -kd * kd / (1.0 + kd * kd);
      const double dh_dw = std::atan(kd) / t.scale - (d / w) / (1.0 + kd * kd);
      const bool inside = p.x > t.tunnel_x0 && p.x < t.tunnel_x0 + t.tunnel_length;
      const double dw_dx = inside ? (t.width_end - t.width_start) / t.tunnel_length : 0.0;
      return {-sign(d) * dh_dw * dw_dx, -sign(d) * dh_dd};
    }
    case TermKind::Vortex: return {-(p.y - t.centre.y), p.x - t.centre.x};
    case TermKind::Saddle: return {p.x - t.centre.x, -(p.y - t.centre.y)};
    case TermKind::Bumps: {
      const double kx = 2.0 * kPi / t.wavelength_x, ky = 2.0 * kPi / t.wavelength_y;
      return {t.bump_height * kx * std::cos(kx * p.x) * std::sin(ky * p.y),
              t.bump_height * ky * std::sin(kx * p.x) * std::cos(ky * p.y)};
    }
  }
  return {};
}

Vec2d field(const Scene& s, Vec2d p) {
  Vec2d g;
  for (const Term& t : s.terms) {
    const Vec2d gt = gradient(t, p);
    g.x += t.weight * gt.x;
    g.y += t.weight * gt.y;
  }
  return g;
}

double profile(const Scene& s, Vec2d p) {
  double a = 0.0;
  for (const Term& t : s.terms) {
    const double u = std::fabs(p.y - t.curve.y(p.x));
    a += t.weight * smootherstep((s.band_half_width + s.band_feather - u) / s.band_feather);
  }
  return std::clamp(a, 0.0, 1.0);
}

double max_gradient(const Scene& s) {
  if (s.rendering != Rendering::Directional) return 0.0;
  auto magnitude = [&](Vec2d p) {
    const Vec2d g = field(s, p);
    return std::hypot(g.x, g.y);
  };
  struct Candidate {
    double m;
    Vec2d p;
  };
  std::vector<Candidate> all;
  all.reserve(800 * 480);
  for (int j = 0; j <= 479; ++j) {
    for (int i = 0; i <= 799; ++i) {
      const Vec2d p{static_cast<double>(i), static_cast<double>(j)};
      all.push_back({magnitude(p), p});
    }
  }
  constexpr size_t kStarts = 16;
  std::partial_sort(all.begin(), all.begin() + kStarts, all.end(),
                    [](const Candidate& a, const Candidate& b) { return a.m > b.m; });
  double best = 0.0;
  for (size_t c = 0; c < kStarts; ++c) {
    Vec2d p = all[c].p;
    double m = all[c].m;
    for (double step = 1.0; step >= 1e-9;) {
      bool moved = false;
      for (int dx = -1; dx <= 1; ++dx) {
        for (int dy = -1; dy <= 1; ++dy) {
          const Vec2d q{std::clamp(p.x + dx * step, 0.0, kMaxX), std::clamp(p.y + dy * step, 0.0, kMaxY)};
          const double mq = magnitude(q);
          if (mq > m) {
            m = mq;
            p = q;
            moved = true;
          }
        }
      }
      if (!moved) step *= 0.5;
    }
    best = std::max(best, m);
  }
  return best;
}

double amplitude(const Scene& s, double max_g, Vec2d p, Vec2d direction) {
  switch (s.rendering) {
    case Rendering::Constant: return s.constant;
    case Rendering::Profile: return profile(s, p);
    case Rendering::Directional: {
      if (!(max_g > 0.0)) return 0.5;
      // friction mu = 0.5 + v_hat . G / (2 max|G|); amplitude A = 1 - mu.
      const Vec2d g = field(s, p);
      return std::clamp(0.5 - (direction.x * g.x + direction.y * g.y) / (2.0 * max_g), 0.0, 1.0);
    }
  }
  return 0.5;
}

}  // namespace ff::bench::reference
