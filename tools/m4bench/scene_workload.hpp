#pragma once
// Each built-in scene's own finger workload for the cycle model (ff-m4trace),
// and the amplitude settings of the M4 accuracy check. Portable: the host's
// ff-m4accuracy uses the same settings.
#include "frictionfield/core/amplitude_map.hpp"
#include "frictionfield/core/scene.hpp"

namespace ff::bench {

struct StrokePoint {
  float x = 0.0f;
  float y = 0.0f;
};

// A 1 s stroke at 600 px/s over what the scene is about, with a sideways
// wave at 3 Hz: along the first valley's curve (+-30 px), through the tunnel
// (+-10 px), otherwise across the screen with a +-200 px wave (bumps, vortex,
// neutral: every region of the field).
class SceneWorkload {
 public:
  explicit SceneWorkload(const SceneDefinition& scene);
  StrokePoint at(float t_s) const;  // clamped to the screen

 private:
  enum class Kind { Valley, Tunnel, Sweep } kind_ = Kind::Sweep;
  PathCurve curve_;
  TunnelParams tunnel_;
};

// Strength and calibration of the accuracy check: neither is the identity.
constexpr float kAccuracyStrength = 0.8f;
DacCalibration accuracy_calibration();  // three points, decreasing (as the AD9834 wiring)

}  // namespace ff::bench
