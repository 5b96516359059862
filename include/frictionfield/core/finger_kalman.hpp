#pragma once
// The tracker's Kalman filter: the finger at constant velocity, driven by
// white acceleration, seen through the sensor's white noise and its wander
// (a third state, zero without one). Both axes share one covariance: they
// start alike and see the same intervals and noise. The tracker and the
// steady-state analysis (velocity_noise.cpp) run this same code.
#include "frictionfield/core/geometry.hpp"
#include "frictionfield/core/report_noise.hpp"

namespace ff {

struct FingerKalman {
  Vec2 p, v, e;  // finger px, finger px/s, the report's wander px
  float P00 = 0.0f, P01 = 0.0f, P02 = 0.0f, P11 = 0.0f, P12 = 0.0f, P22 = 0.0f;
  bool wander = false;  // without one its terms stay 0: skipped (the position filter, a white sensor)

  // One report z, nothing known of the speed (1 sigma initial_speed_px_s).
  void start(Vec2 z, const ReportNoise& n, float initial_speed_px_s) {
    p = z;
    v = {};
    e = {};
    P00 = n.white_variance + n.wander_variance;  // z = p + e + white
    P01 = 0.0f;
    P02 = -n.wander_variance;
    P11 = initial_speed_px_s * initial_speed_px_s;
    P12 = 0.0f;
    P22 = n.wander_variance;
    wander = n.wander_variance > 0.0f;
  }

  // dt_s later, q the acceleration's spectral density (px^2/s^3).
  inline __attribute__((always_inline)) void predict(float dt, float q, const ReportNoise& n) { advance(dt, dt, q, n); }

  // p moves by v per unit of `step` (>= 0), v wanders by white noise of
  // density q per unit of it; the report's wander decays over dt seconds.
  // predict() steps in time; the benchmark's heading model
  // (tools/track_bench/heading_bound.hpp) steps in distance travelled.
  inline __attribute__((always_inline)) void advance(float step, float dt, float q, const ReportNoise& n) {
    p.x += v.x * step;
    p.y += v.y * step;
    const float step2 = step * step;
    P00 += step * (2.0f * P01 + step * P11) + q * step2 * step * (1.0f / 3.0f);
    if (wander) {
      const float phi = n.correlation(dt);
      e.x *= phi;
      e.y *= phi;
      P02 = phi * (P02 + step * P12);
      P12 *= phi;
      P22 = phi * phi * P22 + n.wander_variance * (1.0f - phi * phi);
    }
    P01 += step * P11 + q * step2 * 0.5f;
    P11 += q * step;
  }

  // The innovation's variance per axis (z = p + e + white).
  inline __attribute__((always_inline)) float innovation_variance(const ReportNoise& n) const {
    return P00 + 2.0f * P02 + P22 + n.white_variance;
  }
  // Its inverse: the one division per report.
  inline __attribute__((always_inline)) float inverse_innovation(const ReportNoise& n) const {
    return 1.0f / innovation_variance(n);
  }

  Vec2 innovation(Vec2 z) const { return z - p - e; }

  // Scales the covariance: a filter told it knows less catches up faster.
  inline __attribute__((always_inline)) void widen(float w) {
    P00 *= w;
    P01 *= w;
    P02 *= w;
    P11 *= w;
    P12 *= w;
    P22 *= w;
  }

  struct Gains {
    float position, velocity, wander;  // k0, k1 (1/s), k2
  };
  // P H^T, H = [1 0 1]: the covariance of each state with the report.
  struct CrossCovariance {
    float h0, h1, h2;
  };
  CrossCovariance cross_covariance() const { return {P00 + P02, P01 + P12, P02 + P22}; }
  static Gains gains(const CrossCovariance& h, float inverse_s) {
    return {h.h0 * inverse_s, h.h1 * inverse_s, h.h2 * inverse_s};  // P H^T / S
  }
  Gains gains(float inverse_s) const { return gains(cross_covariance(), inverse_s); }

  inline __attribute__((always_inline)) void update(Vec2 z, float inverse_s) {
    const CrossCovariance h = cross_covariance();
    const float h0 = h.h0, h1 = h.h1, h2 = h.h2;
    const Gains k = gains(h, inverse_s);
    const float k0 = k.position, k1 = k.velocity, k2 = k.wander;
    const Vec2 r = innovation(z);
    p.x += k0 * r.x;
    p.y += k0 * r.y;
    v.x += k1 * r.x;
    v.y += k1 * r.y;
    P00 -= k0 * h0;
    P01 -= k0 * h1;
    P11 -= k1 * h1;
    if (wander) {
      e.x += k2 * r.x;
      e.y += k2 * r.y;
      P02 -= k0 * h2;
      P12 -= k1 * h2;
      P22 -= k2 * h2;
    }
  }
};

}  // namespace ff
