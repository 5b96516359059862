#include "sensor_calibration.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "reference_path.hpp"

namespace ff::bench {

namespace {

constexpr double kPi = 3.14159265358979323846;

double median_of(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(mid), v.end());
  const double upper = v[mid];
  if (v.size() % 2 == 1) return upper;
  return 0.5 * (upper + *std::max_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(mid)));
}

// Mean of v over [t - window / 2, t + window / 2] at each t (fewer samples at the ends).
std::vector<double> moving_mean(const std::vector<double>& t, const std::vector<double>& v, double window_s) {
  std::vector<double> out(v.size());
  size_t lo = 0, hi = 0;
  double sum = 0.0;
  for (size_t i = 0; i < v.size(); ++i) {
    while (hi < v.size() && t[hi] <= t[i] + 0.5 * window_s) sum += v[hi++];
    while (t[lo] < t[i] - 0.5 * window_s) sum -= v[lo++];
    out[i] = sum / static_cast<double>(hi - lo);
  }
  return out;
}

// Leaves out of `run` the reports far from where the finger rests (a
// glitch, a second finger: hundreds of px away), which would read as a noise
// of many px: further on an axis from the run's median than the wander a
// resting finger may have plus 10 robust sigmas of that axis (a sensor may
// be noisier along one). Returns how many; `threshold_px` is the larger
// axis's largest distance kept.
size_t drop_glitches(ReportRun& run, double max_range_px, double& threshold_px) {
  // The median and the distance beyond which a report is a glitch, on one axis.
  const auto limits = [max_range_px](const std::vector<double>& v, double& median, double& threshold) {
    median = median_of(v);
    std::vector<double> deviations;
    for (double value : v) deviations.push_back(std::fabs(value - median));
    threshold = max_range_px + 10.0 * 1.4826 * median_of(deviations);  // 1.4826 MAD: sigma of a normal
  };
  double mx = 0.0, my = 0.0, tx = 0.0, ty = 0.0;
  limits(run.x, mx, tx);
  limits(run.y, my, ty);
  threshold_px = std::max(tx, ty);
  ReportRun kept;
  for (size_t i = 0; i < run.t.size(); ++i) {
    if (std::fabs(run.x[i] - mx) > tx || std::fabs(run.y[i] - my) > ty) continue;
    kept.t.push_back(run.t[i]);
    kept.x.push_back(run.x[i]);
    kept.y.push_back(run.y[i]);
  }
  const size_t dropped = run.t.size() - kept.t.size();
  run = std::move(kept);
  return dropped;
}

// One run, detrended: the residual of each axis and the range of its slow part.
struct Residual {
  std::vector<double> t, x, y;
};

// Sample autocovariance in bins of one nominal interval: bin k holds the
// pairs whose lag rounds to k intervals; x and y pooled.
struct LagBins {
  std::vector<double> lag_sum, product_sum, pairs;
  double zero_sum = 0.0, zero_count = 0.0;
};

LagBins autocovariance(const std::vector<Residual>& runs, double interval_s, size_t bins) {
  LagBins b;
  b.lag_sum.assign(bins + 1, 0.0);
  b.product_sum.assign(bins + 1, 0.0);
  b.pairs.assign(bins + 1, 0.0);
  const double max_lag = (static_cast<double>(bins) + 0.5) * interval_s;
  for (const Residual& r : runs) {
    for (size_t i = 0; i < r.t.size(); ++i) {
      b.zero_sum += r.x[i] * r.x[i] + r.y[i] * r.y[i];
      b.zero_count += 2.0;
      for (size_t j = i + 1; j < r.t.size() && r.t[j] - r.t[i] < max_lag; ++j) {
        const double lag = r.t[j] - r.t[i];
        const auto k = static_cast<size_t>(std::lround(lag / interval_s));
        if (k < 1 || k > bins) continue;
        b.lag_sum[k] += 2.0 * lag;
        b.product_sum[k] += r.x[i] * r.x[j] + r.y[i] * r.y[j];
        b.pairs[k] += 2.0;
      }
    }
  }
  return b;
}

// Power of the residual at frequency f: |sum r e^(-2 pi i f t)|^2 over runs and axes.
double power_at(const std::vector<Residual>& runs, double f_hz) {
  double power = 0.0;
  for (const Residual& r : runs) {
    double xc = 0.0, xs = 0.0, yc = 0.0, ys = 0.0;
    for (size_t i = 0; i < r.t.size(); ++i) {
      const double phase = 2.0 * kPi * f_hz * r.t[i];
      const double c = std::cos(phase), s = std::sin(phase);
      xc += r.x[i] * c;
      xs += r.x[i] * s;
      yc += r.y[i] * c;
      ys += r.y[i] * s;
    }
    power += xc * xc + xs * xs + yc * yc + ys * ys;
  }
  return power;
}

