#include "support/statistics.hpp"

#include <algorithm>
#include <cmath>

namespace ff::support {

double rms(const std::vector<double>& values) {
  if (values.empty()) return 0.0;
  double sum = 0.0;
  for (double v : values) sum += v * v;
  return std::sqrt(sum / static_cast<double>(values.size()));
}

double mean(const std::vector<double>& values) {
  if (values.empty()) return 0.0;
  double sum = 0.0;
  for (double v : values) sum += v;
  return sum / static_cast<double>(values.size());
}

double percentile(std::vector<double> values, double p) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const double rank = std::clamp(p, 0.0, 100.0) / 100.0 * static_cast<double>(values.size() - 1);
  const size_t below = static_cast<size_t>(std::floor(rank));
  const size_t above = std::min(below + 1, values.size() - 1);
  const double frac = rank - static_cast<double>(below);
  return values[below] + frac * (values[above] - values[below]);
}

double angle_deg(double ax, double ay, double bx, double by) {
  const double na = std::hypot(ax, ay), nb = std::hypot(bx, by);
  if (!(na > 0.0) || !(nb > 0.0)) return 90.0;
  const double c = std::clamp((ax * bx + ay * by) / (na * nb), -1.0, 1.0);
  return std::acos(c) * 180.0 / 3.14159265358979323846;
}

double minimise(const std::function<double(double)>& f, double lo, double hi, int steps, double tolerance) {
  steps = std::max(steps, 2);
  const double step = (hi - lo) / (steps - 1);
  double best_x = lo, best_f = f(lo);
  for (int i = 1; i < steps; ++i) {
    const double x = lo + i * step;
    const double fx = f(x);
    if (fx < best_f) best_f = fx, best_x = x;
  }
  // Golden section on the bracket around the best grid point.
  const double phi = (std::sqrt(5.0) - 1.0) / 2.0;
  double a = std::max(lo, best_x - step), b = std::min(hi, best_x + step);
  double c = b - phi * (b - a), d = a + phi * (b - a);
  double fc = f(c), fd = f(d);
  while (b - a > tolerance) {
    if (fc < fd) {
      b = d, d = c, fd = fc;
      c = b - phi * (b - a), fc = f(c);
    } else {
      a = c, c = d, fc = fd;
      d = a + phi * (b - a), fd = f(d);
    }
  }
  const double x = 0.5 * (a + b);
  return f(x) <= best_f ? x : best_x;
}

double best_lag_ms(const std::vector<TimedPosition>& estimates, const std::function<Position2(double t_s)>& truth,
                   double lo_ms, double hi_ms) {
  if (estimates.empty()) return 0.0;
  auto rmse_at = [&](double shift_ms) {
    double sum = 0.0;
    for (const TimedPosition& e : estimates) {
      const Position2 p = truth(e.t_s - shift_ms * 1e-3);
      sum += (e.x - p.x) * (e.x - p.x) + (e.y - p.y) * (e.y - p.y);
    }
    return std::sqrt(sum / static_cast<double>(estimates.size()));
  };
  const int steps = static_cast<int>(std::lround(hi_ms - lo_ms)) / 2 + 1;  // ~2 ms grid
  return minimise(rmse_at, lo_ms, hi_ms, steps, 0.02);
}

}  // namespace ff::support
