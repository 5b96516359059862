#include "heading_bound.hpp"

#include <algorithm>
#include <cmath>

#include "direction_bound.hpp"
#include "observer_replay.hpp"
#include "stroke_end_predictor.hpp"
#include "support/statistics.hpp"

namespace ff::bench {

void StrokeHeading::touch_down(Vec2 z) { k_.start(z, noise_, kUnknownSigma); }

void StrokeHeading::forget(float variance) { k_.P11 += variance; }

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

namespace {

constexpr double kEndToleranceS = kPredictedEndToleranceMs * 1e-3;

bool predicts_ends(StrokeBoundaries b) { return b == StrokeBoundaries::PredictedEnds || b == StrokeBoundaries::TrackerEnds; }

// The tracker's clock: wrapping microseconds.
uint32_t stamp_us(double scan_s) { return static_cast<uint32_t>(std::llround(scan_s * 1e6)); }

}  // namespace

StrokeEndStats stroke_end_stats(const std::vector<StrokeEndLog>& logs) {
  StrokeEndStats stats;
  std::vector<double> delays;
  for (const StrokeEndLog& log : logs) {
    for (const auto& [first, last] : log.standstills) {
      ++stats.standstills;
      double best = INFINITY;
      for (double e : log.ends)
        if (e >= first - kEndToleranceS && e <= last + kEndToleranceS && std::fabs(e - first) < std::fabs(best))
          best = e - first;
      if (std::isfinite(best)) {
        ++stats.found;
        delays.push_back(best * 1e3);
      }
    }
  }
  for (const StrokeEndLog& log : logs) {
    for (double e : log.ends) {
      bool near = false;
      for (const auto& [first, last] : log.standstills)
        near = near || (e >= first - kEndToleranceS && e <= last + kEndToleranceS);
      if (!near) ++stats.other_ends;
    }
  }
  if (!delays.empty()) stats.median_delay_ms = support::percentile(delays, 50.0);
  return stats;
}

HeadingBoundResult heading_bound(const std::vector<PreparedCase>& cases, double moving_speed_px_s,
                                 const ReportNoise& noise, const HeadingBoundOptions& options) {
  constexpr float kUnknownSpeedPxS = 1000.0f;  // the speed filter at touch-down, as the tracker's
  const float speed_q = options.speed_accel_noise_px_s2 * options.speed_accel_noise_px_s2;
  std::vector<StrokeEndLog> logs;
  logs.reserve(cases.size());
  struct Observer {
    StrokeHeading heading;
    FingerKalman speed;
    StrokeEndPredictor predictor;
    ff::StrokeEndPredictor tracker_predictor;
    const ReportNoise& noise;
    const HeadingBoundOptions& options;
    float speed_q;
    StrokeEndLog* log;
    double last_scan_s = 0.0;
    bool in_standstill = false, touch_began_still = false;

    void report(const tracegen::TraceSample& s, const tracegen::TrueState& truth, uint64_t, double scan_s,
                bool touch_down) {
      const Vec2 z{static_cast<float>(s.x), static_cast<float>(s.y)};
      const bool still = standing_still(truth);
      if (touch_down) {
        heading.touch_down(z);
        speed.start(z, noise, kUnknownSpeedPxS);
        predictor.restart();
        predictor.report(scan_s, s.x, s.y);
        tracker_predictor.restart();
        tracker_predictor.add(stamp_us(scan_s), z);
        touch_began_still = still;
      } else {
        // Scan times are the stamps less each report's own latency: at 1 kHz
        // with 1-3 ms of it they need not increase. Out of order: no time.
        const float dt = std::max(0.0f, static_cast<float>(scan_s - last_scan_s));
        speed.predict(dt, speed_q, noise);
        speed.update(z, speed.inverse_innovation(noise));
        const float speed_px_s = length(speed.v);
        float travelled = speed_px_s * dt;
        bool new_stroke = false;
        switch (options.boundaries) {
          case StrokeBoundaries::ToldStandstills:
            new_stroke = still;
            break;
          case StrokeBoundaries::PredictedEnds:
            new_stroke = predictor.report(scan_s, s.x, s.y);
            break;
          case StrokeBoundaries::TrackerEnds:
            tracker_predictor.add(stamp_us(scan_s), z);
            new_stroke = tracker_predictor.refine_due() && tracker_predictor.refine();
            break;
          case StrokeBoundaries::None:
            break;
        }
        if (predicts_ends(options.boundaries)) {
          if (new_stroke) log->ends.push_back(scan_s);
          if (speed_px_s < options.forget_below_px_s) heading.forget(options.forget_variance_per_s * dt);
        }
        if (new_stroke) {
          heading.new_stroke();
          travelled = 0.0f;
        }
        heading.update(z, travelled, dt);
      }
      // The truth's standstills, for StrokeEndStats.
      if (still && !in_standstill && !(touch_down || touch_began_still)) log->standstills.push_back({scan_s, scan_s});
      if (still && in_standstill && !touch_began_still) log->standstills.back().second = scan_s;
      if (!still) touch_began_still = false;
      in_standstill = still;
      last_scan_s = std::max(last_scan_s, scan_s);
    }
    double amplitude(const ScenePlan& heightmap, const TickTruth& tick) const {
      return posterior_mean_amplitude(heightmap, to_vec(tick.state.position), Vec2{1.0f, 0.0f}, heading.kappa(),
                                      heading.mu());
    }
  };
  const ObserverErrors errors = observer_errors(cases, moving_speed_px_s, [&](const PreparedCase&) {
    logs.emplace_back();
    return Observer{StrokeHeading(noise, options.turn_variance_per_px),
                    FingerKalman{},
                    StrokeEndPredictor{},
                    ff::StrokeEndPredictor{},
                    noise,
                    options,
                    speed_q,
                    &logs.back()};
  });
  HeadingBoundResult result{errors.heightmap_rms, errors.rest_rms, {}, std::move(logs)};
  if (predicts_ends(options.boundaries)) result.ends = stroke_end_stats(result.end_logs);
  return result;
}

}  // namespace ff::bench
