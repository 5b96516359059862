#pragma once
// Finger tracking at 2 kHz from a ~200 Hz sensor: where the finger is at the
// tick and which way it is going. Every fault is decided here, counted, and
// answered with a safe state.
#include <cstdint>

#include "frictionfield/core/fault_counters.hpp"
#include "frictionfield/core/finger_kalman.hpp"
#include "frictionfield/core/geometry.hpp"
#include "frictionfield/core/motion_evidence.hpp"
#include "frictionfield/core/one_euro_filter.hpp"
#include "frictionfield/core/report_noise.hpp"
#include "frictionfield/core/sensor_profile.hpp"
#include "frictionfield/core/sensor_sample.hpp"
#include "frictionfield/core/stroke_end_predictor.hpp"

namespace ff {

constexpr uint32_t kTickPeriodUs = 500;  // 2 kHz

enum class Estimator : uint8_t {
  ThesisTicks,         // thesis alg. 3/4: p_k + v_raw * n * 500 us, then 1-euro
  TimedExtrapolation,  // same, extrapolated to the tick's true time, then 1-euro
  Kalman,              // constant-velocity Kalman at the sensor rate, predicted to the tick
  SplitKalman,         // two such filters on the same reports: a fast one for the position
                       // (no lag), a smooth one for the direction (no chatter)
};
const char* to_string(Estimator e);

struct KalmanConfig {
  // The finger's side of the model: white acceleration of spectral density
  // accel_noise^2 (px^2/s^3). The sensor's side, the report noise, comes from
  // the SensorProfile (report_noise.hpp). Tuned by ff-track-bench on the
  // trace classes (docs/tracking.md).
  float accel_noise_px_s2 = 45.0f;
};

struct TrackerConfig {
  Estimator estimator = Estimator::SplitKalman;
  SensorProfile sensor;                // the sensor: report noise and stamp latency
  OneEuroConfig one_euro;              // ThesisTicks and TimedExtrapolation
  KalmanConfig kalman;                 // Kalman; SplitKalman's direction filter
  KalmanConfig position_kalman{750.0f};  // SplitKalman's position filter
  // Direction confidence: the direction fades in as the speed stands out of
  // the velocity's noise, from rest_sigmas to moving_sigmas standard
  // deviations of what a resting finger shows (velocity_noise.hpp) plus the
  // filter's excess uncertainty (after a touch-down, during a gap), so that a
  // resting finger renders 0.5 instead of chattering. Both 0: no fade. The
  // Kalman estimators only: the 1-euro estimators' velocity has no such model.
  float rest_sigmas = 2.5f;
  float moving_sigmas = 5.0f;
  // SplitKalman: the position filter's speed is evidence of motion too, in
  // standard deviations of its own resting noise (and excess). The direction
  // shows as far as the strongest of the filters' evidence allows: the
  // agile filter sees a start or a speed-up tens of ms before the smooth one.
  // Its levels are higher: its noise changes faster, so it crosses any level
  // more often at rest. Both 0: the direction filter's evidence alone.
  float position_rest_sigmas = 3.0f;
  float position_moving_sigmas = 6.0f;
  // SplitKalman: a third, calm filter (less acceleration noise than the
  // direction filter) whose speed is evidence of motion only. Its resting
  // noise is smaller, so a slow stroke (tens of px/s) stands out of it tens
  // of ms sooner. Wherever the direction filter is widened (a change of
  // motion, a predicted stroke end) it starts again at rest, settled, at
  // that report: its evidence is of motion since then, never of a stroke it
  // still lags behind. Its levels are higher: a calm filter's excursions at
  // rest last longer. Both 0: not run (no cost).
  KalmanConfig calm_kalman{20.0f};
  float calm_rest_sigmas = 3.5f;
  float calm_moving_sigmas = 7.0f;
  bool compensate_latency = true;      // date reports sensor.latency_us before their stamp
  // Changes of motion (starts, stops, reversals): the direction filter's
  // recent innovations, each weighted by exp(-age / maneuver_time_ms), are
  // summed; while the filter's model holds, that sum squared over its
  // variance is chi^2 with 2 degrees of freedom (above maneuver_threshold by
  // chance in exp(-threshold / 2) of reports: 0.09 % at 14). Above it the
  // finger changed its motion: the filter's covariance is widened by the
  // ratio so that it catches up instead of lagging or overshooting. A
  // consistent bias shows over a few reports long before any one report is
  // improbable. Threshold 0: never.
  float maneuver_time_ms = 12.0f;
  float maneuver_threshold = 14.0f;
  // Stroke ends: where a minimum-jerk fit to the stroke's reports says the
  // finger stops (stroke_end_predictor.hpp), the direction filter is widened
  // by this factor, as at a change of motion but on time, so that a finger
  // come to rest renders 0.5 at once; before that, the direction fades out
  // as the fitted speed falls to 0 (StrokeEndConfig::quiet_speed_px_s). 1 or
  // less: not predicted (no cost). The Kalman estimators only.
  float stroke_end_widening = 10.0f;
  // SplitKalman: at a predicted end, if the position filter reads the finger
  // slower than the direction filter does, the direction filter takes over
  // its estimate instead of being widened: the fast filter has already seen
  // the finger slow down or turn, where the smooth one still lags the stroke.
  bool stroke_end_takes_position = true;
  StrokeEndConfig stroke_end;

