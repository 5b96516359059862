// The complex solver (complex_solve.hpp) against systems built from a known
// solution in double: b = A x computed here, independently of the solver.
#include "frictionfield/core/complex_solve.hpp"

#include <gtest/gtest.h>

#include <complex>

namespace ff {
namespace {

using ComplexD = std::complex<double>;

struct System {
  ComplexF a[kMaxComplexSolve][kMaxComplexSolve] = {};
  ComplexF b[kMaxComplexSolve] = {};
};

// A x = b for the given A (row-major, n x n) and x, b in double.
System system_for(const ComplexD* a, const ComplexD* x, int n) {
  System s;
  for (int i = 0; i < n; ++i) {
    ComplexD sum = 0.0;
    for (int j = 0; j < n; ++j) {
      s.a[i][j] = ComplexF(a[i * n + j]);
      sum += a[i * n + j] * x[j];
    }
    s.b[i] = ComplexF(sum);
  }
  return s;
}

void expect_solution(System s, const ComplexD* x, int n, double tolerance) {
  solve_in_place(s.a, s.b, n);
  for (int i = 0; i < n; ++i) {
    EXPECT_NEAR(s.b[i].real(), x[i].real(), tolerance) << "x[" << i << "]";
    EXPECT_NEAR(s.b[i].imag(), x[i].imag(), tolerance) << "x[" << i << "]";
  }
}

TEST(ComplexSolve, MagnitudeSquared) { EXPECT_EQ(magnitude2({3.0f, -4.0f}), 25.0f); }

TEST(ComplexSolve, AFullFiveByFiveComplexSystem) {
  const ComplexD a[25] = {{4, 1},  {1, -1}, {0, 2},  {1, 0},   {0.5, 0.5},  //
                          {1, 0},  {5, -2}, {1, 1},  {0, -1},  {2, 0},      //
                          {0, 1},  {2, 0},  {6, 1},  {1, 2},   {0, 0},      //
                          {1, -1}, {0, 0},  {1, 0},  {3, 3},   {1, 1},      //
                          {0, 0},  {1, 1},  {0, -2}, {1, 0},   {4, -1}};
  const ComplexD x[5] = {{1, 2}, {-0.5, 0}, {0, -3}, {2.5, 1}, {-1, -1}};
  expect_solution(system_for(a, x, 5), x, 5, 1e-5);
}

TEST(ComplexSolve, AZeroOnTheDiagonalIsPivotedAway) {
  // Without a row exchange the first step divides by 0.
  const ComplexD a[9] = {{0, 0}, {1, 0}, {0, 1},  //
                         {2, 0}, {0, 0}, {1, 0},  //
                         {0, 1}, {1, 1}, {3, 0}};
  const ComplexD x[3] = {{1, -1}, {2, 0}, {0, 0.5}};
  expect_solution(system_for(a, x, 3), x, 3, 1e-5);
}

TEST(ComplexSolve, TheLargerPivotIsTaken) {
  // A tiny but non-zero first pivot: eliminating with it multiplies the second
  // row by 10^6, and float then keeps only about 5 % of x[0]. The larger pivot loses nothing.
  const ComplexD a[4] = {{1e-6, 0}, {1, 0}, {1, 0}, {1, 0}};
  const ComplexD x[2] = {{1, 0}, {1, 0}};
  expect_solution(system_for(a, x, 2), x, 2, 1e-5);
}

TEST(ComplexSolve, OnlyTheFirstNRowsAndColumnsAreUsed) {
  const ComplexD a[1] = {{2, 0}}, x[1] = {{0, 3}};
  System s = system_for(a, x, 1);
  s.a[1][0] = s.a[0][1] = s.a[1][1] = ComplexF(1e30f, 1e30f);
  s.b[1] = ComplexF(7.0f, 7.0f);
  solve_in_place(s.a, s.b, 1);
  EXPECT_EQ(s.b[0], ComplexF(0.0f, 3.0f));
  EXPECT_EQ(s.b[1], ComplexF(7.0f, 7.0f));
}

}  // namespace
}  // namespace ff
