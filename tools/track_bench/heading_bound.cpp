#include "heading_bound.hpp"

#include <algorithm>
#include <cmath>

#include "direction_bound.hpp"
#include "observer_replay.hpp"

namespace ff::bench {

void StrokeHeading::touch_down(Vec2 z) { k_.start(z, noise_, kUnknownSigma); }

void StrokeHeading::new_stroke() {
  k_.v = {};
  k_.P01 = 0.0f;
  k_.P12 = 0.0f;
  k_.P11 = kUnknownSigma * kUnknownSigma;
}

void StrokeHeading::update(Vec2 z, float travelled_px, float dt_s) {
  k_.advance(travelled_px, dt_s, turn_, noise_);
  k_.update(z, k_.inverse_innovation(noise_));
}

// u ~ N(u_hat, P11 I) on the unit circle: log density u_hat . c / P11 + const.
double StrokeHeading::kappa() const {
  return std::hypot(static_cast<double>(k_.v.x), static_cast<double>(k_.v.y)) / static_cast<double>(k_.P11);
}

double StrokeHeading::mu() const { return std::atan2(static_cast<double>(k_.v.y), static_cast<double>(k_.v.x)); }

double heading_bound_heightmap_rms(const std::vector<PreparedCase>& cases, double moving_speed_px_s,
                                   const ReportNoise& noise, const HeadingBoundOptions& options) {
  constexpr float kUnknownSpeedPxS = 1000.0f;  // the speed filter at touch-down, as the tracker's
  const float speed_q = options.speed_accel_noise_px_s2 * options.speed_accel_noise_px_s2;
  struct Observer {
    StrokeHeading heading;
    FingerKalman speed;
    const ReportNoise& noise;
    float speed_q;
    bool told_standstills;
    double last_scan_s = 0.0;

    void report(const tracegen::TraceSample& s, const tracegen::TrueState& truth, uint64_t, double scan_s,
                bool touch_down) {
      const Vec2 z{static_cast<float>(s.x), static_cast<float>(s.y)};
      if (touch_down) {
        heading.touch_down(z);
        speed.start(z, noise, kUnknownSpeedPxS);
      } else {
        // Scan times are the stamps less each report's own latency: at 1 kHz
        // with 1-3 ms of it they need not increase. Out of order: no time.
        const float dt = std::max(0.0f, static_cast<float>(scan_s - last_scan_s));
        speed.predict(dt, speed_q, noise);
        speed.update(z, speed.inverse_innovation(noise));
        float travelled = length(speed.v) * dt;
        if (told_standstills && standing_still(truth)) {
          heading.new_stroke();
          travelled = 0.0f;
        }
        heading.update(z, travelled, dt);
      }
      last_scan_s = std::max(last_scan_s, scan_s);
    }
    double amplitude(const ScenePlan& heightmap, const TickTruth& tick) const {
      return posterior_mean_amplitude(heightmap, to_vec(tick.state.position), Vec2{1.0f, 0.0f}, heading.kappa(),
                                      heading.mu());
    }
  };
  return observer_heightmap_rms(cases, moving_speed_px_s, [&](const PreparedCase&) {
    return Observer{StrokeHeading(noise, options.turn_variance_per_px), FingerKalman{}, noise, speed_q,
                    options.told_standstills};
  });
}

}  // namespace ff::bench
