#include "frictionfield/core/tick_math.hpp"

#include <cmath>
#include <cstdint>

#include "frictionfield/core/fastrun.hpp"
#include "frictionfield/core/geometry.hpp"

namespace ff {

namespace {

// Half away from zero, for |v| < 2^23 (where the conversion is exact and defined).
inline __attribute__((always_inline)) int32_t round_half_away(float v) {
  return static_cast<int32_t>(v + (v >= 0.0f ? 0.5f : -0.5f));
}

// Compiled into sincos_turns: a call costs about as much as the polynomials.
inline __attribute__((always_inline)) SinCos taylor_sincos(float r) {
  // Taylor series to r^9 and r^10: at |r| = pi/4 the next terms are
  // (pi/4)^11 / 11! < 2e-9 and (pi/4)^12 / 12! < 2e-10, far below a float ulp.
  const float z = r * r;
  const float s = r + r * z * (-1.0f / 6.0f + z * (1.0f / 120.0f + z * (-1.0f / 5040.0f + z * (1.0f / 362880.0f))));
  const float c = 1.0f + z * (-0.5f + z * (1.0f / 24.0f + z * (-1.0f / 720.0f + z * (1.0f / 40320.0f +
                                                                                      z * (-1.0f / 3628800.0f)))));
  return {s, c};
}

}  // namespace

FF_FASTRUN float nearest_integer(float v) {
  if (!(std::fabs(v) < 8388608.0f)) return v;
  return static_cast<float>(round_half_away(v));
}

FF_FASTRUN SinCos sincos_reduced(float r) { return taylor_sincos(r); }

FF_FASTRUN SinCos sincos_turns(float turns) {
  // From 2^23 on every float is a whole number of turns (sin 0, cos 1); inf
  // and NaN have no phase (NaN, like sin(inf): a wavelength so short that
  // x / wavelength overflows; the renderer's clamp makes it 0.5). Below it the
  // conversions to int are exact, and defined: NaN never reaches one.
  if (!(std::fabs(turns) < 8388608.0f)) {
    const float zero_or_nan = turns - turns;
    return {zero_or_nan, 1.0f + zero_or_nan};
  }
  const float fraction = turns - static_cast<float>(round_half_away(turns));  // -0.5 .. 0.5
  const int32_t quarters = round_half_away(4.0f * fraction);                    // -2 .. 2
  const SinCos k = taylor_sincos(2.0f * kPi * (fraction - 0.25f * static_cast<float>(quarters)));
  switch ((quarters + 4) & 3) {
    case 1: return {k.cos, -k.sin};
    case 2: return {-k.sin, -k.cos};
    case 3: return {-k.cos, k.sin};
    default: return k;
  }
}

FF_FASTRUN float arctan(float x) {
  // atan(-x) = -atan(x); atan(x) = pi/2 - atan(1/x) for x > 1; then
  // atan(t) = pi/6 + atan((sqrt3 t - 1) / (t + sqrt3)) for t > tan(pi/12),
  // which leaves |u| <= tan(pi/12) = 0.268 for the series to u^11
  // (next term 0.268^13 / 13 < 3e-9).
  constexpr float kSqrt3 = 1.7320508075688772f;
  constexpr float kTanPi12 = 0.2679491924311227f;
  const bool negative = x < 0.0f;
  float t = std::fabs(x);
  const bool inverted = t > 1.0f;
  if (inverted) t = 1.0f / t;  // +inf -> 0
  const bool shifted = t > kTanPi12;
  if (shifted) t = (kSqrt3 * t - 1.0f) / (t + kSqrt3);
  const float z = t * t;
  float a = t + t * z * (-1.0f / 3.0f + z * (1.0f / 5.0f + z * (-1.0f / 7.0f + z * (1.0f / 9.0f + z * (-1.0f / 11.0f)))));
  if (shifted) a += kPi / 6.0f;
  if (inverted) a = kPi / 2.0f - a;
  return negative ? -a : a;
}

}  // namespace ff
