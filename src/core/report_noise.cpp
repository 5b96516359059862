#include "frictionfield/core/report_noise.hpp"

#include <cmath>

#include "frictionfield/core/geometry.hpp"

namespace ff {

namespace {
constexpr float kMinWhiteShareOfTremor = 1e-6f;
}  // namespace

ReportNoise ReportNoise::of(const SensorProfile& s) {
  ReportNoise n;
  n.white_variance = s.white_noise_px * s.white_noise_px;
  if (s.correlated_noise_px > 0.0f && s.correlation_time_ms > 0.0f) {
    n.wander_variance = s.correlated_noise_px * s.correlated_noise_px;
    n.inverse_tau_s = 1e3f / s.correlation_time_ms;
  }
  return n;
}

TremorBand TremorBand::of(const SensorProfile& s) {
  TremorBand b;
  if (s.tremor_hz > 0.0f) {  // measured
    b.centre_hz = s.tremor_hz;
    b.half_width_hz = kMeasuredHalfWidthHz;
  }
  return b;
}

ReportNoise ReportNoise::with_tremor(const SensorProfile& s) {
  ReportNoise n = of(s);
  if (!(s.tremor_px > 0.0f)) return n;
  TremorModel& t = n.tremor;
  const TremorBand band = TremorBand::of(s);
  const float w = 2.0f * kPi * band.centre_hz;
  t.variance = 0.5f * s.tremor_px * s.tremor_px;
  t.omega2 = w * w;
  t.damping = 1.0f / TremorModel::kDampingS;
  const float damped_omega = std::sqrt(t.omega2 - t.damping * t.damping);
  t.damped_hz = damped_omega / (2.0f * kPi);
  t.inverse_damped_omega = 1.0f / damped_omega;
  // A tremor far larger than the white noise (the profile allows 50 px of
  // tremor on 0.001 px of noise) leaves the float covariance's updates to
  // cancel to nothing and below: the white noise is taken as at least a
  // millionth of the tremor's variance (0.035 px at the limit), far below
  // any sensor's resolution.
  const float floor = kMinWhiteShareOfTremor * t.variance;
  if (n.white_variance < floor) n.white_variance = floor;
  return n;
}

}  // namespace ff
