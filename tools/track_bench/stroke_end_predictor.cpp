#include "stroke_end_predictor.hpp"

#include "support/models/motion.hpp"

namespace ff::bench {

MinJerkFit fit_min_jerk_at(const std::vector<TimedReport>& reports, double start_s, double duration_s) {
  // x_i = from_x + travel_x m_i (and y), m_i the profile at report i: two
  // linear regressions on the same m, one normal matrix.
  double n = 0.0, sm = 0.0, smm = 0.0, sx = 0.0, sy = 0.0, smx = 0.0, smy = 0.0, sxx = 0.0, syy = 0.0;
  for (const TimedReport& r : reports) {
    const double m = tracegen::min_jerk((r.t_s - start_s) / duration_s);
    n += 1.0;
    sm += m;
    smm += m * m;
    sx += r.x;
    sy += r.y;
    smx += m * r.x;
    smy += m * r.y;
    sxx += r.x * r.x;
    syy += r.y * r.y;
  }
  MinJerkFit f;
  f.start_s = start_s;
  f.duration_s = duration_s;
  const double det = n * smm - sm * sm;
  if (!(det > 1e-9 * n * n)) return f;  // the profile constant over the reports
  f.travel_x = (n * smx - sm * sx) / det;
  f.travel_y = (n * smy - sm * sy) / det;
  f.from_x = (sx - f.travel_x * sm) / n;
  f.from_y = (sy - f.travel_y * sm) / n;
  // Residual sum of squares of each regression: S_zz - from S_z - travel S_mz.
  const double cost = (sxx - f.from_x * sx - f.travel_x * smx) + (syy - f.from_y * sy - f.travel_y * smy);
  f.cost = cost > 0.0 ? cost : 0.0;
  // Ordinary least squares: var(travel) = sigma^2 n / det, sigma^2 from the
  // residuals of the 2 n coordinates less the 4 fitted values.
  if (n > 2.0) f.travel_variance = f.cost / (2.0 * n - 4.0) * n / det;
  return f;
}

MinJerkFit fit_min_jerk(const std::vector<TimedReport>& reports, const MinJerkFit& guess, double first_motion_s) {
  constexpr double kMinDuration = 0.04;
  MinJerkFit best;
  auto consider = [&](double start_s, double duration_s) {
    if (duration_s < kMinDuration) return;
    const MinJerkFit f = fit_min_jerk_at(reports, start_s, duration_s);
    if (f.cost < best.cost) best = f;
  };
  if (guess.valid()) {
    consider(guess.start_s, guess.duration_s);
  } else {
    for (int i = 0; i < 24; ++i) {
      const double duration = 0.06 * std::pow(50.0, i / 23.0);  // 60 ms - 3 s
      for (int j = 0; j < 12; ++j) consider(first_motion_s - 0.15 + 0.15 * j / 11.0, duration);
    }
  }
  if (!best.valid()) return best;
  // Pattern search: every neighbour at the current steps, halved when none is better.
  double step_start = 0.01, step_duration = 0.05 * best.duration_s;
  for (int i = 0; i < 30 && step_start > 2e-4; ++i) {
    const MinJerkFit centre = best;
    for (int a = -1; a <= 1; ++a)
      for (int b = -1; b <= 1; ++b)
        if (a != 0 || b != 0) consider(centre.start_s + a * step_start, centre.duration_s + b * step_duration);
    if (!(best.cost < centre.cost)) {
      step_start *= 0.5;
      step_duration *= 0.5;
    }
  }
  return best;
}

void StrokeEndPredictor::restart() {
  stroke_.clear();
  first_motion_s_ = NAN;
  fit_ = MinJerkFit{};
}

bool StrokeEndPredictor::report(double t_s, double x, double y) {
  stroke_.push_back({t_s, x, y});
  const TimedReport& first = stroke_.front();
  if (std::isnan(first_motion_s_) && std::hypot(x - first.x, y - first.y) >= options_.min_motion_px) first_motion_s_ = t_s;
  if (std::isnan(first_motion_s_)) return false;  // not yet moved: nothing to fit
  fit_ = fit_min_jerk(stroke_, fit_, first_motion_s_);
  const double d = fit_.distance_px();
  if (!fit_.valid() || d < options_.min_distance_px || d * d < options_.min_sigmas * options_.min_sigmas * fit_.travel_variance ||
      t_s < fit_.end_s())
    return false;
  stroke_.assign(1, TimedReport{t_s, x, y});  // the next stroke begins here
  fit_ = MinJerkFit{};
  first_motion_s_ = NAN;
  return true;
}

}  // namespace ff::bench
