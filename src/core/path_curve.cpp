#include "frictionfield/core/path_curve.hpp"

#include "frictionfield/core/fastrun.hpp"
#include "frictionfield/core/tick_math.hpp"

#include <cmath>

namespace ff {

FF_FASTRUN CurvePoint PathCurve::at(float x) const {
  switch (kind) {
    case CurveKind::Cubic: {
      // y = -2T/L^3 s^3 + 3T/L^2 s^2 + y0 on s in [0, L]; flat outside.
      const float per_px = 1.0f / length;  // one division
      const float t = clamp(x - x0, 0.0f, length) * per_px;
      const float y = y0 + rise * t * t * (3.0f - 2.0f * t);
      const float slope = 6.0f * rise * per_px * t * (1.0f - t);
      return {y, slope};
    }
    case CurveKind::Sine: {
      const float per_px = 1.0f / wavelength;  // turns per pixel
      const SinCos sc = sincos_turns((x - x0) * per_px);
      return {y0 + amplitude * sc.sin, amplitude * (2.0f * kPi * per_px) * sc.cos};
    }
    case CurveKind::Polyline: {
      if (count == 0) return {0.0f, 0.0f};
      if (x <= points[0].x) return {points[0].y, 0.0f};
      for (int i = 1; i < count; ++i) {
        if (x <= points[i].x) {
          const Vec2 a = points[i - 1];
          const Vec2 b = points[i];
          const float slope = (b.y - a.y) / (b.x - a.x);
          return {a.y + slope * (x - a.x), slope};
        }
      }
      return {points[count - 1].y, 0.0f};
    }
  }
  return {0.0f, 0.0f};
}

PathCurve PathCurve::cubic(float rise, float x0, float y0, float length) {
  PathCurve c;  // Cubic is the default kind
  c.rise = rise;
  c.x0 = x0;
  c.y0 = y0;
  c.length = length;
  return c;
}

PathCurve PathCurve::sine(float y0, float amplitude, float wavelength, float x0) {
  PathCurve c;
  c.kind = CurveKind::Sine;
  c.y0 = y0;
  c.amplitude = amplitude;
  c.wavelength = wavelength;
  c.x0 = x0;
  return c;
}

PathCurve PathCurve::polyline(const Vec2* pts, int n) {
  PathCurve c;
  c.kind = CurveKind::Polyline;
  if (pts == nullptr || n < 2 || n > kMaxPolylinePoints) return c;
  for (int i = 0; i < n; ++i) {
    if (!is_finite(pts[i]) || (i > 0 && !(pts[i].x > pts[i - 1].x))) return c;
  }
  for (int i = 0; i < n; ++i) c.points[i] = pts[i];
  c.count = static_cast<uint8_t>(n);
  return c;
}

}  // namespace ff