struct TremorPeak {
  double hz = 0.0;
  double ratio = 0.0;  // peak power over the median 0.3-1.5 Hz either side
};

TremorPeak find_tremor(const std::vector<Residual>& runs, const CalibrationOptions& o) {
  constexpr double kNear = 0.3, kFar = 1.5;
  const double step = o.tremor_step_hz, first = o.tremor_min_hz - kFar;
  const auto count = static_cast<size_t>(std::lround((o.tremor_max_hz - o.tremor_min_hz + 2.0 * kFar) / step)) + 1;
  std::vector<double> power(count);
  for (size_t i = 0; i < count; ++i) power[i] = power_at(runs, first + step * static_cast<double>(i));
  TremorPeak best;
  const auto near = static_cast<size_t>(std::lround(kNear / step)), far = static_cast<size_t>(std::lround(kFar / step));
  for (size_t i = far; i + far < count; ++i) {
    if (best.hz > 0.0 && power[i] <= power[static_cast<size_t>(std::lround((best.hz - first) / step))]) continue;
    std::vector<double> around;
    for (size_t j = i - far; j <= i + far; ++j)
      if (j + near < i || j > i + near) around.push_back(power[j]);
    best = {first + step * static_cast<double>(i), power[i] / std::max(median_of(around), 1e-300)};
  }
  return best;
}

// Least squares y ~ sum_j coef_j columns_j by the normal equations
// (at most 3 columns here); the squared error, or -1 if singular.
double least_squares(const std::vector<std::vector<double>>& columns, const std::vector<double>& y,
                     std::vector<double>& coef) {
  const size_t p = columns.size();
  std::vector<std::vector<double>> a(p, std::vector<double>(p + 1, 0.0));
  for (size_t r = 0; r < p; ++r) {
    for (size_t c = 0; c < p; ++c)
      for (size_t k = 0; k < y.size(); ++k) a[r][c] += columns[r][k] * columns[c][k];
    for (size_t k = 0; k < y.size(); ++k) a[r][p] += columns[r][k] * y[k];
  }
  for (size_t c = 0; c < p; ++c) {  // Gauss-Jordan with partial pivoting
    size_t pivot = c;
    for (size_t r = c + 1; r < p; ++r)
      if (std::fabs(a[r][c]) > std::fabs(a[pivot][c])) pivot = r;
    if (std::fabs(a[pivot][c]) < 1e-12 * (1.0 + std::fabs(a[c][c]))) return -1.0;
    std::swap(a[c], a[pivot]);
    for (size_t r = 0; r < p; ++r) {
      if (r == c) continue;
      const double f = a[r][c] / a[c][c];
      for (size_t k = c; k <= p; ++k) a[r][k] -= f * a[c][k];
    }
  }
  coef.assign(p, 0.0);
  for (size_t c = 0; c < p; ++c) coef[c] = a[c][p] / a[c][c];
  double sse = 0.0;
  for (size_t k = 0; k < y.size(); ++k) {
    double fit = 0.0;
    for (size_t c = 0; c < p; ++c) fit += coef[c] * columns[c][k];
    sse += (y[k] - fit) * (y[k] - fit);
  }
  return sse;
}

struct NoiseFit {
  double corr2 = 0.0, tau_s = 0.0, tremor2_half = 0.0, slow = 0.0;
  double sse = -1.0;  // < 0: no feasible fit
  size_t params = 0;
};

// The best fit with non-negative variances; with `tau_grid` empty, without the exponential.
NoiseFit fit_noise(const std::vector<double>& lag, const std::vector<double>& value, double tremor_hz,
                   const std::vector<double>& tau_grid) {
  NoiseFit best;
  const std::vector<double> no_tau = {0.0};
  for (const double tau : tau_grid.empty() ? no_tau : tau_grid) {
    for (const bool with_tremor : {true, false}) {
      if (with_tremor && tremor_hz <= 0.0) continue;
      std::vector<std::vector<double>> columns;
      if (tau > 0.0) {
        columns.emplace_back();
        for (double l : lag) columns.back().push_back(std::exp(-l / tau));
      }
      if (with_tremor) {
        columns.emplace_back();
        for (double l : lag) columns.back().push_back(std::cos(2.0 * kPi * tremor_hz * l));
      }
      columns.emplace_back(lag.size(), 1.0);
      std::vector<double> coef;
      const double sse = least_squares(columns, value, coef);
      if (sse < 0.0) continue;
      NoiseFit fit;
      size_t c = 0;
      if (tau > 0.0) {
        fit.corr2 = coef[c++];
        fit.tau_s = tau;
      }
      if (with_tremor) fit.tremor2_half = coef[c++];
      fit.slow = coef[c];
      fit.sse = sse;
      fit.params = columns.size() + (tau > 0.0 ? 1 : 0);
      if (fit.corr2 < 0.0 || fit.tremor2_half < 0.0) continue;
      if (best.sse < 0.0 || fit.sse < best.sse) best = fit;
    }
  }
  return best;
}

}  // namespace

