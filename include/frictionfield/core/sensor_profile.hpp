#pragma once
// What the tracker knows about its touch sensor: how noisy its reports are,
// how often they come and how late they are stamped. A lab measures it from a
// few seconds of a resting finger (ff-track-bench --calibrate,
// docs/tracking.md#calibration) and sends it to the device (the protocol's
// SensorProfile message); the tracker derives its constants from it
// (TrackerConfig::recommended(profile)).
#include <cstdint>

namespace ff {

struct SensorProfile {
  float white_noise_px = 1.0f;        // independent from report to report, 1 sigma per axis
  float correlated_noise_px = 0.0f;   // a slow wander (first-order Gauss-Markov), 1 sigma per axis
  float correlation_time_ms = 0.0f;   // the wander's time constant (0: no wander)
  float tremor_px = 0.0f;             // 8-12 Hz tremor of a resting finger, peak per axis
  float report_rate_hz = 200.0f;      // mean reports per second
  float jitter_us = 150.0f;           // 1 sigma of the report interval around its mean
  uint32_t latency_us = 0;            // from the sensor's scan to the report's stamp
  float tremor_hz = 0.0f;             // the tremor's frequency as measured (0: not measured, somewhere in 8-12 Hz)
};

// The ranges a profile must lie in (a message outside them is refused).
struct SensorProfileLimits {
  static constexpr float kMaxNoisePx = 50.0f;
  static constexpr float kMaxCorrelationTimeMs = 10000.0f;
  static constexpr float kMinRateHz = 10.0f;
  static constexpr float kMaxRateHz = 5000.0f;
  static constexpr float kMaxJitterUs = 50000.0f;
  static constexpr uint32_t kMaxLatencyUs = 50000;
  static constexpr float kMinTremorHz = 3.0f;   // parkinsonian rest tremor is 4-6 Hz
  static constexpr float kMaxTremorHz = 20.0f;
};

// Finite, within SensorProfileLimits, white noise > 0, a wander has a time
// constant, and a tremor frequency is 0 (not measured) or within its limits.
bool is_valid(const SensorProfile& profile);

// Field by field: two profiles are equal when every measured figure is.
bool operator==(const SensorProfile& a, const SensorProfile& b);
inline bool operator!=(const SensorProfile& a, const SensorProfile& b) { return !(a == b); }

}  // namespace ff
