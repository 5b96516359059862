#pragma once
// The noise of one sensor report as the tracker's Kalman filters see it,
// from the SensorProfile: a white part, new in every report, and a wander
// (first-order Gauss-Markov, correlated over tau) that the filters carry as
// a state of their own, so that reports closer together than tau, which
// share most of their wander, count for less than independent ones. The
// finger's tremor, which moves the reports but not the stroke, the direction
// filter carries as two more states: a damped oscillator (TremorModel).
#include "frictionfield/core/sensor_profile.hpp"
#include "frictionfield/core/tick_math.hpp"

namespace ff {

// exp(-x) for x >= 0 to within 2 % up to x = 1, decreasing, in (0, 1]:
// 1 / the exponential series to x^3 (one division, no libm on the tick path).
inline float decay(float x) { return 1.0f / (1.0f + x * (1.0f + x * (0.5f + x * (1.0f / 6.0f)))); }

// Where the tremor's frequency may lie: around the profile's measured
// frequency, or anywhere in physiological tremor's 8-12 Hz if it was not
// measured. The tremor's model resonates at its centre; the fade's resting
// noise is taken at its worst frequency.
struct TremorBand {
  static constexpr float kUnmeasuredHz = 10.0f, kUnmeasuredHalfWidthHz = 2.0f;
  // A calibration finds a steady tremor's peak to a few hundredths of a
  // hertz; a finger's wanders about it, and a session may follow the
  // calibration by hours (a resonance narrowed to the measured frequency
  // let a tremor wandering by 0.75 Hz chatter: docs/tracking-research.md).
  static constexpr float kMeasuredHalfWidthHz = 1.5f;
  float centre_hz = kUnmeasuredHz;
  float half_width_hz = kUnmeasuredHalfWidthHz;
  static TremorBand of(const SensorProfile& sensor);
};

// The tremor as a state: x'' = -w^2 x - 2 d x' + white noise, a resonance at
// the band's centre whose damping lets it follow any frequency of the band
// and a tremor that comes and goes (its correlation time 1/d = kDampingS).
// The noise is sized so that it swings as far as the profile's tremor: a
// sinusoid of peak a has variance a^2 / 2.
struct TremorModel {
  static constexpr float kDampingS = 0.15f;
  float variance = 0.0f;     // of the displacement, px^2 per axis; 0: no tremor state
  float omega2 = 0.0f;       // w^2, (rad/s)^2
  float damping = 0.0f;      // d, 1/s
  float damped_hz = 0.0f;    // sqrt(w^2 - d^2) / 2 pi: the frequency it swings at
  float inverse_damped_omega = 0.0f;  // 1 / sqrt(w^2 - d^2)

  // Over dt seconds: the displacement and its rate (c, u) become R (c, u)
  // plus noise of covariance Q, which keeps the swing stationary.
  struct Step {
    float r00, r01, r10, r11;  // R
    float q00, q01, q11;       // Q = Sigma - R Sigma R^T, Sigma = diag(s, w^2 s)
  };
  Step step(float dt) const {
    const float fade = decay(damping * dt);  // e^(-d dt)
    const SinCos w = sincos_turns(damped_hz * dt);
    const float sn = fade * w.sin * inverse_damped_omega, cs = fade * w.cos;
    Step r;
    r.r00 = cs + damping * sn;
    r.r01 = sn;
    r.r10 = -omega2 * sn;
    r.r11 = cs - damping * sn;
    const float s0 = variance, s1 = variance * omega2;
    r.q00 = s0 - (r.r00 * r.r00 * s0 + r.r01 * r.r01 * s1);
    r.q01 = -(r.r00 * r.r10 * s0 + r.r01 * r.r11 * s1);
    r.q11 = s1 - (r.r10 * r.r10 * s0 + r.r11 * r.r11 * s1);
    return r;
  }
};

struct ReportNoise {
  float white_variance = 1.0f;   // px^2
  float wander_variance = 0.0f;  // px^2, 0: no wander
  float inverse_tau_s = 0.0f;    // 1 / tau
  TremorModel tremor;            // of() leaves it empty

  // White noise and wander (the benchmark's bounds, which model no tremor).
  static ReportNoise of(const SensorProfile& sensor);
  // The same with the profile's tremor as a state: the tracker's filters'.
  static ReportNoise with_tremor(const SensorProfile& sensor);
  // The wander's correlation across dt_s: exp(-dt / tau) (decay()); 0 without a wander.
  float correlation(float dt_s) const {
    if (wander_variance <= 0.0f) return 0.0f;
    return decay(dt_s * inverse_tau_s);
  }
};


}  // namespace ff
