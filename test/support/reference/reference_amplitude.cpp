#include "support/reference/reference_amplitude.hpp"

#include <algorithm>
#include <cmath>

#include "support/reference/reference_scene.hpp"

namespace ff::reference {

ReferenceAmplitude::ReferenceAmplitude(const AmplitudeSettings& s, bool calibration_valid) {
  const double st = s.strength;
  strength_ = std::isnan(st) ? 0.0 : clamp01(st);
  s_curve_ = std::isnan(s.s_curve) ? 0.0 : clamp01(s.s_curve);
  idle_ = std::isnan(s.idle_amplitude) ? 0.0 : clamp01(s.idle_amplitude);
  if (calibration_valid) {
    for (int i = 0; i < s.calibration.count; ++i) {
      amps_.push_back(s.calibration.amplitude[i]);
      codes_.push_back(s.calibration.code[i]);
    }
  } else {  // docs/spec.md#amplitude default: code = round(A * 4095)
    amps_ = {0.0, 1.0};
    codes_ = {0.0, 4095.0};
  }
}

double ReferenceAmplitude::scale(double raw) const {
  double a = std::isnan(raw) ? 0.5 : clamp01(raw);
  a += s_curve_ * (smootherstep(a) - a);
  return 0.5 + strength_ * (a - 0.5);
}

int ReferenceAmplitude::dac(double a, bool* near_tie) const {
  a = std::isnan(a) ? 0.0 : clamp01(a);
  size_t i = 1;
  while (i + 1 < amps_.size() && a > amps_[i]) ++i;
  const double t = (a - amps_[i - 1]) / (amps_[i] - amps_[i - 1]);
  const double c = codes_[i - 1] + t * (codes_[i] - codes_[i - 1]);
  if (near_tie != nullptr) *near_tie = std::fabs(c - std::floor(c) - 0.5) < 1e-3;
  return static_cast<int>(std::min(4095.0, std::max(0.0, std::floor(c + 0.5))));
}

}  // namespace ff::reference
