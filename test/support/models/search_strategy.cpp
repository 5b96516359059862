#include "support/models/search_strategy.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace ff::tracegen {

namespace {

constexpr double kRises[3] = {-200.0, 0.0, 200.0};  // top, middle, bottom (docs/spec.md#paths)
constexpr double kMinX = 30.0, kMaxX = 770.0, kMinY = 20.0, kMaxY = 460.0;

Point clamp_to_screen(Point p) { return {std::clamp(p.x, kMinX, kMaxX), std::clamp(p.y, kMinY, kMaxY)}; }

class Planner {
 public:
  Planner(const MotionOptions& o, uint64_t seed)
      : o_(o), rng_(seed, Stream::Motion), slow_rng_(seed, Stream::SlowStrokes),
        hesitation_rng_(seed, Stream::Hesitations), reversal_rng_(seed, Stream::Reversals),
        motion_(start_point()) {
    // Rests and lifts at random moments between 10 % and 90 % of the trace.
    for (int i = 0; i < o.rests; ++i) events_.push_back({rng_.uniform(0.1, 0.9) * o.duration_s, false});
    for (int i = 0; i < o.lifts; ++i) events_.push_back({rng_.uniform(0.1, 0.9) * o.duration_s, true});
    std::sort(events_.begin(), events_.end(), [](const Event& a, const Event& b) { return a.t_s < b.t_s; });
    rise_ = pick_rise();
  }

  Motion run() {
    Strategy mode = o_.strategy == Strategy::Mixed ? (rng_.chance(0.5) ? Strategy::Along : Strategy::Across)
                                                   : o_.strategy;
    int strokes_left_in_mode = rng_.integer(2, 6);
    while (motion_.duration_s() < o_.duration_s || next_event_ < events_.size()) {
      if (mode == Strategy::Along) along_stroke();
      else across_stroke();
      dwell();
      handle_events();
      if (o_.strategy == Strategy::Mixed && --strokes_left_in_mode <= 0) {
        mode = mode == Strategy::Along ? Strategy::Across : Strategy::Along;
        strokes_left_in_mode = rng_.integer(2, 6);
      }
    }
    // Never end in the air: the finger lands and makes one more stroke.
    if (motion_.segments().back().kind == SegmentKind::Lifted) {
      if (mode == Strategy::Along) along_stroke();
      else across_stroke();
    }
    return motion_;
  }

 private:
  struct Event {
    double t_s;
    bool lift;
  };

  Point start_point() { return {rng_.uniform(50.0, 100.0), 240.0 + 5.0 * rng_.gaussian()}; }

  double speed() { return rng_.log_uniform(o_.speed_min_mm_s, o_.speed_max_mm_s) * kPxPerMm; }

  double pick_rise() {
    switch (o_.paths) {
      case PathChoice::Top: return kRises[0];
      case PathChoice::Middle: return kRises[1];
      case PathChoice::Bottom: return kRises[2];
      case PathChoice::All: break;
    }
    return kRises[rng_.integer(0, 2)];
  }

  // Back and forth along one path; a new path is chosen only back in the
  // start area, where the three paths meet.
  void along_stroke() {
    const Point here = motion_.position();
    if (here.x < 160.0 && rightwards_) rise_ = pick_rise();
    const double length = rightwards_ ? rng_.uniform(250.0, 600.0) : rng_.uniform(150.0, 550.0);
    double x1 = rightwards_ ? here.x + length : here.x - length;
    x1 = std::clamp(x1, 40.0, 690.0);
    if (std::fabs(x1 - here.x) < 40.0) {  // at an end: turn round
      rightwards_ = !rightwards_;
      x1 = std::clamp(rightwards_ ? here.x + length : here.x - length, 40.0, 690.0);
    }
    double u1 = std::clamp(6.0 * rng_.gaussian(), -18.0, 18.0);
    double peak = speed();
    if (o_.slow_fraction > 0.0) {
      Segment planned;
      planned.shape = StrokeShape::AlongPath;
      planned.p0 = here;
      planned.p1 = {x1, path_y(x1, rise_) + u1};
      planned.rise_px = rise_;
      planned.u0 = here.y - path_y(here.x, rise_);
      planned.u1 = u1;
      const double scale = slow_down(stroke_length(planned), peak);
      x1 = here.x + scale * (x1 - here.x);
      u1 = planned.u0 + scale * (u1 - planned.u0);
    }
    // Leave the current offset from the path continuous: start from where the finger is.
    if (hesitates()) {
      const double f = hesitation_rng_.uniform(0.35, 0.65);
      const double u0 = here.y - path_y(here.x, rise_);
      motion_.stroke_along_path(here.x + f * (x1 - here.x), rise_, u0 + f * (u1 - u0), peak);
      hesitate();
    }
    motion_.stroke_along_path(x1, rise_, u1, peak);
    if (reverses()) {
      const double back = reversal_rng_.uniform(0.15, 0.40);
      motion_.stroke_along_path(x1 - back * (x1 - here.x), rise_, u1, peak);
    }
    const bool went_right = x1 > here.x;
    rightwards_ = rng_.chance(0.85) ? !went_right : went_right;  // mostly back and forth
  }

