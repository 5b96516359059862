#pragma once
// docs/spec.md#amplitude in double: the strength map, the S-curve, the idle
// amplitude and the DAC calibration, with the sanitising the spec asks for.
#include <vector>

#include "frictionfield/core/amplitude_map.hpp"

namespace ff::reference {

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

}  // namespace ff::reference
