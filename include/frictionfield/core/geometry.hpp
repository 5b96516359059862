#pragma once
// Screen geometry and a minimal 2-D vector: everything in screen pixels
// (800 x 480, origin top-left, y down; 1 px ~ 0.2 mm).
#include <cmath>

namespace ff {

constexpr float kPi = 3.14159265358979f;
constexpr float kScreenWidthPx = 800.0f;
constexpr float kScreenHeightPx = 480.0f;
// The screen as a closed domain of pixel centres: max|G| and tables cover it.
constexpr float kScreenMaxX = kScreenWidthPx - 1.0f;
constexpr float kScreenMaxY = kScreenHeightPx - 1.0f;

struct Vec2 {
  float x = 0.0f;
  float y = 0.0f;
};

constexpr Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
constexpr Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
constexpr Vec2 operator*(float s, Vec2 a) { return {s * a.x, s * a.y}; }
constexpr float dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
inline float length(Vec2 a) { return std::sqrt(dot(a, a)); }
// Not NaN, not infinite. std::isfinite is a call to newlib's __fpclassifyf on
// the M4 (in flash, off the tick's RAM path); this is one VABS and a compare.
inline bool is_finite(float v) { return std::fabs(v) <= 3.40282347e38f; }
inline bool is_finite(Vec2 a) { return is_finite(a.x) && is_finite(a.y); }

constexpr float clamp(float v, float lo, float hi) { return v < lo ? lo : (v > hi ? hi : v); }

// 0 at t <= 0, 1 at t >= 1, and 3t^2 - 2t^3 between: an S-shaped fade (the
// quintic smootherstep of field_element.hpp where the slope's ends matter too).
constexpr float smoothstep(float t) {
  t = clamp(t, 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

// NaN-safe clamp to [lo, hi]: NaN maps to `fallback`.
inline float clamp_finite(float v, float lo, float hi, float fallback) {
  return std::isnan(v) ? fallback : clamp(v, lo, hi);
}

}  // namespace ff
