#include "scene_workload.hpp"

#include <algorithm>
#include <cmath>

#include "frictionfield/core/geometry.hpp"

namespace ff::bench {

SceneWorkload::SceneWorkload(const SceneDefinition& scene) {
  for (int i = 0; i < scene.element_count; ++i) {
    const FieldElement& e = scene.elements[i];
    if (e.kind == ElementKind::PathSink) {
      kind_ = Kind::Valley;
      curve_ = e.valley.curve;
      return;
    }
    if (e.kind == ElementKind::Tunnel) {
      kind_ = Kind::Tunnel;
      tunnel_ = e.tunnel;
      return;
    }
  }
}

StrokePoint SceneWorkload::at(float t_s) const {
  const float wave = std::sin(2.0f * kPi * 3.0f * t_s);
  StrokePoint p;
  switch (kind_) {
    case Kind::Valley:
      p.x = 100.0f + 600.0f * t_s;
      p.y = curve_.at(p.x).y + 30.0f * wave;
      break;
    case Kind::Tunnel:
      p.x = tunnel_.x_start - 50.0f + 600.0f * t_s;
      p.y = tunnel_.y_centre + 10.0f * wave;
      break;
    case Kind::Sweep:
      p.x = 100.0f + 600.0f * t_s;
      p.y = 240.0f + 200.0f * wave;
      break;
  }
  p.x = std::clamp(p.x, 0.0f, kScreenMaxX);
  p.y = std::clamp(p.y, 0.0f, kScreenMaxY);
  return p;
}

DacCalibration accuracy_calibration() {
  const float amplitudes[] = {0.0f, 0.4f, 1.0f};
  const float codes[] = {4000.0f, 2500.0f, 300.0f};
  DacCalibration c;
  DacCalibration::from_points(amplitudes, codes, 3, c);
  return c;
}

}  // namespace ff::bench
