#include "frictionfield/core/stroke_end_predictor.hpp"

#include <cmath>
#include <initializer_list>

#include "frictionfield/bus/clock.hpp"
#include "frictionfield/core/fastrun.hpp"
#include "frictionfield/core/min_jerk.hpp"
#include "frictionfield/core/tick_math.hpp"

namespace ff {

namespace {

constexpr float kMinDurationS = 0.04f;
// The search's first guess when the stroke begins to move (a 4 px rise of a
// stroke of a few hundred ms has run ~60 ms) and its steps' range.
constexpr float kGuessLeadS = 0.06f, kGuessRestS = 0.25f;
constexpr float kStartStepS = 0.02f, kEndStepS = 0.05f;
constexpr float kMinStepS = 0.0005f, kMaxStartStepS = 0.1f, kMaxEndStepS = 0.5f;
// Below this spread of the profile over the points it cannot tell from from travel.
constexpr float kMinSpreadPerPoint = 1e-5f;

}  // namespace

void StrokeEndPredictor::configure(const StrokeEndConfig& config) {
  config_ = config;
  refine_interval_s_ = static_cast<float>(config.refine_interval_us) * 1e-6f;
  refinements_ = 0;
  restart();
}

void StrokeEndPredictor::restart() {  // the next report begins a stroke (begin_stroke_at)
  quiet_known_ = false;
  started_ = false;
  moving_ = false;
}

namespace {
// Origins are whole pixels: a report less its origin is then exact, and the
// points the same in two runs that kept the same reports.
FF_FASTRUN Vec2 whole(Vec2 p) { return {nearest_integer(p.x), nearest_integer(p.y)}; }
}  // namespace

FF_FASTRUN void StrokeEndPredictor::reorigin_at_first() {
  // Times and positions from the oldest kept point: small, and the same in
  // two runs that kept the same points whatever came before.
  const Point first = points_[0];
  const Vec2 origin = whole(origin_ + Vec2{first.x, first.y});
  const Vec2 shift = origin_ - origin;  // whole pixels: exact
  origin_ = origin;
  origin_us_ = first.t_us;
  for (int i = 0; i < count_; ++i) {
    points_[i].t = static_cast<float>(signed_elapsed(points_[i].t_us, origin_us_)) * 1e-6f;
    points_[i].x += shift.x;
    points_[i].y += shift.y;
  }
}

FF_FASTRUN void StrokeEndPredictor::begin_stroke_at(const Point& newest) {
  count_ = 1;
  points_[0] = newest;
  reorigin_at_first();
  newest_ = points_[0];
  moving_ = false;  // so the next report, whatever it is, says whether it is kept
  quiet_known_ = false;
  spacing_us_ = kSpacingUs;
}

FF_FASTRUN void StrokeEndPredictor::keep_resting(const Point& p) {
  points_[count_++] = p;
  if (count_ > kRestPoints) {
    for (int i = 1; i < count_; ++i) points_[i - 1] = points_[i];
    --count_;
    reorigin_at_first();
  }
}

FF_FASTRUN void StrokeEndPredictor::keep_moving(const Point& p) {
  if (count_ == kCapacity) {  // every other point goes, and from now on twice the spacing
    for (int i = 1; i < kCapacity / 2; ++i) points_[i] = points_[2 * i];
    count_ = kCapacity / 2;
    spacing_us_ *= 2u;
  }
  points_[count_++] = p;
}

FF_FASTRUN void StrokeEndPredictor::add(uint32_t t_us, Vec2 p) {
  if (!started_) {  // any origin will do: begin_stroke_at() moves it to this report
    started_ = true;
    begin_stroke_at({0.0f, p.x - origin_.x, p.y - origin_.y, t_us});
    return;
  }
  if (signed_elapsed(t_us, newest_.t_us) <= 0) return;  // not after the newest: no order, no fit
  const Point q{static_cast<float>(signed_elapsed(t_us, origin_us_)) * 1e-6f, p.x - origin_.x, p.y - origin_.y, t_us};
  newest_ = q;
  if (moving_) {
    // A report about spacing_us_ after the last kept (a period's jitter
    // allowed) is kept: at any report rate the points lie alike.
    newest_kept_ = t_us - points_[count_ - 1].t_us >= spacing_us_ - spacing_us_ / 5u;
    if (newest_kept_) keep_moving(q);
    return;
  }
  // Moved away from where the finger rested (the kept points' mean)?
  Vec2 mean{};
  for (int i = 0; i < count_; ++i) mean = mean + Vec2{points_[i].x, points_[i].y};
  const Vec2 d = Vec2{q.x, q.y} - (1.0f / static_cast<float>(count_)) * mean;
  const bool moved = dot(d, d) >= config_.motion_px * config_.motion_px;
  // At rest a report about kRestSpacingUs after the last kept is kept: the
  // mean lags a slow start by half their span, so that it shows.
  newest_kept_ = moved || t_us - points_[count_ - 1].t_us >= kRestSpacingUs - kRestSpacingUs / 5u;
  if (newest_kept_) {
    keep_resting(q);
    newest_ = points_[count_ - 1];  // q, perhaps re-origined
  }
  if (!moved) return;
  moving_ = true;
  motion_s_ = newest_.t;
  start_s_ = motion_s_ - kGuessLeadS;
  end_s_ = motion_s_ + kGuessRestS;
  start_step_s_ = kStartStepS;
  end_step_s_ = kEndStepS;
  last_refine_s_ = motion_s_ - refine_interval_s_;  // due now
}

FF_FASTRUN float StrokeEndPredictor::quiet_gain(uint32_t now_us) const {
  // The share of the quiet span still ahead, faded as the tracker's direction is.
  return smoothstep(1.0f - static_cast<float>(signed_elapsed(now_us, quiet_from_us_)) * inverse_quiet_us_);
}

FF_FASTRUN bool StrokeEndPredictor::refine_due() const { return moving_ && newest_.t - last_refine_s_ >= refine_interval_s_; }

FF_FASTRUN StrokeEndPredictor::Fit StrokeEndPredictor::evaluate(float start_s, float end_s, int n, Vec2 mean) const {
  Fit f;
  if (!(end_s - start_s >= kMinDurationS)) return f;
  const float inverse_duration = 1.0f / (end_s - start_s);
  // The points are in time order: before the start the profile is 0 and
  // adds nothing, after the end it is 1.
  int i = 0;
  while (i < n && points_[i].t <= start_s) ++i;
  float sm = 0.0f, smm = 0.0f, smx = 0.0f, smy = 0.0f;
  for (; i < n && points_[i].t < end_s; ++i) {
    const Point& p = points_[i];
    const float m = min_jerk_within((p.t - start_s) * inverse_duration);
    sm += m;
    smm += m * m;
    smx += m * p.x;
    smy += m * p.y;
  }
  const float after = static_cast<float>(n - i);
  sm += after;
  smm += after;
  for (; i < n; ++i) {
    smx += points_[i].x;
    smy += points_[i].y;
  }
  // x_i = from + travel m_i per axis: travel = S_mx / S_mm about the means,
  // and the squares it explains S_mx^2 / S_mm.
  const float spread = smm - sm * sm / static_cast<float>(n);
  if (!(spread > kMinSpreadPerPoint * static_cast<float>(n))) return f;
  const float cx = smx - sm * mean.x, cy = smy - sm * mean.y;
  f.explained = (cx * cx + cy * cy) / spread;
  f.profile_spread = spread;
  return f;
}

FF_FASTRUN bool StrokeEndPredictor::refine() {
  if (!moving_) return false;
  ++refinements_;
  last_refine_s_ = newest_.t;
  int n = count_;
  if (!newest_kept_) points_[n++] = newest_;
  Vec2 mean{};
  for (int i = 0; i < n; ++i) mean = mean + Vec2{points_[i].x, points_[i].y};
  mean = (1.0f / static_cast<float>(n)) * mean;
  float total = 0.0f;  // the squares about the mean, px^2: what the fit can explain
  for (int i = 0; i < n; ++i) {
    const Vec2 d = Vec2{points_[i].x, points_[i].y} - mean;
    total += dot(d, d);
  }
  // A compass search, the optimum moving as reports come: the centre again,
  // then a step either way on the start or (every other time) the end; a
  // step grows after a move and shrinks when the centre holds. Three fits:
  // half the cost of trying both every time, as good on the trace classes.
  Fit best = evaluate(start_s_, end_s_, n, mean);
  float best_start = start_s_, best_end = end_s_;
  const bool on_end = (refinements_ & 1u) == 0u;
  float& step = on_end ? end_step_s_ : start_step_s_;
  for (const float sign : {-1.0f, 1.0f}) {
    const float start = on_end ? start_s_ : start_s_ + sign * step;
    const float end = on_end ? end_s_ + sign * step : end_s_;
    const Fit f = evaluate(start, end, n, mean);
    if (f.explained > best.explained) {
      best = f;
      best_start = start;
      best_end = end;
    }
  }
  const bool moved = best_start != start_s_ || best_end != end_s_;
  step = clamp(step * (moved ? 2.0f : 0.5f), kMinStepS, on_end ? kMaxEndStepS : kMaxStartStepS);
  start_s_ = best_start;
  end_s_ = best_end;
  if (newest_.t - motion_s_ > kMaxStrokeS) {  // no end found in time: begin again
    begin_stroke_at(newest_);
    return false;
  }
  // A stroke: it stands out of the noise. |travel|^2 = explained / spread;
  // each component's variance sigma^2 / spread, sigma^2 from the residuals
  // of 2n coordinates less 4 fitted values. Moving, a fit has at least a
  // rest and the report that left it; it needs a third.
  const float residual = total - best.explained;
  const float sigma2 = n >= 3 && residual > 0.0f ? residual / static_cast<float>(2 * n - 4) : 0.0f;
  const bool stroke = n >= 3 && best.explained >= 0.0f &&
                      best.explained >= config_.min_travel_px * config_.min_travel_px * best.profile_spread &&
                      best.explained >= config_.min_sigmas * config_.min_sigmas * sigma2;
  quiet_known_ = stroke && config_.quiet_speed_px_s > 0.0f;
  if (quiet_known_) {
    // Near the end the speed is travel / T * 30 (1 - tau)^2 (min_jerk.hpp):
    // quiet_speed that long before it, at most from the peak.
    const float duration = end_s_ - start_s_;
    const float travel = std::sqrt(best.explained / best.profile_spread);
    float quiet_s = duration * std::sqrt(config_.quiet_speed_px_s * duration / (30.0f * travel));
    if (quiet_s > 0.5f * duration) quiet_s = 0.5f * duration;
    inverse_quiet_us_ = 1.0f / static_cast<float>(static_cast<uint32_t>(quiet_s * 1e6f) + 1u);  // whole us, at least 1
    quiet_from_us_ = origin_us_ + static_cast<uint32_t>(static_cast<int32_t>((end_s_ - quiet_s) * 1e6f));
  }
  if (n < 3) return false;
  if (newest_.t < end_s_) return false;
  // Past the fitted end: a stroke that does not stand out of the noise is
  // none, and given up once well past it, so that the finger at rest is
  // watched for the next start.
  if (!stroke) {
    if (newest_.t > end_s_ + kGiveUpS) begin_stroke_at(newest_);
    return false;
  }
  begin_stroke_at(newest_);
  return true;
}

}  // namespace ff
