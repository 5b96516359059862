#include "support/reference/reference_tracker.hpp"

#include <cmath>

namespace ff::reference {

namespace {
constexpr double kPiD = 3.14159265358979323846;
}  // namespace

double ReferenceOneEuro::operator()(double x) {
  auto alpha = [&](double fc) { return 1.0 / (1.0 + rate_hz / (2.0 * kPiD * fc)); };
  if (!init) {
    init = true;
    xhat = xprev = x;
    dxhat = 0.0;
    return x;
  }
  const double dx = (x - (from_filtered ? xhat : xprev)) * rate_hz;
  dxhat = alpha(derivative_cutoff_hz) * dx + (1.0 - alpha(derivative_cutoff_hz)) * dxhat;
  const double a = alpha(min_cutoff_hz + beta * std::fabs(dxhat));
  xhat = a * x + (1.0 - a) * xhat;
  xprev = x;
  return xhat;
}

void ReferenceThesisTracker::on_sample(const SensorSample& s) {
  if (!s.touch) return;
  if (have_) {
    const double dt = static_cast<double>(static_cast<int32_t>(s.t_us - t_));
    vx_ = (static_cast<double>(s.x) - x_) / dt;
    vy_ = (static_cast<double>(s.y) - y_) / dt;
  }
  have_ = true;
  x_ = s.x;
  y_ = s.y;
  t_ = s.t_us;
  n_ = 0;
}

double ReferenceThesisTracker::filtered_speed() const { return std::hypot(ex_.dxhat, ey_.dxhat); }

void ReferenceThesisTracker::on_tick(DVec& position, DVec& direction) {
  const double h = static_cast<double>(n_) * 500.0;
  ++n_;
  position = {ex_(x_ + vx_ * h), ey_(y_ + vy_ * h)};
  const double speed = std::hypot(ex_.dxhat, ey_.dxhat);
  direction = speed > 0.0 ? DVec{ex_.dxhat / speed, ey_.dxhat / speed} : DVec{};
}

}  // namespace ff::reference
