#include "frictionfield/core/report_noise.hpp"

namespace ff {

ReportNoise ReportNoise::of(const SensorProfile& s) {
  ReportNoise n;
  n.white_variance = s.white_noise_px * s.white_noise_px;
  if (s.correlated_noise_px > 0.0f && s.correlation_time_ms > 0.0f) {
    n.wander_variance = s.correlated_noise_px * s.correlated_noise_px;
    n.inverse_tau_s = 1e3f / s.correlation_time_ms;
  }
  return n;
}

}  // namespace ff
