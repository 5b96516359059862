#pragma once
// What the reports can tell of a stroke's direction (issue 14): the
// heightmap error of an observer told everything about the finger but where
// each stroke goes. It knows the true path of the stroke up to a rotation
// about the point where the finger last stood still, when each stroke
// starts, the tremor, the drift, the stamp latency and the noise's model;
// only the rotation is unknown, uniform a priori at each start. With
// Gaussian noise (white plus the wander, a Gauss-Markov process) the
// rotation's posterior is exactly a von Mises distribution, and the observer
// renders the amplitude's posterior mean: the least squared error any
// renderer with that knowledge reaches on average over strokes turned at
// random. On the actual strokes, in a scene that is not the same in every
// direction, a renderer can beat it by a little; so it is a floor for
// trackers that assume nothing about where a stroke goes, not a strict
// bound. Not a tracker: it reads the truth.
#include <array>
#include <vector>

#include "support/models/sensor_model.hpp"
#include "support/models/trace_classes.hpp"
#include "tracking_evaluation.hpp"

namespace ff::bench {

// The report noise the observer does not know: white (the quantum's
// uniform error counted as white) and the wander. 1 sigma per axis.
struct UnknownNoise {
  double white_px = 1.0;
  double wander_px = 0.0;
  double wander_tau_s = 0.03;
};
UnknownNoise unknown_noise(const tracegen::SensorOptions& sensor);

// The same traces without the drift: the generator draws the drift from a
// stream of its own, so everything else is unchanged (the observer knows it).
std::vector<TrackCase> without_drift(std::vector<TrackCase> cases);

// Rotation c = (cos phi, sin phi) of a stroke's known displacement d_k from
// its anchor, seen as e_k = R(phi) d_k + w_k + g_k (w white, g the wander),
// estimated with c free in the plane (a linear Kalman filter, c constant, g
// Gauss-Markov) and then restricted to the unit circle: there the Gaussian's
// log density is kappa cos(phi - mu) + const with (kappa cos mu, kappa sin
// mu) = Lambda c_hat, Lambda the information of c (isotropic by symmetry).
class StrokeRotation {
 public:
  explicit StrokeRotation(const UnknownNoise& noise);
  void touch_down();   // the wander unknown again (its stationary spread), and the rotation
  void new_stroke();   // the rotation unknown again; the wander's estimate kept
  void predict(double dt_s);
  // One report minus the anchor (and the tremor), and the stroke's true
  // displacement from the anchor at the report's scan time.
  void update(double ex, double ey, double dx, double dy);
  double kappa() const;
  double mu() const;  // radians

 private:
  std::array<double, 2> information_times_mean() const;  // (kappa cos mu, kappa sin mu)
  UnknownNoise noise_;
  std::array<double, 4> x_{};       // c1, c2, gx, gy
  std::array<double, 16> p_{};      // row-major covariance
};

// The posterior mean of the heightmap amplitude at `position` when the
// direction is `direction` turned by phi ~ von Mises(mu, kappa): a 61-point
// rule over +-6 spreads of phi (the whole circle when wider), the mean
// direction alone above kappa 1e8.
double posterior_mean_amplitude(const ScenePlan& heightmap, Vec2 position, Vec2 direction, double kappa, double mu);

// The observer of one trace (observer_replay.hpp): the rotation of each
// stroke about where the finger last stood still (or touched down), from
// the reports less the tremor and the truth's path since that anchor.
class RotationObserver {
 public:
  RotationObserver(const UnknownNoise& noise, const tracegen::GeneratedTrace& trace) : rotation_(noise), trace_(trace) {}
  void report(const tracegen::TraceSample& s, const tracegen::TrueState& truth, uint64_t scanned_us, double scan_s,
              bool touch_down);
  double amplitude(const ScenePlan& heightmap, const TickTruth& tick) const;
  const StrokeRotation& rotation() const { return rotation_; }

 private:
  StrokeRotation rotation_;
  const tracegen::GeneratedTrace& trace_;
  double last_scan_s_ = 0.0;
  tracegen::Point anchor_;
};

// RMS of |A - A_ideal| over the moving ticks (as Metrics::heightmap_rms
// counts them, from the first report of each touch) of the observer's
// posterior-mean amplitude; the cases generated without drift.
double direction_bound_heightmap_rms(const std::vector<PreparedCase>& cases, double moving_speed_px_s,
                                     const UnknownNoise& noise);

// The bound on a class's cases (class_cases(trace_class, duration_s)):
// generated again without the drift where the class has one.
double class_direction_bound(const tracegen::TraceClass& trace_class, const std::vector<PreparedCase>& cases,
                             double duration_s, double moving_speed_px_s);

}  // namespace ff::bench
