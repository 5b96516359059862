#pragma once
// The tracker's Kalman filter: the finger at constant velocity, driven by
// white acceleration, seen through the sensor's white noise and its wander
// (a third state, zero without one) and the finger's tremor (a damped
// oscillator, two more states, report_noise.hpp; zero without one). Both
// axes share one covariance: they start alike and see the same intervals and
// noise. The tracker and the steady-state analysis (velocity_noise.cpp) run
// this same code.
#include "frictionfield/core/geometry.hpp"
#include "frictionfield/core/report_noise.hpp"

namespace ff {

struct FingerKalman {
  Vec2 p, v, e;  // finger px, finger px/s, the report's wander px
  Vec2 c, u;     // the tremor's displacement px and rate px/s
  float P00 = 0.0f, P01 = 0.0f, P02 = 0.0f, P11 = 0.0f, P12 = 0.0f, P22 = 0.0f;
  // The tremor's covariances: with the finger and the wander (P03 ... P24), its own (P33, P34, P44).
  float P03 = 0.0f, P04 = 0.0f, P13 = 0.0f, P14 = 0.0f, P23 = 0.0f, P24 = 0.0f, P33 = 0.0f, P34 = 0.0f, P44 = 0.0f;
  bool wander = false;  // without one its terms stay 0: skipped (the position filter, a white sensor)
  bool tremor = false;  // likewise (a profile without tremor)

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
    // z = p + e + c as well: the tremor at rest, its phase unknown.
    c = {};
    u = {};
    tremor = n.tremor.variance > 0.0f;
    P00 += n.tremor.variance;
    P03 = -n.tremor.variance;
    P04 = P13 = P14 = P23 = P24 = P34 = 0.0f;
    P33 = n.tremor.variance;
    P44 = n.tremor.variance * n.tremor.omega2;
  }

  // dt_s later, q the acceleration's spectral density (px^2/s^3).
  inline __attribute__((always_inline)) void predict(float dt, float q, const ReportNoise& n) { advance(dt, dt, q, n); }

