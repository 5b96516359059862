#include "frictionfield/core/sensor_profile.hpp"

#include "frictionfield/core/geometry.hpp"

namespace ff {

bool is_valid(const SensorProfile& p) {
  using L = SensorProfileLimits;
  const auto within = [](float v, float lo, float hi) { return is_finite(v) && v >= lo && v <= hi; };
  return within(p.white_noise_px, 0.0f, L::kMaxNoisePx) && p.white_noise_px > 0.0f &&
         within(p.correlated_noise_px, 0.0f, L::kMaxNoisePx) &&
         within(p.correlation_time_ms, 0.0f, L::kMaxCorrelationTimeMs) &&
         (p.correlated_noise_px == 0.0f || p.correlation_time_ms > 0.0f) &&
         within(p.tremor_px, 0.0f, L::kMaxNoisePx) && within(p.report_rate_hz, L::kMinRateHz, L::kMaxRateHz) &&
         within(p.jitter_us, 0.0f, L::kMaxJitterUs) && p.latency_us <= L::kMaxLatencyUs &&
         (p.tremor_hz == 0.0f || within(p.tremor_hz, L::kMinTremorHz, L::kMaxTremorHz));
}

bool operator==(const SensorProfile& a, const SensorProfile& b) {
  return a.white_noise_px == b.white_noise_px && a.correlated_noise_px == b.correlated_noise_px &&
         a.correlation_time_ms == b.correlation_time_ms && a.tremor_px == b.tremor_px &&
         a.report_rate_hz == b.report_rate_hz && a.jitter_us == b.jitter_us && a.latency_us == b.latency_us &&
         a.tremor_hz == b.tremor_hz;
}

}  // namespace ff
