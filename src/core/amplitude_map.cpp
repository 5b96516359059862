#include "frictionfield/core/amplitude_map.hpp"

#include "frictionfield/core/fastrun.hpp"

#include <cmath>

#include "frictionfield/core/field_element.hpp"
#include "frictionfield/core/geometry.hpp"

namespace ff {

DacCalibration DacCalibration::linear() { return DacCalibration{}; }

DacCalibration DacCalibration::inverted() {
  DacCalibration c;
  c.code[0] = 4095.0f;
  c.code[1] = 0.0f;
  return c;
}

bool DacCalibration::valid() const {
  if (count < 2 || count > kMaxCalibrationPoints) return false;
  if (amplitude[0] != 0.0f || amplitude[count - 1] != 1.0f) return false;
  const bool increasing = code[1] > code[0];
  // No test of finiteness of its own: NaN fails every ordered comparison
  // below, and an infinity lies outside 0..4095 or above the last amplitude, 1.
  for (int i = 0; i < count; ++i) {
    if (code[i] < 0.0f || code[i] > static_cast<float>(kDacMax)) return false;
    if (i == 0) continue;
    if (!(amplitude[i] > amplitude[i - 1])) return false;
    if (increasing ? !(code[i] > code[i - 1]) : !(code[i] < code[i - 1])) return false;
  }
  return true;
}

bool DacCalibration::from_points(const float* amplitudes, const float* codes, int n,
                                 DacCalibration& out) {
  DacCalibration c;
  if (amplitudes != nullptr && codes != nullptr && n >= 2 && n <= kMaxCalibrationPoints) {
    c.count = static_cast<uint8_t>(n);
    for (int i = 0; i < n; ++i) {
      c.amplitude[i] = amplitudes[i];
      c.code[i] = codes[i];
    }
    if (c.valid()) {
      out = c;
      return true;
    }
  }
  out = linear();
  return false;
}

FF_FASTRUN uint16_t DacCalibration::code_for(float a) const {
  a = clamp_finite(a, 0.0f, 1.0f, 0.0f);
  int i = 1;
  while (i < count - 1 && a > amplitude[i]) ++i;
  const float t = (a - amplitude[i - 1]) / (amplitude[i] - amplitude[i - 1]);
  const float c = code[i - 1] + t * (code[i] - code[i - 1]);
  return static_cast<uint16_t>(clamp_finite(c + 0.5f, 0.0f, static_cast<float>(kDacMax), 0.0f));
}

bool AmplitudeMap::configure(const AmplitudeSettings& in) {
  bool ok = true;
  settings_ = in;
  float& s = settings_.strength;
  if (!(s > 0.0f && s <= 1.0f)) {
    ok = false;
    s = std::isnan(s) ? 0.0f : clamp(s, 0.0f, 1.0f);  // 0: no modulation, plate at 0.5
  }
  if (!(settings_.s_curve >= 0.0f && settings_.s_curve <= 1.0f)) {
    ok = false;
    settings_.s_curve = clamp_finite(settings_.s_curve, 0.0f, 1.0f, 0.0f);
  }
  if (!(settings_.idle_amplitude >= 0.0f && settings_.idle_amplitude <= 1.0f)) {
    ok = false;
    settings_.idle_amplitude = clamp_finite(settings_.idle_amplitude, 0.0f, 1.0f, 0.0f);
  }
  if (!settings_.calibration.valid()) {
    ok = false;
    settings_.calibration = DacCalibration::linear();
  }
  idle_code_ = settings_.calibration.code_for(settings_.idle_amplitude);
  return ok;
}

FF_FASTRUN float AmplitudeMap::scale(float raw) const {
  const float s = settings_.strength;
  float a = clamp_finite(raw, 0.0f, 1.0f, 0.5f);
  if (settings_.s_curve > 0.0f) a += settings_.s_curve * (smootherstep(a) - a);
  return clamp(0.5f + s * (a - 0.5f), 0.5f - 0.5f * s, 0.5f + 0.5f * s);
}

// flatten: scale() and code_for() compiled in, one call instead of three on the tick.
FF_FASTRUN __attribute__((flatten)) AmplitudeMap::Output AmplitudeMap::output(float raw) const {
  const float a = scale(raw);
  return {a, dac_code(a)};
}

}  // namespace ff
