#pragma once
// Double-precision reference of the rendering chain of docs/spec.md, written from the
// spec and the scene data format, not from the core's code: every element's
// gradient and position-only profile, max|G| by a dense scan, the strength
// map, the DAC calibration, and the thesis tracker (algorithms 3/4 + 1-euro).
#include <cstdint>
#include <vector>

#include "frictionfield/core/amplitude_map.hpp"
#include "frictionfield/core/scene.hpp"
#include "frictionfield/core/scene_plan.hpp"
#include "frictionfield/core/sensor_sample.hpp"

namespace ff::stress {

struct DVec {
  double x = 0.0;
  double y = 0.0;
};

namespace detail {
// Every scene parameter widened to double once, so the reference's math is all double.
struct DCurve {
  CurveKind kind;
  double x0, y0, length, rise, amplitude, wavelength;
  int count;
  double px[kMaxPolylinePoints], py[kMaxPolylinePoints];
};
struct DElement {
  ElementKind kind;
  double weight;
  double cx, cy, radius, feather;                       // point
  DCurve curve;                                         // valley
  double a, band_half_width, band_feather;
  double t_x_start, t_length, t_w0, t_w1, t_scale, t_yc;  // tunnel
  double lx, ly, height;                                // texture
};

}  // namespace detail

double ref_smootherstep(double t);
// Path centre line and slope in double.
void ref_curve(const PathCurve& c, double x, double& y, double& slope);
// Unweighted height (0 for the vortex), gradient and profile of one element.
double ref_height(const FieldElement& e, double x, double y);
DVec ref_gradient(const FieldElement& e, double x, double y);
double ref_profile(const FieldElement& e, double x, double y);

class ReferenceScene {
 public:
  explicit ReferenceScene(const SceneDefinition& scene);
  DVec field(double x, double y) const;
  double profile(double x, double y) const;  // PositionOnly, clamped to [0, 1]
  // max|G| over [0, 799] x [0, 479]: 4 px scan, then refinement of the best nodes.
  double max_gradient() const { return max_gradient_; }
  // Normalise by another max|G| (the core's), so that the float32 evaluation
  // is compared apart from the accuracy of the core's search for the maximum.
  void use_max_gradient(double m) { max_gradient_ = m; }
  // Raw amplitude in [0, 1] at p for the direction d (docs/spec.md#rendering: A = 0.5 - d . G / (2 max|G|)).
  double raw_amplitude(double px, double py, double dx, double dy) const;

 private:
  double find_max_gradient() const;
  SceneDefinition scene_;
  std::vector<detail::DElement> elements_;
  double max_gradient_ = 0.0;
};

// Strength, S-curve, idle amplitude and calibration as docs/spec.md#amplitude and the
// settings' documentation define them, with the sanitising the spec asks
// for: NaN strength gives no modulation (0), others are clamped to [0, 1].
class ReferenceAmplitude {
 public:
  explicit ReferenceAmplitude(const AmplitudeSettings& settings, bool calibration_valid);
  double strength() const { return strength_; }
  double idle() const { return idle_; }
  double scale(double raw) const;
  // Code for an amplitude; `near_tie` says the exact value is within 1e-3 of
  // a rounding boundary (float and double may then round apart by one).
  int dac(double amplitude, bool* near_tie = nullptr) const;

 private:
  double strength_ = 1.0;
  double s_curve_ = 0.0;
  double idle_ = 0.0;
  std::vector<double> amps_, codes_;
};

// The 1-euro filter of docs/spec.md#thesis-tracker (thesis appendix G) in
// double, at a fixed rate: the first value passes through with derivative 0;
// the derivative from the previous filtered value (or, for the older variant,
// the previous raw value).
struct ReferenceOneEuro {
  bool from_filtered = true;
  double rate_hz = 2000.0, min_cutoff_hz = 20.0, beta = 0.0004, derivative_cutoff_hz = 25.0;
  bool init = false;
  double xhat = 0.0, xprev = 0.0, dxhat = 0.0;
  double operator()(double x);
};

// docs/spec.md#thesis-tracker in double: v_raw between samples,
// p_ext = p_k + v_raw n 500 us, 1-euro per axis (derivative from the
// previous filtered value), v_hat = dxhat / |dxhat|. Clean input only (no
// faults): the core's fault handling is not part of the spec's algorithm.
class ReferenceThesisTracker {
 public:
  void on_sample(const SensorSample& s);
  // Position and direction at the next tick.
  void on_tick(DVec& position, DVec& direction);
  bool present() const { return have_; }
  double filtered_speed() const;  // |(dxhat, dyhat)|, px/s

 private:
  ReferenceOneEuro ex_, ey_;
  bool have_ = false;
  double x_ = 0.0, y_ = 0.0, vx_ = 0.0, vy_ = 0.0;  // px, px/us
  uint32_t t_ = 0;
  uint64_t n_ = 0;
};

}  // namespace ff::stress
