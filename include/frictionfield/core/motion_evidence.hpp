#pragma once
// One Kalman filter's speed as evidence that the finger moves: its squared
// speed over its velocity noise, on the fade's scale (0 at rest_sigmas, 1 at
// moving_sigmas). The noise is what a resting finger shows through the filter
// plus what the filter has not yet learned: its P11 above the settled value
// after a touch-down, a gap or a change of motion.
namespace ff {

// One filter's velocity noise, derived outside the tick (fade_noise).
struct SpeedNoise {
  float steady_variance = 0.0f;   // the filter's settled P11, px^2/s^2
  float resting_variance = 0.0f;  // a resting finger's velocity through it, per axis, px^2/s^2
};

class MotionEvidence {
 public:
  // Unused (never asked) unless `used` and moving_sigmas > rest_sigmas.
  void configure(bool used, float rest_sigmas, float moving_sigmas, const SpeedNoise& noise) {
    noise_ = noise;
    rest_level_ = rest_sigmas * rest_sigmas;
    const float span = moving_sigmas * moving_sigmas - rest_level_;
    inverse_span_ = used && span > 0.0f ? 1.0f / span : 0.0f;
    inverse_noise_ = 0.0f;
  }
  bool used() const { return inverse_span_ > 0.0f; }
  // Once per report, so that a tick costs no division for it.
  void learn(float velocity_variance) {
    const float excess = velocity_variance - noise_.steady_variance;
    inverse_noise_ = 1.0f / (noise_.resting_variance + (excess > 0.0f ? excess : 0.0f));
  }
  // Unclamped: the fade's smoothstep clamps.
  float of(float speed_squared) const { return (speed_squared * inverse_noise_ - rest_level_) * inverse_span_; }

 private:
  SpeedNoise noise_;
  float inverse_noise_ = 0.0f;  // 1 / (resting + the filter's excess P11)
  float rest_level_ = 0.0f;     // rest_sigmas^2
  float inverse_span_ = 0.0f;   // 1 / (moving^2 - rest^2); 0: unused
};

}  // namespace ff
