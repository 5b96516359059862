#include "frictionfield/core/complex_solve.hpp"

#include <utility>

namespace ff {

namespace {

// Products and quotients written out in float. std::complex's own operators
// call libgcc's __mulsc3 / __divsc3 for C99's infinity rules, and on the M4
// __divsc3 computes in software double; the pivots here are finite and non-zero.
ComplexF times(ComplexF a, ComplexF b) {
  return {a.real() * b.real() - a.imag() * b.imag(), a.real() * b.imag() + a.imag() * b.real()};
}
ComplexF over(ComplexF a, ComplexF b) { return times(a, std::conj(b)) * (1.0f / magnitude2(b)); }

}  // namespace

void solve_in_place(ComplexF a[kMaxComplexSolve][kMaxComplexSolve], ComplexF b[kMaxComplexSolve], int n) {
  for (int col = 0; col < n; ++col) {
    int pivot = col;
    for (int r = col + 1; r < n; ++r)
      if (magnitude2(a[r][col]) > magnitude2(a[pivot][col])) pivot = r;
    for (int j = 0; j < n; ++j) std::swap(a[col][j], a[pivot][j]);
    std::swap(b[col], b[pivot]);
    for (int r = col + 1; r < n; ++r) {
      const ComplexF f = over(a[r][col], a[col][col]);
      for (int j = col; j < n; ++j) a[r][j] -= times(f, a[col][j]);
      b[r] -= times(f, b[col]);
    }
  }
  for (int r = n - 1; r >= 0; --r) {
    for (int j = r + 1; j < n; ++j) b[r] -= times(a[r][j], b[j]);
    b[r] = over(b[r], a[r][r]);
  }
}

}  // namespace ff
