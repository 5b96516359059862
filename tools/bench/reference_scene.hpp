#pragma once
// An independent double-precision implementation of every benchmarked scene,
// written from docs/spec.md's formulas (and, for the numbers it leaves open,
// the values the built-in scenes document): heights, analytic gradients,
// position-only profiles, max|G| by a dense scan plus refinement, and the
// rendered amplitude. It never calls the float core.
#include <vector>

#include "bench_cases.hpp"

namespace ff::bench::reference {

struct Vec2d {
  double x = 0.0;
  double y = 0.0;
};

enum class TermKind { Cone, Valley, Tunnel, Vortex, Saddle, Bumps };
enum class CurveKind { Cubic, Sine };

// y_path(x): docs/spec.md#paths' cubic (slope 0 at both joins, flat outside) or a sine.
struct Curve {
  CurveKind kind = CurveKind::Cubic;
  double x0 = 100.0, y0 = 240.0, length = 600.0, rise = 0.0;  // cubic
  double amplitude = 0.0, wavelength = 1.0;                    // sine (phase from x0)
  double y(double x) const;
  double slope(double x) const;
};

struct Term {
  TermKind kind = TermKind::Cone;
  double weight = 1.0;
  Vec2d centre;                 // cone, vortex, saddle
  Curve curve;                  // valley
  double a = 0.2;               // valley steepness
  double tunnel_x0 = 100.0, tunnel_length = 400.0;  // tunnel
  double width_start = 60.0, width_end = 20.0, scale = 1.0, y_centre = 240.0;
  double wavelength_x = 160.0, wavelength_y = 160.0, bump_height = 20.0;  // bumps
};

enum class Rendering { Constant, Profile, Directional };

struct Scene {
  Rendering rendering = Rendering::Constant;
  double constant = 0.5;
  std::vector<Term> terms;
  // Profile scenes: a slippery band of this half width and feather around `terms[0]`'s curve.
  double band_half_width = 10.0, band_feather = 20.0;
};

Scene scene_for(SceneId id);

double height(const Term& t, Vec2d p);    // Z (0 for the vortex, which has none)
Vec2d gradient(const Term& t, Vec2d p);   // grad Z, or the vortex field
Vec2d field(const Scene& s, Vec2d p);     // weighted sum
double profile(const Scene& s, Vec2d p);  // position-only amplitude, clamped to [0, 1]

// max |G| over the screen [0, 799] x [0, 479]: every pixel, then a compass
// search from the best 16 down to 1e-9 px.
double max_gradient(const Scene& s);

// Raw amplitude in [0, 1] for a unit direction (ignored unless directional).
double amplitude(const Scene& s, double max_g, Vec2d p, Vec2d direction);

}  // namespace ff::bench::reference
