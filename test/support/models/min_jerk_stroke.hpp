#pragma once
// A minimum-jerk stroke for the tests of the stroke end predictors, its
// profile written out here (10 tau^3 - 15 tau^4 + 6 tau^5), independent of
// the code under test (core/min_jerk.hpp, which the trace generator uses).

namespace ff::testing {

inline double min_jerk_profile(double tau) {
  if (tau <= 0.0) return 0.0;
  if (tau >= 1.0) return 1.0;
  return tau * tau * tau * (10.0 - 15.0 * tau + 6.0 * tau * tau);
}

struct MinJerkStroke {
  double start_s, duration_s, from_x, from_y, travel_x, travel_y;
  double end_s() const { return start_s + duration_s; }
  double x(double t) const { return from_x + travel_x * min_jerk_profile((t - start_s) / duration_s); }
  double y(double t) const { return from_y + travel_y * min_jerk_profile((t - start_s) / duration_s); }
};

}  // namespace ff::testing
