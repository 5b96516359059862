#pragma once
// From a scene's raw amplitude to the 12-bit DAC code: optional S-shaped
// friction-to-amplitude curve, strength around 0.5, monotonic calibration.
#include <cstdint>

namespace ff {

constexpr uint16_t kDacMax = 4095;
constexpr int kMaxCalibrationPoints = 16;

// Piecewise-linear, strictly monotonic (increasing or decreasing) map from
// amplitude in [0, 1] to DAC code in [0, 4095]. Default: code = A * 4095.
struct DacCalibration {
  uint8_t count = 2;
  float amplitude[kMaxCalibrationPoints] = {0.0f, 1.0f};
  float code[kMaxCalibrationPoints] = {0.0f, 4095.0f};

  static DacCalibration linear();
  // The AD9834 FSADJUST wiring of Analog Devices' circuit note: more DAC volts, less current.
  static DacCalibration inverted();
  // Points must have strictly increasing amplitudes in [0, 1] covering 0 and 1,
  // codes in [0, 4095], strictly monotonic. Returns false (and linear()) if not.
  static bool from_points(const float* amplitudes, const float* codes, int n, DacCalibration& out);

  bool valid() const;
  uint16_t code_for(float amplitude) const;  // NaN -> code_for(0)
};

struct AmplitudeSettings {
  float strength = 1.0f;          // s in (0, 1]
  float s_curve = 0.0f;           // 0: off; 1: full quintic S between friction and amplitude
  float idle_amplitude = 0.0f;    // no finger: 0 lets the plate rest
  DacCalibration calibration = DacCalibration::linear();
};

// Sanitised settings and the mapping. Errors are counted by the caller.
class AmplitudeMap {
 public:
  // Returns false if anything had to be repaired (NaN, s outside (0, 1], bad table).
  bool configure(const AmplitudeSettings& settings);

  // A_s = 0.5 + s (curve(A) - 0.5), finite and inside [0.5 - s/2, 0.5 + s/2].
  float scale(float raw_amplitude) const;
  uint16_t dac_code(float scaled_amplitude) const { return settings_.calibration.code_for(scaled_amplitude); }
  // scale() and dac_code() in one call, for the tick.
  struct Output {
    float amplitude;
    uint16_t dac;
  };
  Output output(float raw_amplitude) const;
  float idle_amplitude() const { return settings_.idle_amplitude; }
  uint16_t idle_code() const { return idle_code_; }
  const AmplitudeSettings& settings() const { return settings_; }

 private:
  AmplitudeSettings settings_;
  uint16_t idle_code_ = 0;
};

}  // namespace ff
