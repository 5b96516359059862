#pragma once
// Summary statistics for the benches, the stress report and the tests. Host only (double).
#include <functional>
#include <vector>

namespace ff::support {

// Root mean square; 0 for no values.
double rms(const std::vector<double>& values);
double mean(const std::vector<double>& values);
// p-th percentile (0..100) with linear interpolation between closest ranks
// (numpy's default); 0 for no values.
double percentile(std::vector<double> values, double p);

// Angle between two vectors in degrees, [0, 180]; 90 if either is zero
// (no direction carries no information either way).
double angle_deg(double ax, double ay, double bx, double by);

// The argument in [lo, hi] that minimises f, assumed unimodal near its
// minimum: a grid of `steps` points, then golden-section search around the
// best one down to `tolerance`.
double minimise(const std::function<double(double)>& f, double lo, double hi, int steps, double tolerance);

// An estimate of the finger's position at a time.
struct TimedPosition {
  double t_s = 0.0;
  double x = 0.0;
  double y = 0.0;
};
struct Position2 {
  double x = 0.0;
  double y = 0.0;
};

// The lag of `estimates` behind `truth`: the shift (ms, in [lo_ms, hi_ms])
// minimising sqrt(mean |estimate(t) - truth(t - shift)|^2). Positive: the
// estimate trails the finger.
double best_lag_ms(const std::vector<TimedPosition>& estimates, const std::function<Position2(double t_s)>& truth,
                   double lo_ms = -10.0, double hi_ms = 30.0);

}  // namespace ff::support
