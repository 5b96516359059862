#pragma once
// A path as y(x): the centre line of a valley or of a slippery band. Offsets
// from it are vertical (u = y - y_path(x)), as in docs/spec.md#paths.
#include <cstdint>

#include "frictionfield/core/geometry.hpp"

namespace ff {

enum class CurveKind : uint8_t {
  Cubic,     // docs/spec.md#paths: experiment paths: slope 0 at both joins
  Sine,      // familiarisation: y0 + amplitude sin(2 pi (x - x0) / wavelength)
  Polyline,  // any path drawn as points with increasing x
};

constexpr int kMaxPolylinePoints = 16;

struct CurvePoint {
  float y = 0.0f;      // y_path(x)
  float slope = 0.0f;  // dy_path/dx
};

struct PathCurve {
  CurveKind kind = CurveKind::Cubic;
  // Cubic: from (x0, y0) to (x0 + length, y0 + rise), flat outside.
  // Sine: centre line y0, starting phase at x0.
  float x0 = 100.0f;
  float y0 = 240.0f;
  float length = 600.0f;
  float rise = 0.0f;
  float amplitude = 0.0f;
  float wavelength = 1.0f;
  // Polyline: count points, x strictly increasing; flat beyond the ends.
  uint8_t count = 0;
  Vec2 points[kMaxPolylinePoints] = {};

  CurvePoint at(float x) const;

  static PathCurve cubic(float rise, float x0 = 100.0f, float y0 = 240.0f, float length = 600.0f);
  static PathCurve sine(float y0, float amplitude, float wavelength, float x0 = 0.0f);
  // Returns a curve with count = 0 (flat at y = 0) if the points are invalid.
  static PathCurve polyline(const Vec2* points, int count);
};

// The three experiment targets: the path ends at (700, 240 + T).
enum class Target : uint8_t { Top, Middle, Bottom };
constexpr float target_rise(Target t) {
  return t == Target::Top ? -200.0f : (t == Target::Bottom ? 200.0f : 0.0f);
}
constexpr Vec2 target_point(Target t) { return {700.0f, 240.0f + target_rise(t)}; }

}  // namespace ff
