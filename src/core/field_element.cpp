#include "frictionfield/core/field_element.hpp"

#include "frictionfield/core/fastrun.hpp"
#include "frictionfield/core/tick_math.hpp"

#include <cmath>
#include <cstdint>

namespace ff {

FF_FASTRUN float smootherstep(float t) {
  t = clamp(t, 0.0f, 1.0f);
  return t * t * t * (t * (6.0f * t - 15.0f) + 10.0f);
}

namespace {

float sign_of(float v) { return v > 0.0f ? 1.0f : (v < 0.0f ? -1.0f : 0.0f); }

// d|g|/du for g(u) = (1/a) atan(a u) - u: sign(u) a^2 u^2 / (1 + a^2 u^2).
// Closed form: no atan on the tick path.
FF_FASTRUN float valley_slope(float u, float a) {
  const float au2 = (a * u) * (a * u);
  // Far from the path (a u)^2 overflows: the slope has saturated at 1 (inf / inf would be NaN).
  return sign_of(u) * (au2 < 1e30f ? au2 / (1.0f + au2) : 1.0f);
}

float valley_height(float u, float a) { return std::fabs(std::atan(a * u) / a - u); }

FF_FASTRUN float band(float distance, float half_width, float feather) {
  return smootherstep((half_width + feather - distance) / feather);
}

FF_FASTRUN float tunnel_width(const TunnelParams& t, float x) {
  const float f = clamp((x - t.x_start) / t.length, 0.0f, 1.0f);
  return t.width_start + (t.width_end - t.width_start) * f;
}

}  // namespace

float element_height(const FieldElement& e, Vec2 p) {
  switch (e.kind) {
    case ElementKind::PointSink:
      return length(p - e.point.centre);
    case ElementKind::PathSink:
      return valley_height(p.y - e.valley.curve.at(p.x).y, e.valley.a);
    case ElementKind::Tunnel: {
      const TunnelParams& t = e.tunnel;
      return valley_height(p.y - t.y_centre, t.scale / tunnel_width(t, p.x));
    }
    case ElementKind::Vortex:
      return 0.0f;
    case ElementKind::Saddle: {
      const Vec2 d = p - e.point.centre;
      return 0.5f * (d.x * d.x - d.y * d.y);
    }
    case ElementKind::Texture: {
      const TextureParams& t = e.texture;
      return t.height * sincos_turns(p.x / t.wavelength_x).sin * sincos_turns(p.y / t.wavelength_y).sin;
    }
  }
  return 0.0f;
}

FF_FASTRUN Vec2 element_gradient(const FieldElement& e, Vec2 p) {
  switch (e.kind) {
    case ElementKind::PointSink: {
      const Vec2 d = p - e.point.centre;
      const float r = length(d);
      // The apex has no gradient; 0 keeps the output at 0.5 there.
      return r > 0.0f ? (1.0f / r) * d : Vec2{};
    }
    case ElementKind::PathSink: {
      const CurvePoint c = e.valley.curve.at(p.x);
      const float dz_du = valley_slope(p.y - c.y, e.valley.a);
      return {-c.slope * dz_du, dz_du};  // grad u = (-y_path', 1)
    }
    case ElementKind::Tunnel: {
      const TunnelParams& t = e.tunnel;
      const float d = p.y - t.y_centre;
      const float k = t.scale / tunnel_width(t, p.x);
      const float dz_dy = valley_slope(d, k);
      const bool inside = p.x > t.x_start && p.x < t.x_start + t.length;
      float dz_dx = 0.0f;
      if (inside && d != 0.0f) {
        // h = (w/s) atan(s d / w) - d; |h| has the sign of -d. With kd = s d / w,
        // dh/dw = (atan(kd) - kd / (1 + kd^2)) / s, and dw/dx = (w_end - w_start) / L.
        const float kd = k * d;
        const float dh_dw_s = arctan(kd) - kd / (1.0f + kd * kd);
        dz_dx = -sign_of(d) * dh_dw_s * (t.width_end - t.width_start) / (t.scale * t.length);
      }
      return {dz_dx, dz_dy};
    }
    case ElementKind::Vortex: {
      const Vec2 d = p - e.point.centre;
      return {-d.y, d.x};
    }
    case ElementKind::Saddle: {
      const Vec2 d = p - e.point.centre;
      return {d.x, -d.y};
    }
    case ElementKind::Texture: {
      const TextureParams& t = e.texture;
      const float kx = 2.0f * kPi / t.wavelength_x;
      const float ky = 2.0f * kPi / t.wavelength_y;
      const SinCos x = sincos_turns(p.x / t.wavelength_x);
      const SinCos y = sincos_turns(p.y / t.wavelength_y);
      return {t.height * kx * x.cos * y.sin, t.height * ky * x.sin * y.cos};
    }
  }
  return {};
}

FF_FASTRUN float element_profile(const FieldElement& e, Vec2 p) {
  switch (e.kind) {
    case ElementKind::PointSink:
      return band(length(p - e.point.centre), e.point.radius, e.point.feather);
    case ElementKind::PathSink: {
      const float u = p.y - e.valley.curve.at(p.x).y;
      return band(std::fabs(u), e.valley.band_half_width, e.valley.band_feather);
    }
    case ElementKind::Tunnel: {
      const TunnelParams& t = e.tunnel;
      const bool inside = p.x >= t.x_start && p.x <= t.x_start + t.length;
      return inside ? band(std::fabs(p.y - t.y_centre), 0.5f * tunnel_width(t, p.x), 10.0f) : 0.0f;
    }
    case ElementKind::Texture: {
      const TextureParams& t = e.texture;
      return 0.5f + 0.5f * sincos_turns(p.x / t.wavelength_x).sin * sincos_turns(p.y / t.wavelength_y).sin;
    }
    case ElementKind::Vortex:
    case ElementKind::Saddle:
      return 0.0f;
  }
  return 0.0f;
}

FieldElement FieldElement::point_sink(Vec2 centre, float weight) {
  FieldElement e;  // PointSink is the default kind
  e.weight = weight;
  e.point.centre = centre;
  return e;
}

FieldElement FieldElement::path_sink(const PathCurve& curve, float a, float weight) {
  FieldElement e;
  e.kind = ElementKind::PathSink;
  e.weight = weight;
  e.valley.curve = curve;
  e.valley.a = a;
  return e;
}

FieldElement FieldElement::tunnel_valley(const TunnelParams& params, float weight) {
  FieldElement e;
  e.kind = ElementKind::Tunnel;
  e.weight = weight;
  e.tunnel = params;
  return e;
}

FieldElement FieldElement::vortex(Vec2 centre, float weight) {
  FieldElement e;
  e.kind = ElementKind::Vortex;
  e.weight = weight;
  e.point.centre = centre;
  return e;
}

FieldElement FieldElement::saddle(Vec2 centre, float weight) {
  FieldElement e;
  e.kind = ElementKind::Saddle;
  e.weight = weight;
  e.point.centre = centre;
  return e;
}

FieldElement FieldElement::sine_texture(float wavelength_x, float wavelength_y, float height,
                                        float weight) {
  FieldElement e;
  e.kind = ElementKind::Texture;
  e.weight = weight;
  e.texture = {wavelength_x, wavelength_y, height};
  return e;
}

}  // namespace ff