  uint32_t max_extrapolation_us = 15000;  // then hold the position
  uint32_t stale_timeout_us = 250000;     // no sample this long: lift-off
  uint32_t lift_off_timeout_us = 20000;   // touch = 0 this long: lift-off
  float max_speed_px_s = 5000.0f;         // 1 m/s: faster implies a second finger or a glitch
  float jump_slack_px = 25.0f;            // noise allowance on top of max speed
  float screen_margin_px = 40.0f;         // beyond the screen by more: dropped; within: clamped
  uint32_t max_tick_step_us = 100000;     // a longer step between ticks is suspect until confirmed
  uint32_t max_sample_lead_us = 2000;     // a report may be stamped this far after the last tick

  static TrackerConfig thesis();       // exactly the thesis (docs/spec.md#thesis-tracker) (no fade, no latency)
  static TrackerConfig recommended();  // the benchmarked default, for the default SensorProfile
  // The benchmarked tracker for a measured sensor (an invalid profile: the default's).
  static TrackerConfig recommended(const SensorProfile& sensor);
};

struct TrackState {
  bool present = false;  // a finger is being tracked
  Vec2 position;         // filtered position at the tick
  Vec2 velocity;         // px/s estimate
  Vec2 direction;        // unit while moving, shorter while fading, 0 at rest
};

// What the direction confidence measures speeds against: each filter's
// settled velocity variance and a resting finger's velocity noise through it
// (velocity_noise.hpp). Deriving it settles the filters: up to ~800,000 M4
// instructions with every sensor effect (docs/benchmarks.md), more than a
// tick may spend, so the device derives it in its main loop
// (HapticPipeline::set_sensor_profile) and the tick only takes it over.
struct FadeNoise {
  SpeedNoise direction, position, calm;  // per filter; zero where its evidence is unused
};
FadeNoise fade_noise(const TrackerConfig& config);

class Tracker {
 public:
  explicit Tracker(const TrackerConfig& config = TrackerConfig::recommended());
  Tracker(const TrackerConfig& config, const FadeNoise& fade);  // `fade` = fade_noise(config)
  // Both forget the finger (found again at its next report) but keep the
  // tick clock, by which that report is judged.
  void configure(const TrackerConfig& config);  // derives its FadeNoise
  // Bounded work, for the tick: `fade` must be fade_noise(config).
  void configure(const TrackerConfig& config, const FadeNoise& fade);
  void reset();  // a new start: forgets the finger and the tick clock