  // Up and down across the paths, drifting right; from the start area the
  // finger first sweeps into the field, from the far right back to the start.
  void across_stroke() {
    const Point here = motion_.position();
    // The draws are sequenced bow, speed, target: the order GCC evaluated
    // them in when they were one call's arguments, so the traces made then
    // are unchanged, and now the same with every compiler.
    if (here.x > 680.0) {
      const double bow = 20.0 * rng_.gaussian();
      const double peak = speed();
      const Point target = clamp_to_screen({rng_.uniform(60.0, 160.0), 240.0 + 30.0 * rng_.gaussian()});
      straight_stroke(target, peak, bow);
      return;
    }
    if (here.x < 150.0) {
      const double bow = 20.0 * rng_.gaussian();
      const double peak = speed();
      const Point target = clamp_to_screen({rng_.uniform(180.0, 500.0), rng_.uniform(100.0, 380.0)});
      straight_stroke(target, peak, bow);
      return;
    }
    downwards_ = here.y < 240.0 ? true : (here.y > 240.0 ? false : !downwards_);
    const double reach = rng_.uniform(150.0, 380.0);
    const double centre = 240.0 + 40.0 * rng_.gaussian();
    const double y1 = downwards_ ? centre + reach / 2.0 : centre - reach / 2.0;
    const double x1 = here.x + rng_.uniform(-20.0, 90.0);
    const double bow = 10.0 * rng_.gaussian();
    const double peak = speed();
    straight_stroke(clamp_to_screen({x1, y1}), peak, bow);
  }

  // A bowed stroke to p1 with the effects of MotionOptions applied.
  void straight_stroke(Point p1, double peak, double bow) {
    const Point here = motion_.position();
    Segment whole;
    whole.p0 = here;
    whole.p1 = p1;
    whole.bow_px = bow;
    // Scaling the chord and the bow together scales the arc by the same share.
    const double scale = o_.slow_fraction > 0.0 ? slow_down(stroke_length(whole), peak) : 1.0;
    p1 = whole.p1 = {here.x + scale * (p1.x - here.x), here.y + scale * (p1.y - here.y)};
    bow = whole.bow_px = bow * scale;
    if (hesitates()) {
      // Stop on the bowed curve and go on from there: two halves, each bowed half as much.
      Point mid, tangent;
      stroke_curve(whole, hesitation_rng_.uniform(0.35, 0.65), mid, tangent);
      motion_.stroke_to(mid, peak, 0.5 * bow);
      hesitate();
      motion_.stroke_to(p1, peak, 0.5 * bow);
    } else {
      motion_.stroke_to(p1, peak, bow);
    }
    if (reverses()) {
      const double back = reversal_rng_.uniform(0.15, 0.40);
      motion_.stroke_to({p1.x - back * (p1.x - here.x), p1.y - back * (p1.y - here.y)}, peak);
    }
  }

  // A slow stroke (slow_fraction of them): `peak` becomes slow and the
  // stroke (arc `length`) short enough to last 0.8-2 s; returns the share of
  // the stroke kept (along a curved path only nearly its share of the arc).
  double slow_down(double length, double& peak) {
    if (o_.slow_fraction <= 0.0 || !slow_rng_.chance(o_.slow_fraction)) return 1.0;
    peak = slow_rng_.log_uniform(o_.slow_min_px_s, o_.slow_max_px_s);
    const double slow_length = peak * slow_rng_.uniform(0.8, 2.0) / kMinJerkPeakRate;
    return length > slow_length ? slow_length / length : 1.0;
  }
  bool hesitates() { return o_.hesitation_fraction > 0.0 && hesitation_rng_.chance(o_.hesitation_fraction); }
  void hesitate() {
    motion_.hold(hesitation_rng_.uniform(o_.hesitation_min_s, o_.hesitation_max_s), false, true);
  }
  bool reverses() { return o_.reversal_fraction > 0.0 && reversal_rng_.chance(o_.reversal_fraction); }

  void dwell() { motion_.hold(rng_.uniform(o_.dwell_min_s, o_.dwell_max_s), false); }

  // At most one event after each stroke, so that two lifts never merge.
  void handle_events() {
    if (next_event_ < events_.size() && events_[next_event_].t_s <= motion_.duration_s()) {
      const Event& e = events_[next_event_++];
      if (e.lift) {
        const Point landing = clamp_to_screen({rng_.uniform(60.0, 700.0), rng_.uniform(60.0, 420.0)});
        motion_.lift(rng_.uniform(o_.lift_min_s, o_.lift_max_s), landing);
      } else {
        motion_.hold(rng_.uniform(o_.rest_min_s, o_.rest_max_s), true);
      }
    }
  }

  const MotionOptions& o_;
  Random rng_;
  Random slow_rng_, hesitation_rng_, reversal_rng_;
  Motion motion_;
  std::vector<Event> events_;
  size_t next_event_ = 0;
  double rise_ = 0.0;
  bool rightwards_ = true;
  bool downwards_ = true;
};

}  // namespace

const char* to_string(Strategy s) {
  switch (s) {
    case Strategy::Along: return "along";
    case Strategy::Across: return "across";
    case Strategy::Mixed: return "mixed";
  }
  return "?";
}

bool parse_strategy(const std::string& text, Strategy& out) {
  for (Strategy s : {Strategy::Along, Strategy::Across, Strategy::Mixed}) {
    if (text == to_string(s)) {
      out = s;
      return true;
    }
  }
  return false;
}

const char* to_string(PathChoice p) {
  switch (p) {
    case PathChoice::All: return "all";
    case PathChoice::Top: return "top";
    case PathChoice::Middle: return "middle";
    case PathChoice::Bottom: return "bottom";
  }
  return "?";
}

bool parse_path_choice(const std::string& text, PathChoice& out) {
  for (PathChoice p : {PathChoice::All, PathChoice::Top, PathChoice::Middle, PathChoice::Bottom}) {
    if (text == to_string(p)) {
      out = p;
      return true;
    }
  }
  return false;
}

Motion plan_motion(const MotionOptions& options, uint64_t seed) {
  if (options.rest_only) {
    Motion rest(Point{400.0, 240.0});
    rest.hold(options.duration_s, true);
    return rest;
  }
  return Planner(options, seed).run();
}

}  // namespace ff::tracegen
