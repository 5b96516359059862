#pragma once
// The project's one independent double-precision reference of the rendering
// formulas of docs/spec.md#elements: every element's height, gradient and
// position-only profile, a scene's field and max|G|, and its raw amplitude.
// Written from the spec and the scene data format (SceneDefinition is plain
// data), never from the core's code: the core's float evaluation, the bench,
// the stress suite and the tests are all judged against this one oracle.
#include <vector>

#include "frictionfield/core/scene.hpp"

namespace ff::reference {

struct DVec {
  double x = 0.0;
  double y = 0.0;
};

// A path's centre line and its slope dy/dx at x.
struct PathPoint {
  double y = 0.0;
  double slope = 0.0;
};

// v clamped to [0, 1].
double clamp01(double v);
// S5(t) = 6t^5 - 15t^4 + 10t^3 on t clamped to [0, 1].
double smootherstep(double t);
PathPoint path_at(const PathCurve& c, double x);
// The experiment's cubic path (docs/spec.md#paths): from (100, 240) to (700, 240 + rise), flat outside.
PathPoint experiment_path_at(double x, double rise);

// One element, unweighted: height (0 for the vortex, which has none), gradient, profile.
double element_height(const FieldElement& e, double x, double y);
DVec element_gradient(const FieldElement& e, double x, double y);
double element_profile(const FieldElement& e, double x, double y);

// How max|G| is found over the screen [0, 799] x [0, 479]: a scan every
// `scan_step_px`, then a compass search from the `starts` best nodes with
// steps halving from the scan step down to `last_step_px`.
struct MaxGradientSearch {
  double scan_step_px = 4.0;
  int starts = 8;
  double last_step_px = 1e-4;
};
// Every pixel centre, refined to 1e-9 px: the benchmark's accuracy reference.
constexpr MaxGradientSearch kEveryPixel{1.0, 16, 1e-9};

class ReferenceScene {
 public:
  explicit ReferenceScene(const SceneDefinition& scene, const MaxGradientSearch& search = {});
  Rendering rendering() const { return scene_.rendering; }
  double height(double x, double y) const;  // weighted sum of the element heights
  DVec field(double x, double y) const;      // weighted sum of the element gradients
  double profile(double x, double y) const;  // PositionOnly: bias + weighted profiles, clamped to [0, 1]
  double max_gradient() const { return max_gradient_; }
  // Normalise by another max|G| (the core's), so that the float32 evaluation
  // is compared apart from the accuracy of the core's search for the maximum.
  void use_max_gradient(double m) { max_gradient_ = m; }
  // Raw amplitude in [0, 1] at p for the unit direction d (docs/spec.md#rendering:
  // A = 0.5 - d . G / (2 max|G|); 0.5 for a flat or non-finite field).
  double raw_amplitude(double px, double py, double dx, double dy) const;

 private:
  double find_max_gradient(const MaxGradientSearch& search) const;
  SceneDefinition scene_;
  double max_gradient_ = 0.0;
};

}  // namespace ff::reference