  // p moves by v per unit of `step` (>= 0), v wanders by white noise of
  // density q per unit of it; the report's wander decays over dt seconds.
  // predict() steps in time; the benchmark's heading model
  // (tools/track_bench/heading_bound.hpp) steps in distance travelled.
  inline __attribute__((always_inline)) void advance(float step, float dt, float q, const ReportNoise& n) {
    if (tremor) advance_tremor(step, dt, n);
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

  // The tremor's part of advance(): its own step, and its covariance with
  // the other states carried through theirs ([[1 step] [0 1]] and the
  // wander's phi on the left, R on the right). It computes phi itself:
  // advance() computing it once outside its branch cost the default profile
  // 12 M4 instructions a report (measured) to save one decay() here.
  void advance_tremor(float step, float dt, const ReportNoise& n) {
    const TremorModel::Step r = n.tremor.step(dt);
    const Vec2 c0 = c, u0 = u;
    c = {r.r00 * c0.x + r.r01 * u0.x, r.r00 * c0.y + r.r01 * u0.y};
    u = {r.r10 * c0.x + r.r11 * u0.x, r.r10 * c0.y + r.r11 * u0.y};
    const float phi = wander ? n.correlation(dt) : 0.0f;
    const float y03 = P03 + step * P13, y04 = P04 + step * P14;  // the finger's rows stepped
    const float y23 = phi * P23, y24 = phi * P24;
    P03 = y03 * r.r00 + y04 * r.r01;
    P04 = y03 * r.r10 + y04 * r.r11;
    const float p13 = P13, p14 = P14;
    P13 = p13 * r.r00 + p14 * r.r01;
    P14 = p13 * r.r10 + p14 * r.r11;
    P23 = y23 * r.r00 + y24 * r.r01;
    P24 = y23 * r.r10 + y24 * r.r11;
    const float a = r.r00 * P33 + r.r01 * P34, b = r.r00 * P34 + r.r01 * P44;  // first row of R P
    const float d = r.r10 * P33 + r.r11 * P34, f = r.r10 * P34 + r.r11 * P44;  // second
    P33 = a * r.r00 + b * r.r01 + r.q00;
    P34 = a * r.r10 + b * r.r11 + r.q01;
    P44 = d * r.r10 + f * r.r11 + r.q11;
  }

  // The innovation's variance per axis (z = p + e + c + white).
  inline __attribute__((always_inline)) float innovation_variance(const ReportNoise& n) const {
    const float s = P00 + 2.0f * P02 + P22 + n.white_variance;
    return tremor ? s + 2.0f * (P03 + P23) + P33 : s;
  }
  // Its inverse: the one division per report.
  inline __attribute__((always_inline)) float inverse_innovation(const ReportNoise& n) const {
    return 1.0f / innovation_variance(n);
  }

  Vec2 innovation(Vec2 z) const { return z - p - e - c; }

  // Scales the covariance: a filter told it knows less catches up faster.
  // Not the tremor's own: a change of the finger's motion says nothing new
  // of it. The wander's only up to kMaxWanderWidening times its stationary
  // variance, what one widening from there may reach: the reports see only
  // the finger plus the wander, so repeated widenings would inflate both
  // without bound (with a long correlation time nothing pulls them back)
  // until the innovation's variance, their difference, rounds to 0 or below
  // and the filter diverges. Each state i is scaled by f_i, each covariance
  // by sqrt(f_i f_j): still positive definite.
  static constexpr float kMaxWanderWidening = 100.0f;
  inline __attribute__((always_inline)) void widen(float w, const ReportNoise& n) {
    float w_wander = w;
    const float wander_cap = kMaxWanderWidening * n.wander_variance;
    if (wander && P22 * w > wander_cap) {
      w_wander = P22 < wander_cap ? wander_cap / P22 : 1.0f;
    }
    const float finger_wander = std::sqrt(w * w_wander);
    P00 *= w;
    P01 *= w;
    P11 *= w;
    P02 *= finger_wander;
    P12 *= finger_wander;
    P22 *= w_wander;
    if (tremor) {
      const float r = std::sqrt(w), r_wander = std::sqrt(w_wander);
      P03 *= r;
      P04 *= r;
      P13 *= r;
      P14 *= r;
      P23 *= r_wander;
      P24 *= r_wander;
    }
  }

  struct Gains {
    float position, velocity, wander;  // k0, k1 (1/s), k2
    float tremor, tremor_rate;         // k3, k4 (1/s)
  };
  // P H^T, H = [1 0 1 1 0]: the covariance of each state with the report.
  struct CrossCovariance {
    float h0, h1, h2, h3, h4;
  };
  CrossCovariance cross_covariance() const {
    if (!tremor) return {P00 + P02, P01 + P12, P02 + P22, 0.0f, 0.0f};
    return {P00 + P02 + P03, P01 + P12 + P13, P02 + P22 + P23, P03 + P23 + P33, P04 + P24 + P34};
  }
  static Gains gains(const CrossCovariance& h, float inverse_s) {
    return {h.h0 * inverse_s, h.h1 * inverse_s, h.h2 * inverse_s, h.h3 * inverse_s, h.h4 * inverse_s};  // P H^T / S
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
    if (tremor) {
      const float h3 = h.h3, h4 = h.h4, k3 = k.tremor, k4 = k.tremor_rate;
      c.x += k3 * r.x;
      c.y += k3 * r.y;
      u.x += k4 * r.x;
      u.y += k4 * r.y;
      P03 -= k0 * h3;
      P04 -= k0 * h4;
      P13 -= k1 * h3;
      P14 -= k1 * h4;
      P23 -= k2 * h3;
      P24 -= k2 * h4;
      P33 -= k3 * h3;
      P34 -= k3 * h4;
      P44 -= k4 * h4;
    }
  }
};

}  // namespace ff
