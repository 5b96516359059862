#pragma once
// The thesis tracker of docs/spec.md#thesis-tracker (thesis appendices F and G)
// in double: the one reference the core's trackers and the stress suite's
// end-to-end chain are compared with.
#include <cstdint>

#include "frictionfield/core/sensor_sample.hpp"
#include "support/reference/reference_scene.hpp"

namespace ff::reference {

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

}  // namespace ff::reference
