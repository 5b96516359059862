#include "frictionfield/core/tracker.hpp"

#include "frictionfield/core/fastrun.hpp"

#include <cmath>
#include <limits>

#include "frictionfield/bus/clock.hpp"
#include "frictionfield/core/velocity_noise.hpp"

namespace ff {

namespace {

// Stamps are the wrapping 32-bit micros(): differences by the clock's rule.
constexpr int32_t elapsed_us(uint32_t later, uint32_t earlier) { return signed_elapsed(later, earlier); }

// Helpers of on_sample and on_tick, compiled into them: a call and its
// register saves cost more than the arithmetic on the M4 (docs/cycle-model.md).
#define FF_TICK_INLINE inline __attribute__((always_inline))

constexpr float kInitialSpeedSigmaPxS = 1000.0f;  // touch-down: velocity unknown
constexpr float kMinSpeedPxS = 1e-6f;             // below this the direction is undefined
constexpr float kMaxWidening = 100.0f;            // of the direction filter's covariance per report

}  // namespace

const char* to_string(Estimator e) {
  switch (e) {
    case Estimator::ThesisTicks: return "thesis-ticks";
    case Estimator::TimedExtrapolation: return "timed-extrapolation";
    case Estimator::Kalman: return "kalman";
    case Estimator::SplitKalman: return "split-kalman";
  }
  return "?";
}

TrackerConfig TrackerConfig::thesis() {
  TrackerConfig c;
  c.estimator = Estimator::ThesisTicks;  // 1-euro, no fade (v_hat = dxhat / |dxhat|)
  c.compensate_latency = false;           // stamps as given, whatever sensor it is told
  c.max_extrapolation_us = std::numeric_limits<uint32_t>::max();  // the thesis never stops counting
  c.max_speed_px_s = std::numeric_limits<float>::infinity();       // no jump rejection
  return c;
}

TrackerConfig TrackerConfig::recommended() { return recommended(SensorProfile{}); }

TrackerConfig TrackerConfig::recommended(const SensorProfile& sensor) {
  TrackerConfig c;
  if (is_valid(sensor)) c.sensor = sensor;
  return c;
}

Tracker::Tracker(const TrackerConfig& config) { configure(config); }
Tracker::Tracker(const TrackerConfig& config, const FadeNoise& fade) { configure(config, fade); }

namespace {

SensorProfile usable(const SensorProfile& sensor) { return is_valid(sensor) ? sensor : SensorProfile{}; }
float squared(float x) { return x * x; }
bool kalman_estimator(const TrackerConfig& c) {
  return c.estimator == Estimator::Kalman || c.estimator == Estimator::SplitKalman;
}
bool fades(const TrackerConfig& c) { return kalman_estimator(c) && squared(c.moving_sigmas) > squared(c.rest_sigmas); }
bool position_evidence(const TrackerConfig& c) {
  return c.estimator == Estimator::SplitKalman && fades(c) &&
         squared(c.position_moving_sigmas) > squared(c.position_rest_sigmas);
}
bool calm_evidence(const TrackerConfig& c) {
  return c.estimator == Estimator::SplitKalman && fades(c) &&
         squared(c.calm_moving_sigmas) > squared(c.calm_rest_sigmas);
}

}  // namespace

FadeNoise fade_noise(const TrackerConfig& config) {
  const SensorProfile sensor = usable(config.sensor);
  // The tremor moves the finger about its stroke by a fraction of a mm at
  // 3-20 Hz: a state of every filter (Tracker::configure).
  const ReportNoise noise = ReportNoise::with_tremor(sensor);
  const auto settled = [&](const KalmanConfig& k) {
    const SteadyStateFilter steady = steady_state_filter(squared(k.accel_noise_px_s2), noise, sensor);
    return SpeedNoise{steady.velocity_variance, resting_velocity_variance(steady, sensor)};
  };
  FadeNoise f;
  if (fades(config)) f.direction = settled(config.kalman);
  if (position_evidence(config)) f.position = settled(config.position_kalman);
  if (calm_evidence(config)) f.calm = settled(config.calm_kalman);
  return f;
}

void Tracker::configure(const TrackerConfig& config) { configure(config, fade_noise(config)); }

void Tracker::configure(const TrackerConfig& config, const FadeNoise& fade) {
  config_ = config;
  OneEuroConfig euro = config.one_euro;
  euro.rate_hz = 1e6f / static_cast<float>(kTickPeriodUs);
  filter_x_.configure(euro);
  filter_y_.configure(euro);
  config_.sensor = usable(config.sensor);
  const SensorProfile& sensor = config_.sensor;
  // The tremor moves the finger about its stroke by a fraction of a mm at
  // 3-20 Hz: a state of every filter, so the direction is the stroke's and
  // the rendered position the voluntary one, not shaking with the tremor.
  noise_ = ReportNoise::with_tremor(sensor);
  direction_q_ = squared(config.kalman.accel_noise_px_s2);
  position_q_ = squared(config.position_kalman.accel_noise_px_s2);
  calm_q_ = squared(config.calm_kalman.accel_noise_px_s2);
  latency_us_ = config.compensate_latency ? sensor.latency_us : 0u;
  inverse_maneuver_time_s_ = config.maneuver_threshold > 0.0f && config.maneuver_time_ms > 0.0f
                                 ? 1e3f / config.maneuver_time_ms : 0.0f;
  maneuvers_ = 0;
  stroke_ends_ = 0;
  stroke_end_.configure(config.stroke_end);
  predict_stroke_ends_ = kalman_estimator(config) && config.stroke_end_widening > 1.0f;
  // What the fade measures speeds against: derived by fade_noise(), outside the tick.
  direction_evidence_.configure(fades(config), config.rest_sigmas, config.moving_sigmas, fade.direction);
  position_evidence_.configure(position_evidence(config), config.position_rest_sigmas, config.position_moving_sigmas,
                               fade.position);
  calm_evidence_.configure(calm_evidence(config), config.calm_rest_sigmas, config.calm_moving_sigmas, fade.calm);
  calm_steady_speed_ = std::sqrt(fade.calm.steady_variance);
  // The tick clock runs on: the device's micros() did not change with the
  // configuration, and the next report must be judged by it like any other.
  forget_finger();
}

void Tracker::reset() {
  forget_finger();
  have_tick_ = false;
}

void Tracker::forget_finger() {
  // Everything else about the finger (filters, velocity, pending jump, stroke
  // fit) starts again at the next touch-down, in restart_at(), the only way
  // back to having one.
  state_ = TrackState{};
  have_last_ = false;
}

FF_TICK_INLINE void Tracker::learn_velocity_noise() {
  if (!direction_evidence_.used()) return;
  direction_evidence_.learn(direction_.P11);
  if (position_evidence_.used()) position_evidence_.learn(position_.P11);
  if (calm_evidence_.used()) calm_evidence_.learn(calm_.P11);
}

FF_FASTRUN void Tracker::lose_finger() {
  // The tick that calls this renders no finger; the next report touches down
  // again, and restart_at() sets everything else about the finger afresh.
  have_last_ = false;
}

FF_FASTRUN void Tracker::restart_at(const SensorSample& s) {
  // No history survives a touch-down or a confirmed jump: no velocity spike.
  copy_sample(last_, s);
  have_last_ = true;
  raw_velocity_ = {};
  have_pending_jump_ = false;
  lifting_ = false;
  stale_reported_ = false;
  filter_x_.reset();
  filter_y_.reset();
  direction_.start({s.x, s.y}, noise_, kInitialSpeedSigmaPxS);
  position_.start({s.x, s.y}, noise_, kInitialSpeedSigmaPxS);
  if (calm_evidence_.used()) calm_.start({s.x, s.y}, noise_, kInitialSpeedSigmaPxS);
  recent_innovation_ = {};
  recent_innovation_variance_ = 0.0f;
  stroke_end_.restart();
  if (predict_stroke_ends_) stroke_end_.add(s.t_us, {s.x, s.y});
  filters_fresh_ = false;
  // The fade learns the new filters' noise at the next report; their velocity is 0 till then.
}

FF_TICK_INLINE bool Tracker::moved_further_than_allowed(const SensorSample& s, const SensorSample& from) const {
  const float dt_s = static_cast<float>(elapsed_us(s.t_us, from.t_us)) * 1e-6f;
  const float allowed = config_.max_speed_px_s * dt_s + config_.jump_slack_px;
  // Squared, without a square root: both sides are >= 0 (allowed may be infinite).
  const Vec2 d = Vec2{s.x, s.y} - Vec2{from.x, from.y};
  return dot(d, d) > allowed * allowed;
}

FF_TICK_INLINE void Tracker::accept(const SensorSample& s, bool need_filter) {
  const int32_t dt_us = elapsed_us(s.t_us, last_.t_us);
  const bool kalman = config_.estimator == Estimator::Kalman || config_.estimator == Estimator::SplitKalman;
  if (!kalman) {  // the 1-euro estimators extrapolate with the raw velocity; the Kalman filters never read it
    const float inv_dt = 1.0f / static_cast<float>(dt_us);
    raw_velocity_ = {(s.x - last_.x) * inv_dt, (s.y - last_.y) * inv_dt};
  }
  copy_sample(last_, s);
  ticks_since_sample_ = 0;
  lifting_ = false;
  stale_reported_ = false;
  if (!need_filter) filters_fresh_ = true;  // restart from this report when motion matters again
  if (!need_filter || !kalman) return;      // the 1-euro estimators filter at the tick
  const float dt_s = static_cast<float>(dt_us) * 1e-6f;
  const Vec2 z{s.x, s.y};
  direction_.predict(dt_s, direction_q_, noise_);
  if (calm_evidence_.used()) calm_.predict(dt_s, calm_q_, noise_);
  float s_variance = direction_.innovation_variance(noise_);
  float widen = 1.0f;
  if (inverse_maneuver_time_s_ > 0.0f) {
    // The innovations are independent, of variance S each, while the model
    // holds: so is their age-weighted sum, of variance sum(a^2k S).
    const float a = decay(dt_s * inverse_maneuver_time_s_);
    recent_innovation_ = a * recent_innovation_ + direction_.innovation(z);
    recent_innovation_variance_ = a * a * recent_innovation_variance_ + s_variance;
    const float sum_squared = dot(recent_innovation_, recent_innovation_);
    const float bound = recent_innovation_variance_ * config_.maneuver_threshold;
    if (sum_squared > bound) {  // the finger changed its motion (a division only then)
      const float ratio = sum_squared / bound;
      widen = ratio < kMaxWidening ? ratio : kMaxWidening;
      ++maneuvers_;
    }
  }
  bool stroke_end = false;
  if (predict_stroke_ends_) {
    stroke_end_.add(s.t_us, z);
    if (!refined_this_tick_ && stroke_end_.refine_due()) {
      refined_this_tick_ = true;
      if (stroke_end_.refine()) {  // the finger stops now
        if (widen < config_.stroke_end_widening) widen = config_.stroke_end_widening;
        ++stroke_ends_;
        stroke_end = true;
      }
    }
  }
  const bool split = config_.estimator == Estimator::SplitKalman;
  if (split) {
    position_.predict(dt_s, position_q_, noise_);
    position_.update(z, position_.inverse_innovation(noise_));
  }
  if (stroke_end && split && config_.stroke_end_takes_position &&
      dot(position_.v, position_.v) < dot(direction_.v, direction_.v)) {
    direction_ = position_;  // its estimate and its uncertainty, this report included
  } else {
    if (widen > 1.0f) {
      direction_.widen(widen, noise_);
      s_variance = direction_.innovation_variance(noise_);
    }
    direction_.update(z, 1.0f / s_variance);
  }
  if (calm_evidence_.used()) {
    // A change of motion or a stroke's end: the calm filter starts again at
    // rest at this report, so that its evidence is of motion since then (a
    // slow start), never of a stroke it still lags behind.
    if (widen > 1.0f) calm_.start(z, noise_, calm_steady_speed_);
    else calm_.update(z, calm_.inverse_innovation(noise_));
  }
  learn_velocity_noise();
}

FF_FASTRUN void Tracker::on_sample(const SensorSample& in, bool need_filter) {
  if (!in.touch) {
    if (have_last_ && !lifting_) {
      lifting_ = true;
      untouched_since_us_ = in.t_us;
    }
    return;
  }
  if (!is_finite(in.x) || !is_finite(in.y)) {
    faults_.add(Fault::NonFiniteCoordinate);
    return;
  }
  const float m = config_.screen_margin_px;
  if (in.x < -m || in.x > kScreenMaxX + m || in.y < -m || in.y > kScreenMaxY + m) {
    faults_.add(Fault::OffScreen);
    return;
  }
  SensorSample s;  // within the margin: clamped onto the screen
  s.t_us = in.t_us - latency_us_;  // when the sensor saw the finger (judged by the stamp below)
  s.x = clamp(in.x, 0.0f, kScreenMaxX);
  s.y = clamp(in.y, 0.0f, kScreenMaxY);

  if (have_tick_) {
    // Judge the stamp by the tick clock (the same micros() on the device): a
    // report from the future, or older than the stale timeout, is a glitch.
    // In 64 bits: a lead of INT32_MIN (2^31 us either way) has no negation.
    const int64_t lead = elapsed_us(in.t_us, last_tick_us_);
    if (lead > static_cast<int64_t>(config_.max_sample_lead_us) ||
        lead < -static_cast<int64_t>(config_.stale_timeout_us)) {
      faults_.add(Fault::SampleTimeImplausible);
      return;
    }
  }
  if (!have_last_) {
    faults_.add(Fault::TouchDown);
    restart_at(s);
    return;
  }
  if (elapsed_us(s.t_us, last_.t_us) <= 0) {
    faults_.add(Fault::NonIncreasingTime);
    return;
  }
  if (moved_further_than_allowed(s, last_)) {
    if (have_pending_jump_ && elapsed_us(s.t_us, pending_jump_.t_us) > 0) {
      if (!moved_further_than_allowed(s, pending_jump_)) {
        faults_.add(Fault::JumpConfirmed);  // the finger really is there now
        restart_at(s);
        return;
      }
      faults_.add(Fault::JumpRejected);  // the previous candidate was a glitch
    }
    copy_sample(pending_jump_, s);
    have_pending_jump_ = true;
    return;
  }
  if (have_pending_jump_) {
    faults_.add(Fault::JumpRejected);  // back on the old track: it was a glitch
    have_pending_jump_ = false;
  }
  accept(s, need_filter);
}

FF_TICK_INLINE uint32_t Tracker::extrapolation_us(uint32_t now_us) {
  const int32_t since = elapsed_us(now_us, last_.t_us);
  const uint32_t dt = since > 0 ? static_cast<uint32_t>(since) : 0u;
  if (dt > config_.max_extrapolation_us) {
    if (!stale_reported_) faults_.add(Fault::StaleSample);
    stale_reported_ = true;
    return config_.max_extrapolation_us;
  }
  return dt;
}

FF_TICK_INLINE Vec2 Tracker::estimate(uint32_t now_us, Vec2& velocity) {
  switch (config_.estimator) {
    case Estimator::ThesisTicks:
    case Estimator::TimedExtrapolation: {
      float horizon_us;
      if (config_.estimator == Estimator::ThesisTicks) {
        // n ticks since the sample, 0 at the first tick that sees it.
        const uint64_t n_us = static_cast<uint64_t>(ticks_since_sample_) * kTickPeriodUs;
        horizon_us = static_cast<float>(n_us < config_.max_extrapolation_us ? n_us : config_.max_extrapolation_us);
        if (ticks_since_sample_ != UINT32_MAX) ++ticks_since_sample_;
      } else {
        horizon_us = static_cast<float>(extrapolation_us(now_us));
      }
      const Vec2 p_ext = Vec2{last_.x, last_.y} + horizon_us * raw_velocity_;
      const Vec2 p{filter_x_.filter(p_ext.x), filter_y_.filter(p_ext.y)};
      velocity = {filter_x_.derivative(), filter_y_.derivative()};
      return p;
    }
    case Estimator::Kalman: {
      const float dt_s = static_cast<float>(extrapolation_us(now_us)) * 1e-6f;
      velocity = direction_.v;
      return {direction_.p.x + direction_.v.x * dt_s, direction_.p.y + direction_.v.y * dt_s};
    }
    case Estimator::SplitKalman: {
      const float dt_s = static_cast<float>(extrapolation_us(now_us)) * 1e-6f;
      velocity = direction_.v;  // smooth: the direction
      return {position_.p.x + position_.v.x * dt_s, position_.p.y + position_.v.y * dt_s};  // fast: the position
    }
  }
  return {last_.x, last_.y};
}

FF_TICK_INLINE Vec2 Tracker::faded_direction(Vec2 v) const {
  // Normalise by the larger component first: squares of tiny (subnormal)
  // speeds lose precision, and v / |v| must stay unit length.
  const float ax = std::fabs(v.x), ay = std::fabs(v.y);
  const float m = ax > ay ? ax : ay;
  if (!is_finite(v) || !(m > kMinSpeedPxS)) return {};  // at rest (or not a number): no direction
  const Vec2 u = (1.0f / m) * v;
  const float len = length(u);  // in [1, sqrt 2]
  float gain = 1.0f;
  if (direction_evidence_.used()) {
    // The speed in standard deviations of the velocity's noise (learn_velocity_noise).
    const float speed = m * len;
    float motion = direction_evidence_.of(speed * speed);
    if (position_evidence_.used()) {  // or the position filter's, if it says more
      const float agile = position_evidence_.of(dot(position_.v, position_.v));
      if (agile > motion) motion = agile;
    }
    if (calm_evidence_.used()) {  // or the calm filter's
      const float calm = calm_evidence_.of(dot(calm_.v, calm_.v));
      if (calm > motion) motion = calm;
    }
    gain = smoothstep(motion);
  }
  return (gain / len) * u;
}

FF_FASTRUN const TrackState& Tracker::on_tick(uint32_t now_us, bool need_filter) {
  if (have_tick_) {
    const int32_t step = elapsed_us(now_us, last_tick_us_);
    if (step <= 0 || step > static_cast<int32_t>(config_.max_tick_step_us)) {
      // Time stood still, ran back or leapt. One odd tick is a glitch: repeat
      // the last state. Two in a row that agree with each other mean the
      // clock itself moved: re-anchor on it.
      const int32_t since = elapsed_us(now_us, tick_candidate_us_);
      const bool confirmed = have_tick_candidate_ && since > 0 &&
                             since <= static_cast<int32_t>(config_.max_tick_step_us);
      faults_.add(Fault::BadTickTime);
      if (!confirmed) {
        tick_candidate_us_ = now_us;
        have_tick_candidate_ = true;
        return state_;
      }
      // The clock moved: the reports' ages are unknown (a leap beyond 2^31 us
      // even looks like the past), so the finger is found again from the
      // next report instead of rendering an old one.
      faults_.add(Fault::TimeBaseReset);
      lose_finger();
    }
  }
  have_tick_ = true;
  have_tick_candidate_ = false;
  last_tick_us_ = now_us;
  refined_this_tick_ = false;

  if (have_last_ && lifting_ && elapsed_us(now_us, untouched_since_us_) >= static_cast<int32_t>(config_.lift_off_timeout_us)) {
    faults_.add(Fault::LiftOff);
    lose_finger();
  }
  if (have_last_ && elapsed_us(now_us, last_.t_us) > static_cast<int32_t>(config_.stale_timeout_us)) {
    faults_.add(Fault::SensorTimeout);
    lose_finger();
  }
  if (!have_last_) {
    state_.present = false;
    state_.velocity = {};
    state_.direction = {};
    return state_;
  }

  state_.present = true;
  if (!need_filter) {
    // The scene needs no position: report the sample, restart filters on next use.
    state_.position = {last_.x, last_.y};
    state_.velocity = {};
    state_.direction = {};
    filters_fresh_ = true;
    return state_;
  }
  if (filters_fresh_) {
    SensorSample keep;
    copy_sample(keep, last_);
    const Vec2 v = raw_velocity_;
    restart_at(keep);
    raw_velocity_ = v;
  }

  Vec2 velocity;
  Vec2 p = estimate(now_us, velocity);
  if (!is_finite(p) || !is_finite(velocity)) {  // cannot happen with valid input; never propagate
    restart_at(last_);
    p = {last_.x, last_.y};
    velocity = {};
  }
  state_.position = {clamp(p.x, 0.0f, kScreenMaxX), clamp(p.y, 0.0f, kScreenMaxY)};
  state_.velocity = velocity;
  state_.direction = faded_direction(velocity);
  if (predict_stroke_ends_) {
    const float quiet = stroke_end_.stopping_gain(now_us);  // 1 but over a fitted stop
    if (quiet < 1.0f) state_.direction = quiet * state_.direction;
  }
  return state_;
}

}  // namespace ff