bool calibrate_from_rest(const std::vector<host::TraceRow>& rows, const CalibrationOptions& options,
                         uint32_t latency_us, Calibration& out, std::string& error) {
  Calibration cal;
  cal.profile.latency_us = latency_us;
  SkippedReports skipped;
  const std::vector<ReportRun> runs =
      touch_runs(rows, rows.empty() ? 0 : rows.front().t_us, options.max_gap_s, &skipped);
  std::vector<double> intervals_us;  // whole microseconds, as stamped: their sums are exact
  for (const ReportRun& r : runs) {
    cal.reports += r.t.size();
    cal.duration_s += r.t.back() - r.t.front();
    for (size_t i = 1; i < r.t.size(); ++i) intervals_us.push_back(std::round((r.t[i] - r.t[i - 1]) * 1e6));
  }
  cal.runs = runs.size();
  cal.off_screen = skipped.off_screen;
  cal.not_after = skipped.not_after;
  char line[200];
  if (cal.reports < options.min_reports) {
    std::snprintf(line, sizeof line, "only %zu usable touch report%s (at least %zu needed: record a resting finger for ~10 s)",
                  cal.reports, cal.reports == 1 ? "" : "s", options.min_reports);
    error = line;
    if (skipped.off_screen + skipped.not_after > 0) {
      std::snprintf(line, sizeof line,
                    "; left out: %zu off the screen or not finite, %zu stamped at or before the one before",
                    skipped.off_screen, skipped.not_after);
      error += line;
    }
    return false;
  }
  if (intervals_us.empty()) {
    std::snprintf(line, sizeof line,
                  "no two of its %zu touch reports lie within %.2f s of each other (a longer gap or a lift splits "
                  "a recording): record a resting finger at the sensor's own rate",
                  cal.reports, options.max_gap_s);
    error = line;
    return false;
  }
  if (cal.duration_s < options.min_duration_s) {
    std::snprintf(line, sizeof line, "only %.2f s of touch reports (at least %.1f s needed: record a resting finger for ~10 s)",
                  cal.duration_s, options.min_duration_s);
    error = line;
    return false;
  }

  // Timing, in microseconds: a steady clock's jitter is then 0, not the 1e-10
  // of seconds' rounding.
  const double median_us = median_of(intervals_us);
  const double median_interval = median_us * 1e-6;
  // Symmetric about the median, so that cutting the tails of a wide jitter
  // does not move the mean.
  const double longest = options.max_interval_factor * median_us;
  const double shortest = (2.0 - options.max_interval_factor) * median_us;
  auto normal = [&](double dt) { return dt >= shortest && dt <= longest; };
  double sum = 0.0, sum2 = 0.0;
  for (double dt : intervals_us) {
    if (!normal(dt)) {
      ++cal.dropped_intervals;
      continue;
    }
    ++cal.intervals;
    sum += dt;
  }
  const double mean_us = sum / static_cast<double>(cal.intervals);
  for (double dt : intervals_us)
    if (normal(dt)) sum2 += (dt - mean_us) * (dt - mean_us);
  cal.median_interval_us = median_us;
  const double median_rate_hz = 1e6 / median_us;
  if (median_rate_hz > double{SensorProfileLimits::kMaxRateHz} || median_rate_hz < double{SensorProfileLimits::kMinRateHz}) {
    std::snprintf(line, sizeof line, "reports every %.0f us: not a sensor at %.0f-%.0f Hz", median_us,
                  double{SensorProfileLimits::kMinRateHz}, double{SensorProfileLimits::kMaxRateHz});
    error = line;
    return false;
  }
  cal.profile.report_rate_hz = static_cast<float>(1e6 / mean_us);
  cal.profile.jitter_us =
      static_cast<float>(cal.intervals > 1 ? std::sqrt(sum2 / static_cast<double>(cal.intervals - 1)) : 0.0);

  // The reports' stamps count for the timing above; the glitches' positions
  // are left out of the noise below.
  std::vector<ReportRun> resting = runs;
  for (ReportRun& r : resting) {
    double threshold_px = 0.0;
    const size_t dropped = drop_glitches(r, options.max_range_px, threshold_px);
    if (dropped > 0) cal.glitch_threshold_px = std::max(cal.glitch_threshold_px, threshold_px);
    cal.glitches += dropped;
  }
  resting.erase(std::remove_if(resting.begin(), resting.end(), [](const ReportRun& r) { return r.t.empty(); }),
                resting.end());

  // The residual of each run after its slow part.
  std::vector<Residual> residuals;
  for (const ReportRun& r : resting) {
    Residual res{r.t, r.x, r.y};
    const std::vector<double> mx = moving_mean(r.t, r.x, options.detrend_window_s);
    const std::vector<double> my = moving_mean(r.t, r.y, options.detrend_window_s);
    for (size_t i = 0; i < r.t.size(); ++i) {
      res.x[i] -= mx[i];
      res.y[i] -= my[i];
    }
    const auto [x_lo, x_hi] = std::minmax_element(mx.begin(), mx.end());
    const auto [y_lo, y_hi] = std::minmax_element(my.begin(), my.end());
    cal.range_px = std::max({cal.range_px, *x_hi - *x_lo, *y_hi - *y_lo});
    residuals.push_back(std::move(res));
  }
  if (cal.range_px > options.max_range_px) {
    std::snprintf(line, sizeof line,
                  "the finger is not resting: its 1 s mean moves %.1f px (at most %.0f px; record a finger held still)",
                  cal.range_px, options.max_range_px);
    error = line;
    return false;
  }

  // Tremor: a peak in the band that stands out of its neighbourhood.
  const TremorPeak peak = find_tremor(residuals, options);
  cal.tremor_peak_ratio = peak.ratio;
  const double tremor_hz = peak.ratio > options.tremor_peak_ratio ? peak.hz : 0.0;

  // The autocovariance and its fit.
  const auto bins = static_cast<size_t>(std::max(2.0, std::floor(options.max_lag_s / median_interval)));
  const LagBins lb = autocovariance(residuals, median_interval, bins);
  const double c0 = lb.zero_sum / lb.zero_count;
  if (!(c0 > 0.0)) {
    error = "the reports do not vary at all (0 px of noise): a sensor that repeats one position, or a file not "
            "recorded from a finger; a profile needs noise above 0 (record a finger resting on the real sensor)";
    return false;
  }
  std::vector<double> lag, value;
  for (size_t k = 1; k <= bins; ++k) {
    if (lb.pairs[k] == 0.0) continue;
    lag.push_back(lb.lag_sum[k] / lb.pairs[k]);
    value.push_back(lb.product_sum[k] / lb.pairs[k]);
  }
  cal.lag_bins = lag.size();
  std::vector<double> taus;
  const double tau_lo = 0.5 * median_interval, tau_hi = std::max(options.max_tau_s, 2.0 * tau_lo);
  for (int i = 0; i < 60; ++i) taus.push_back(tau_lo * std::pow(tau_hi / tau_lo, i / 59.0));
  const NoiseFit without = fit_noise(lag, value, tremor_hz, {});
  const NoiseFit with = fit_noise(lag, value, tremor_hz, taus);
  NoiseFit fit = without;
  if (with.sse >= 0.0 && without.sse >= 0.0 && lag.size() > with.params) {
    const double bin_variance = std::max(with.sse / static_cast<double>(lag.size() - with.params), 1e-300);
    cal.correlated_improvement = (without.sse - with.sse) / bin_variance;
    if (cal.correlated_improvement > options.correlated_improvement) fit = with;
  }
  if (fit.sse < 0.0) {
    error = "the noise's autocovariance could not be fitted";
    return false;
  }
  cal.total_noise_px = std::sqrt(c0);
  cal.slow_px2 = fit.slow;
  cal.fit_rms_px2 = std::sqrt(fit.sse / static_cast<double>(lag.size()));
  cal.tremor_hz = fit.tremor2_half > 0.0 ? tremor_hz : 0.0;
  // White is what C(0) has beyond the terms that persist over lags; at least
  // a hundredth of C(0), so that the profile stays valid.
  const double white2 = std::max(c0 - fit.corr2 - fit.tremor2_half - fit.slow, 0.01 * c0);
  cal.profile.white_noise_px = static_cast<float>(std::sqrt(white2));
  cal.profile.correlated_noise_px = static_cast<float>(std::sqrt(fit.corr2));
  cal.profile.correlation_time_ms = static_cast<float>(fit.corr2 > 0.0 ? fit.tau_s * 1e3 : 0.0);
  cal.profile.tremor_px = static_cast<float>(std::sqrt(2.0 * fit.tremor2_half));
  cal.profile.tremor_hz = static_cast<float>(cal.tremor_hz);
  if (!is_valid(cal.profile)) {
    std::snprintf(line, sizeof line, "the estimate (noise %.1f px, jitter %.0f us) is outside the profile's limits",
                  cal.total_noise_px, double{cal.profile.jitter_us});
    error = line;
    return false;
  }
  out = cal;
  return true;
}

}  // namespace ff::bench
