#include "support/models/motion.hpp"

#include <algorithm>
#include <cmath>

#include "frictionfield/core/min_jerk.hpp"
#include "support/reference/reference_scene.hpp"

namespace ff::tracegen {

double path_y(double x, double rise) { return reference::experiment_path_at(x, rise).y; }
double path_slope(double x, double rise) { return reference::experiment_path_at(x, rise).slope; }

double min_jerk(double tau) { return ff::min_jerk(tau); }

double min_jerk_rate(double tau) {
  if (tau <= 0.0 || tau >= 1.0) return 0.0;
  return 30.0 * tau * tau * (1.0 - tau) * (1.0 - tau);
}

void stroke_curve(const Segment& s, double sigma, Point& point, Point& tangent) {
  if (s.shape == StrokeShape::AlongPath) {
    const double dx = s.p1.x - s.p0.x;
    const double x = s.p0.x + sigma * dx;
    const double u = s.u0 + sigma * (s.u1 - s.u0);
    point = {x, path_y(x, s.rise_px) + u};
    tangent = {dx, path_slope(x, s.rise_px) * dx + (s.u1 - s.u0)};
    return;
  }
  const Point d{s.p1.x - s.p0.x, s.p1.y - s.p0.y};
  const double len = std::hypot(d.x, d.y);
  const Point n = len > 0.0 ? Point{-d.y / len, d.x / len} : Point{};
  const double b = 4.0 * sigma * (1.0 - sigma) * s.bow_px;
  const double db = 4.0 * (1.0 - 2.0 * sigma) * s.bow_px;
  point = {s.p0.x + sigma * d.x + b * n.x, s.p0.y + sigma * d.y + b * n.y};
  tangent = {d.x + db * n.x, d.y + db * n.y};
}

double stroke_length(const Segment& s) {
  constexpr int kPieces = 64;
  double length = 0.0;
  Point prev, tangent;
  stroke_curve(s, 0.0, prev, tangent);
  for (int i = 1; i <= kPieces; ++i) {
    Point p;
    stroke_curve(s, static_cast<double>(i) / kPieces, p, tangent);
    length += std::hypot(p.x - prev.x, p.y - prev.y);
    prev = p;
  }
  return length;
}

void Motion::push(Segment s) {
  s.t_start_s = end_s_;
  end_s_ += s.duration_s;
  segments_.push_back(s);
}

void Motion::stroke_to(Point p1, double peak_speed_px_s, double bow_px) {
  Segment s;  // bowed, as the default shape
  s.p0 = cursor_;
  s.p1 = p1;
  s.bow_px = bow_px;
  // Peak speed of a minimum-jerk stroke is 1.875 L / T.
  stroke_for(p1, std::max(0.05, kMinJerkPeakRate * stroke_length(s) / peak_speed_px_s), bow_px);
  segments_.back().peak_speed_px_s = peak_speed_px_s;
}

void Motion::stroke_for(Point p1, double duration_s, double bow_px) {
  Segment s;
  s.kind = SegmentKind::Stroke;
  s.p0 = cursor_;
  s.p1 = p1;
  s.bow_px = bow_px;
  s.duration_s = duration_s;
  s.peak_speed_px_s = kMinJerkPeakRate * stroke_length(s) / duration_s;
  push(s);
  cursor_ = p1;
}

void Motion::stroke_along_path(double x1, double rise_px, double u1, double peak_speed_px_s) {
  Segment s;
  s.kind = SegmentKind::Stroke;
  s.shape = StrokeShape::AlongPath;
  s.p0 = cursor_;
  s.rise_px = rise_px;
  s.u0 = cursor_.y - path_y(cursor_.x, rise_px);
  s.u1 = u1;
  s.p1 = {x1, path_y(x1, rise_px) + u1};
  s.peak_speed_px_s = peak_speed_px_s;
  s.duration_s = std::max(0.05, kMinJerkPeakRate * stroke_length(s) / peak_speed_px_s);
  push(s);
  cursor_ = s.p1;
}

void Motion::hold(double duration_s, bool rest, bool hesitation) {
  if (duration_s <= 0.0) return;
  Segment s;  // a hold, the default kind
  s.p0 = s.p1 = cursor_;
  s.duration_s = duration_s;
  s.rest = rest;
  s.hesitation = hesitation;
  push(s);
}

void Motion::lift(double duration_s, Point landing) {
  Segment s;
  s.kind = SegmentKind::Lifted;
  s.p0 = cursor_;
  s.p1 = landing;
  s.duration_s = duration_s;
  push(s);
  cursor_ = landing;
}

const Segment* Motion::find(double t_s) const {
  if (segments_.empty()) return nullptr;
  // Last segment starting at or before t.
  auto it = std::upper_bound(segments_.begin(), segments_.end(), t_s,
                             [](double t, const Segment& s) { return t < s.t_start_s; });
  if (it == segments_.begin()) return &segments_.front();
  return &*(it - 1);
}

TrueState Motion::at(double t_s) const {
  TrueState state;
  const Segment* s = find(t_s);
  if (s == nullptr) {
    state.touching = true;
    state.position = cursor_;
    return state;
  }
  switch (s->kind) {
    case SegmentKind::Hold:
      state.touching = true;
      state.resting = s->rest;
      state.position = s->p0;
      break;
    case SegmentKind::Lifted:
      // Off the screen; past its end the finger is down at the landing point.
      state.touching = t_s >= s->t_start_s + s->duration_s;
      state.position = state.touching ? s->p1 : s->p0;
      break;
    case SegmentKind::Stroke: {
      const double tau = (t_s - s->t_start_s) / s->duration_s;
      Point p, tangent;
      stroke_curve(*s, min_jerk(tau), p, tangent);
      const double rate = min_jerk_rate(tau) / s->duration_s;
      state.touching = true;
      state.position = p;
      state.velocity = {tangent.x * rate, tangent.y * rate};
      break;
    }
  }
  return state;
}

}  // namespace ff::tracegen
