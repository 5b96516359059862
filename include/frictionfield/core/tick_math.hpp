#pragma once
// sin, cos and atan for the 2 kHz tick, in float, without libm: newlib's
// sinf/cosf/atanf live in flash and read their constant tables there, which
// costs more on a cold cache than the whole rest of a tick (docs/cycle-model.md).
// Range reduction plus short Taylor polynomials, accurate to a few float ulp.
namespace ff {

struct SinCos {
  float sin;
  float cos;
};

// Nearest integer (ties away from zero) without a libm call (the FPv4 has no
// VRINT); floats of magnitude 2^23 and more are integers already.
float nearest_integer(float v);

// sin and cos of r for |r| <= pi/4 (beyond, the error grows quickly).
SinCos sincos_reduced(float r);

// sin and cos of 2 pi turns, for any finite turns: the phase is reduced
// exactly (whole turns, then quarter turns) to |2 pi r| <= pi/4.
SinCos sincos_turns(float turns);

// atan(x) for every float (+-inf -> +-pi/2, NaN -> NaN).
float arctan(float x);

}  // namespace ff
