#pragma once
// The building blocks of every scene: one term of a weighted sum. Each kind
// has a closed-form height (where one exists), a closed-form gradient, and a
// position-only profile in [0, 1] for friction-map rendering.
#include <cstdint>

#include "frictionfield/core/geometry.hpp"
#include "frictionfield/core/path_curve.hpp"

namespace ff {

enum class ElementKind : uint8_t {
  PointSink,  // cone Z = |p - c| (negative weight: a source)
  PathSink,   // valley Z = |(1/a) atan(a u) - u| along a curve
  Tunnel,     // steering tunnel: valley whose width w(x) changes along x
  Vortex,     // G = (-(y - yc), x - xc): no potential produces it
  Saddle,     // Z = ((x - xc)^2 - (y - yc)^2) / 2
  Texture,    // Z = sin(2 pi x / lx) sin(2 pi y / ly) * wavelength-scaled bumps
};

struct ValleyParams {
  PathCurve curve;
  float a = 0.2f;             // steepness: 1/5 for the experiment, s/w for the pilots
  float band_half_width = 10.0f;  // position-only: fully slippery for |u| <= this
  float band_feather = 20.0f;     // then a quintic smoothstep down to 0 over this
};

struct PointParams {
  Vec2 centre;
  float radius = 10.0f;   // position-only profile: a slippery disc
  float feather = 20.0f;
};

struct TunnelParams {
  float x_start = 100.0f;
  float length = 400.0f;
  float width_start = 60.0f;
  float width_end = 20.0f;
  float scale = 1.0f;     // s: 1 in pilot A, 10 in pilot B
  float y_centre = 240.0f;
};

struct TextureParams {
  float wavelength_x = 100.0f;
  float wavelength_y = 100.0f;
  float height = 1.0f;    // bump height in px: sets the slope, so the mix with other terms
};

struct FieldElement {
  ElementKind kind = ElementKind::PointSink;
  float weight = 1.0f;
  PointParams point;      // PointSink, Vortex, Saddle (centre)
  ValleyParams valley;    // PathSink
  TunnelParams tunnel;    // Tunnel
  TextureParams texture;  // Texture

  static FieldElement point_sink(Vec2 centre, float weight = 1.0f);
  static FieldElement path_sink(const PathCurve& curve, float a, float weight = 1.0f);
  static FieldElement tunnel_valley(const TunnelParams& params, float weight = 1.0f);
  static FieldElement vortex(Vec2 centre, float weight = 1.0f);
  static FieldElement saddle(Vec2 centre, float weight = 1.0f);
  static FieldElement sine_texture(float wavelength_x, float wavelength_y, float height,
                                   float weight = 1.0f);
};

// Unweighted height; 0 for the vortex (it has none).
float element_height(const FieldElement& e, Vec2 p);
// Unweighted gradient of the height (the vortex's field for the vortex).
Vec2 element_gradient(const FieldElement& e, Vec2 p);
// Unweighted position-only profile in [0, 1] (0 where a kind has none).
float element_profile(const FieldElement& e, Vec2 p);

// S5(t) = 6t^5 - 15t^4 + 10t^3 on t clamped to [0, 1].
float smootherstep(float t);

}  // namespace ff
