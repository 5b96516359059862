#pragma once
// Small dense complex linear systems in float: the direction filter's
// frequency response to the tremor (velocity_noise.cpp) is one solve of
// (I - M / z) x = K per frequency. Computed per configuration, not per tick.
#include <complex>

namespace ff {

using ComplexF = std::complex<float>;
constexpr int kMaxComplexSolve = 5;  // the five-state direction filter

inline float magnitude2(ComplexF a) { return a.real() * a.real() + a.imag() * a.imag(); }  // |a|^2

// Solves a x = b for n <= kMaxComplexSolve by Gaussian elimination with
// partial pivoting: b becomes x, a is overwritten. a must be non-singular.
void solve_in_place(ComplexF a[kMaxComplexSolve][kMaxComplexSolve], ComplexF b[kMaxComplexSolve], int n);

}  // namespace ff
