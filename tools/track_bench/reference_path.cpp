#include "reference_path.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "frictionfield/core/geometry.hpp"

namespace ff::bench {

namespace {

// Signed: a stamp before t0 (rows out of order, a clock stepped back) is in
// the past, not 2^64 us ahead.
double seconds_since(uint64_t t_us, uint64_t t0_us) {
  return static_cast<double>(static_cast<int64_t>(t_us - t0_us)) * 1e-6;
}

bool on_screen(double x, double y) {
  return std::isfinite(x) && std::isfinite(y) && x >= 0.0 && y >= 0.0 && x <= static_cast<double>(kScreenMaxX) &&
         y <= static_cast<double>(kScreenMaxY);
}

}  // namespace

AxisPass filter_axis(const std::vector<double>& t, const std::vector<double>& z, const SmootherOptions& options,
                     const std::vector<bool>* standstill) {
  const size_t n = t.size();
  AxisPass f;
  f.t = t;
  f.predicted_p.resize(n);
  f.predicted_v.resize(n);
  f.filtered_p.resize(n);
  f.filtered_v.resize(n);
  f.predicted_cov.resize(n);
  f.filtered_cov.resize(n);
  if (n == 0) return f;
  const double r = options.measurement_noise_px * options.measurement_noise_px;
  const auto still = [standstill](size_t k) { return standstill != nullptr && (*standstill)[k]; };
  double p = z[0], v = 0.0;
  AxisCov c{1e12, 0.0, 1e12};  // nothing known before the first report: a diffuse prior
  for (size_t k = 0; k < n; ++k) {
    if (k > 0) {
      const double dt = t[k] - t[k - 1];
      if (still(k - 1) && !still(k)) c = {c.pp, 0.0, kStartSpeedSigmaPxS * kStartSpeedSigmaPxS};  // a start
      const double q = still(k) ? 0.0 : options.accel_noise_px2_s3;
      p += v * dt;  // predict: F = [1 dt; 0 1], Q = q [dt^3/3 dt^2/2; dt^2/2 dt]
      c = {c.pp + 2.0 * dt * c.pv + dt * dt * c.vv + q * dt * dt * dt / 3.0, c.pv + dt * c.vv + q * dt * dt / 2.0,
           c.vv + q * dt};
    }
    f.predicted_p[k] = p;
    f.predicted_v[k] = v;
    f.predicted_cov[k] = c;
    const double s = c.pp + r, kp = c.pp / s, kv = c.pv / s, innovation = z[k] - p;  // update: H = [1 0]
    p += kp * innovation;
    v += kv * innovation;
    c = {c.pp * r / s, c.pv * r / s, c.vv - kv * c.pv};  // 1 - kp = r / s, without the cancellation
    if (still(k)) {  // known: not moving
      v = 0.0;
      c = {c.pp, 0.0, 0.0};
    }
    f.filtered_p[k] = p;
    f.filtered_v[k] = v;
    f.filtered_cov[k] = c;
  }
  return f;
}

void smooth_step(const AxisPass& pass, size_t k, double& p, double& v) {
  // x_s(k) = x_f(k) + G (x_s(k+1) - x_p(k+1)), G = P_f F^T P_p(k+1)^-1.
  const double dt = pass.t[k + 1] - pass.t[k];
  const AxisCov& f = pass.filtered_cov[k];
  const AxisCov& pr = pass.predicted_cov[k + 1];
  // P_f F^T = [f.pp + dt f.pv, f.pv; f.pv + dt f.vv, f.vv]
  const double a00 = f.pp + dt * f.pv, a01 = f.pv, a10 = f.pv + dt * f.vv, a11 = f.vv;
  const double det = pr.pp * pr.vv - pr.pv * pr.pv;
  const double i00 = pr.vv / det, i01 = -pr.pv / det, i11 = pr.pp / det;
  const double g00 = a00 * i00 + a01 * i01, g01 = a00 * i01 + a01 * i11;
  const double g10 = a10 * i00 + a11 * i01, g11 = a10 * i01 + a11 * i11;
  const double dp = p - pass.predicted_p[k + 1], dv = v - pass.predicted_v[k + 1];
  p = pass.filtered_p[k] + g00 * dp + g01 * dv;
  v = pass.filtered_v[k] + g10 * dp + g11 * dv;
}

void smooth_pass(const AxisPass& pass, std::vector<double>& position, std::vector<double>& velocity) {
  const size_t n = pass.t.size();
  position.assign(n, 0.0);
  velocity.assign(n, 0.0);
  if (n == 0) return;
  double p = pass.filtered_p[n - 1], v = pass.filtered_v[n - 1];
  position[n - 1] = p;
  velocity[n - 1] = v;
  for (size_t k = n - 1; k-- > 0;) {
    smooth_step(pass, k, p, v);
    position[k] = p;
    velocity[k] = v;
  }
}

void smooth_axis(const std::vector<double>& t, const std::vector<double>& z, const SmootherOptions& options,
                 std::vector<double>& position, std::vector<double>& velocity) {
  smooth_pass(filter_axis(t, z, options), position, velocity);
}

ReferencePath ReferencePath::from_truth(const std::vector<host::TraceRow>& rows,
                                        const std::vector<host::TruthPoint>& truth, uint64_t t0_us) {
  ReferencePath path;
  std::vector<PathNode> segment;
  auto close = [&] {
    if (segment.size() >= 2) {
      for (size_t k = 0; k < segment.size(); ++k) {  // central differences, one-sided at the ends
        const PathNode& a = segment[k == 0 ? 0 : k - 1];
        const PathNode& b = segment[k + 1 == segment.size() ? k : k + 1];
        segment[k].vx = (b.x - a.x) / (b.t_s - a.t_s);
        segment[k].vy = (b.y - a.y) / (b.t_s - a.t_s);
      }
      path.segments_.push_back(segment);
    }
    segment.clear();
  };
  for (size_t i = 0; i < rows.size() && i < truth.size(); ++i) {
    if (!std::isfinite(truth[i].x) || !std::isfinite(truth[i].y)) {
      close();  // lifted
      continue;
    }
    const double t = seconds_since(rows[i].t_us, t0_us);
    if (!segment.empty() && !(t > segment.back().t_s)) continue;  // a duplicate or out-of-order stamp
    segment.push_back({t, truth[i].x, truth[i].y, 0.0, 0.0});
  }
  close();
  return path;
}

std::vector<ReportRun> touch_runs(const std::vector<host::TraceRow>& rows, uint64_t t0_us, double max_gap_s,
                                  SkippedReports* skipped) {
  SkippedReports skips;
  std::vector<ReportRun> runs;
  ReportRun run;
  auto close = [&] {
    if (!run.t.empty()) runs.push_back(std::exchange(run, {}));
  };
  for (const host::TraceRow& row : rows) {
    const double ts = seconds_since(row.t_us, t0_us);
    if (!row.touch) {
      close();
      continue;
    }
    const double rx = static_cast<double>(row.x), ry = static_cast<double>(row.y);
    if (!on_screen(rx, ry)) {  // sensor faults: skipped
      ++skips.off_screen;
      continue;
    }
    if (!run.t.empty() && !(ts > run.t.back())) {
      ++skips.not_after;
      continue;
    }
    if (!run.t.empty() && ts - run.t.back() > max_gap_s) close();
    run.t.push_back(ts);
    run.x.push_back(rx);
    run.y.push_back(ry);
  }
  close();
  if (skipped) *skipped = skips;
  return runs;
}

ReferencePath ReferencePath::smoothed(const std::vector<host::TraceRow>& rows, uint64_t t0_us,
                                      const SmootherOptions& options) {
  ReferencePath path;
  for (const ReportRun& run : touch_runs(rows, t0_us, options.max_gap_s)) {
    if (run.t.size() < 2) continue;
    std::vector<double> px, vx, py, vy;
    smooth_axis(run.t, run.x, options, px, vx);
    smooth_axis(run.t, run.y, options, py, vy);
    std::vector<PathNode> segment(run.t.size());
    for (size_t k = 0; k < run.t.size(); ++k) segment[k] = {run.t[k], px[k], py[k], vx[k], vy[k]};
    path.segments_.push_back(std::move(segment));
  }
  return path;
}

tracegen::TrueState ReferencePath::at(double t_s, double rest_speed_px_s) const {
  tracegen::TrueState state;
  double nearest = HUGE_VAL;
  for (const std::vector<PathNode>& s : segments_) {
    // Off the screen (or unseen) the finger is where it was last seen, or first seen next.
    const PathNode& end = t_s < s.front().t_s ? s.front() : s.back();
    if (std::fabs(t_s - end.t_s) < nearest && (t_s < s.front().t_s || t_s > s.back().t_s)) {
      nearest = std::fabs(t_s - end.t_s);
      state.position = {end.x, end.y};
    }
    if (t_s < s.front().t_s || t_s > s.back().t_s) continue;
    auto hi = std::lower_bound(s.begin(), s.end(), t_s, [](const PathNode& n, double t) { return n.t_s < t; });
    if (hi == s.begin()) ++hi;
    const PathNode& a = *(hi - 1);
    const PathNode& b = *hi;
    // Cubic Hermite on [a, b] with the nodes' velocities as tangents.
    const double h = b.t_s - a.t_s, u = (t_s - a.t_s) / h;
    const double h00 = 2 * u * u * u - 3 * u * u + 1, h10 = u * u * u - 2 * u * u + u;
    const double h01 = -2 * u * u * u + 3 * u * u, h11 = u * u * u - u * u;
    const double d00 = (6 * u * u - 6 * u) / h, d10 = 3 * u * u - 4 * u + 1;
    const double d01 = (-6 * u * u + 6 * u) / h, d11 = 3 * u * u - 2 * u;
    state.touching = true;
    state.position = {h00 * a.x + h10 * h * a.vx + h01 * b.x + h11 * h * b.vx,
                      h00 * a.y + h10 * h * a.vy + h01 * b.y + h11 * h * b.vy};
    state.velocity = {d00 * a.x + d10 * a.vx + d01 * b.x + d11 * b.vx, d00 * a.y + d10 * a.vy + d01 * b.y + d11 * b.vy};
    state.resting = std::hypot(state.velocity.x, state.velocity.y) < rest_speed_px_s;
    return state;
  }
  return state;
}

}  // namespace ff::bench
