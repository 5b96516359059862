#pragma once
// Independent double-precision forms of the fields of docs/spec.md#scenes, written from the
// spec (not from the core), for tests to compare against.
#include <cmath>

namespace ff::reference {

inline double path_y(double x, double T) {
  const double L = 600.0;
  if (x < 100.0) return 240.0;
  if (x > 700.0) return 240.0 + T;
  const double s = x - 100.0;
  return -2.0 * T / (L * L * L) * s * s * s + 3.0 * T / (L * L) * s * s + 240.0;
}

inline double path_slope(double x, double T) {
  const double L = 600.0;
  if (x < 100.0 || x > 700.0) return 0.0;
  const double s = x - 100.0;
  return -6.0 * T / (L * L * L) * s * s + 6.0 * T / (L * L) * s;
}

// Z = 1/2 |(1/a) atan(a u) - u| + 1/2 |p - target|, by central differences
// in double (h small): independent of the core's closed-form gradient.
inline double heightmap_z(double x, double y, double T) {
  const double a = 0.2;
  const double u = y - path_y(x, T);
  const double z_path = std::fabs(std::atan(a * u) / a - u);
  const double z_cone = std::hypot(x - 700.0, y - (240.0 + T));
  return 0.5 * z_path + 0.5 * z_cone;
}

struct Grad {
  double x, y;
};

inline Grad heightmap_gradient(double x, double y, double T) {
  const double h = 1e-4;
  return {(heightmap_z(x + h, y, T) - heightmap_z(x - h, y, T)) / (2 * h),
          (heightmap_z(x, y + h, T) - heightmap_z(x, y - h, T)) / (2 * h)};
}

// max|G| over every pixel centre of the 800 x 480 screen.
inline double heightmap_max_gradient_scan(double T) {
  double best = 0.0;
  for (int y = 0; y < 480; ++y) {
    for (int x = 0; x < 800; ++x) {
      if (x == 700 && y == static_cast<int>(240.0 + T)) continue;  // cone apex: no gradient
      const Grad g = heightmap_gradient(x, y, T);
      best = std::fmax(best, std::hypot(g.x, g.y));
    }
  }
  return best;
}

inline double smootherstep(double t) {
  t = t < 0 ? 0 : (t > 1 ? 1 : t);
  return t * t * t * (t * (6 * t - 15) + 10);
}

inline double frictionmap_amplitude(double x, double y, double T) {
  return smootherstep((30.0 - std::fabs(y - path_y(x, T))) / 20.0);
}

}  // namespace ff::reference
