#pragma once
// The noise of one sensor report as the tracker's Kalman filters see it,
// from the SensorProfile: a white part, new in every report, and a wander
// (first-order Gauss-Markov, correlated over tau) that the filters carry as
// a state of their own, so that reports closer together than tau, which
// share most of their wander, count for less than independent ones.
#include "frictionfield/core/sensor_profile.hpp"

namespace ff {

// exp(-x) for x >= 0 to within 2 % up to x = 1, decreasing, in (0, 1]:
// 1 / the exponential series to x^3 (one division, no libm on the tick path).
inline float decay(float x) { return 1.0f / (1.0f + x * (1.0f + x * (0.5f + x * (1.0f / 6.0f)))); }

struct ReportNoise {
  float white_variance = 1.0f;   // px^2
  float wander_variance = 0.0f;  // px^2, 0: no wander
  float inverse_tau_s = 0.0f;    // 1 / tau

  static ReportNoise of(const SensorProfile& sensor);
  // The wander's correlation across dt_s: exp(-dt / tau) (decay()); 0 without a wander.
  float correlation(float dt_s) const {
    if (wander_variance <= 0.0f) return 0.0f;
    return decay(dt_s * inverse_tau_s);
  }
};


}  // namespace ff