  // A sensor report (any order of calls with tick() is allowed). With
  // need_filter = false (the scene needs no motion) the filters are not fed;
  // they restart from the newest report when needed again.
  void on_sample(const SensorSample& s, bool need_filter = true);
  // Advances to the tick at now_us and returns the state there.
  // With need_filter = false only presence and the last sample are updated.
  const TrackState& on_tick(uint32_t now_us, bool need_filter = true);  // state()

  const TrackState& state() const { return state_; }
  const FaultCounters& faults() const { return faults_; }
  // Reports that widened the direction filter (changes of motion), since configure().
  uint32_t maneuvers() const { return maneuvers_; }
  // Predicted stroke ends that widened it, since configure().
  uint32_t stroke_ends() const { return stroke_ends_; }
  const StrokeEndPredictor& stroke_end_predictor() const { return stroke_end_; }
  FaultCounters& faults() { return faults_; }
  const TrackerConfig& config() const { return config_; }

 private:
  void restart_at(const SensorSample& s);
  void accept(const SensorSample& s, bool need_filter);
  // Further from `from` than max_speed allows in the time between (plus the slack).
  bool moved_further_than_allowed(const SensorSample& s, const SensorSample& from) const;
  void lose_finger();
  void forget_finger();  // no finger and no state to render: configure() and reset()
  Vec2 estimate(uint32_t now_us, Vec2& velocity);
  uint32_t extrapolation_us(uint32_t now_us);
  Vec2 faded_direction(Vec2 velocity) const;
  void learn_velocity_noise();

  TrackerConfig config_;
  OneEuroFilter filter_x_;
  OneEuroFilter filter_y_;
  TrackState state_;
  FaultCounters faults_;

  // Newest accepted sample and the raw velocity to it (1-euro estimators only).
  SensorSample last_;
  Vec2 raw_velocity_;            // px/us
  bool have_last_ = false;
  uint32_t ticks_since_sample_ = 0;  // the thesis' idx_extrapol
  // Jump candidate waiting for confirmation.
  SensorSample pending_jump_;
  bool have_pending_jump_ = false;
  // Lift-off bookkeeping: touch = 0 seen at untouched_since_us_.
  bool lifting_ = false;
  uint32_t untouched_since_us_ = 0;
  bool stale_reported_ = false;  // StaleSample counted once per gap
  FingerKalman direction_;  // the direction (or only) filter
  FingerKalman position_;   // SplitKalman's position filter
  FingerKalman calm_;       // SplitKalman's calm filter: evidence of slow motion
  // From the configuration, so that a report costs no squares or divisions of it.
  ReportNoise noise_;  // every filter's: white, wander and the tremor's state
  float direction_q_ = 0.0f, position_q_ = 0.0f, calm_q_ = 0.0f;  // accel_noise^2
  // Direction confidence: each filter's speed as evidence of motion.
  MotionEvidence direction_evidence_, position_evidence_, calm_evidence_;
  float calm_steady_speed_ = 0.0f;  // the calm filter's settled velocity sigma per axis: where it starts again
  uint32_t latency_us_ = 0;
  // The direction filter's recent innovations (px) and their variance while its model holds (px^2 per axis).
  Vec2 recent_innovation_;
  float recent_innovation_variance_ = 0.0f;
  float inverse_maneuver_time_s_ = 0.0f;  // 0: never widen
  uint32_t maneuvers_ = 0;
  StrokeEndPredictor stroke_end_;
  bool predict_stroke_ends_ = false;
  bool refined_this_tick_ = false;  // one refinement per tick at most: bounded work
  uint32_t stroke_ends_ = 0;
  bool filters_fresh_ = false;  // filters restarted from the last sample on next use
  uint32_t last_tick_us_ = 0;
  bool have_tick_ = false;
  // A tick time that broke the 500 us rhythm, waiting for the next to confirm it.
  uint32_t tick_candidate_us_ = 0;
  bool have_tick_candidate_ = false;
};

}  // namespace ff
