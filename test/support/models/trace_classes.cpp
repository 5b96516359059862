#include "support/models/trace_classes.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace ff::tracegen {

namespace {

// Today's model: 200 Hz with 150 us stamp jitter, 1 px white noise, the zForce's 0.5 px unit.
void white_200hz(TraceOptions& o) {
  const MotionOptions plain;
  o.motion.slow_fraction = plain.slow_fraction;
  o.motion.hesitation_fraction = plain.hesitation_fraction;
  o.motion.reversal_fraction = plain.reversal_fraction;
  o.tremor = TremorOptions{};
  o.sensor = SensorOptions{};  // 200 Hz, 150 us, kNoiseLowPx
  o.sensor.quantum_px = kZForceQuantumPx;
}

// Starts, stops and careful tracing: about a fifth of the moving ticks at
// 20-70 px/s (docs/tracking.md#trace-classes), against 13 % without.
void slow_fingers_only(TraceOptions& o) {
  o.motion.slow_fraction = 0.1;
  o.motion.hesitation_fraction = 0.2;
  o.motion.reversal_fraction = 0.3;
}

// 0.3 mm peak: mid-range physiological tremor.
void tremor_only(TraceOptions& o) { o.tremor.amplitude_px = 1.5; }

// Stamped when read, 1-3 ms after the scan.
void latency_only(TraceOptions& o) {
  o.sensor.latency_us = 1000.0;
  o.sensor.latency_spread_us = 2000.0;
}

// Most of the noise a slow wander (1.5 px, the default tau of 30 ms), a little white.
void correlated_only(TraceOptions& o) {
  o.sensor.noise_px = 0.5;
  o.sensor.correlated_noise_px = 1.5;
}

void realistic(TraceOptions& o, double rate_hz) {
  white_200hz(o);
  slow_fingers_only(o);
  o.tremor.amplitude_px = 1.0;
  latency_only(o);
  correlated_only(o);
  o.sensor.rate_hz = rate_hz;
  o.sensor.period_jitter_us = 0.02 * 1e6 / rate_hz;
  o.sensor.drift_px = 2.0;  // tau: the default 10 s
}

}  // namespace

const std::vector<TraceClass>& trace_classes() {
  static const std::vector<TraceClass> kClasses = {
      {"white-200hz", "today's model: 200 Hz, 150 us stamp jitter, 1 px white noise, 0.5 px quantum", white_200hz},
      {"slow-fingers", "white-200hz with 10 % slow strokes (20-70 px/s), 20 % hesitations, 30 % sharp reversals",
       [](TraceOptions& o) { white_200hz(o); slow_fingers_only(o); }},
      {"tremor", "white-200hz with 8-12 Hz tremor of 1.5 px (0.3 mm) peak", [](TraceOptions& o) { white_200hz(o); tremor_only(o); }},
      {"latency", "white-200hz stamped 1-3 ms after the scan", [](TraceOptions& o) { white_200hz(o); latency_only(o); }},
      {"correlated-noise", "white-200hz with the noise 1.5 px Gauss-Markov (tau 30 ms) + 0.5 px white",
       [](TraceOptions& o) { white_200hz(o); correlated_only(o); }},
      {"realistic-100hz", "every effect: slow fingers, 1 px tremor, 1-3 ms latency, 2 % period jitter, "
                          "correlated noise, 2 px drift (tau 10 s); 100 Hz", [](TraceOptions& o) { realistic(o, 100.0); }},
      {"realistic-200hz", "every effect at 200 Hz", [](TraceOptions& o) { realistic(o, 200.0); }},
      {"realistic-1khz", "every effect at 1 kHz", [](TraceOptions& o) { realistic(o, 1000.0); }},
  };
  return kClasses;
}

const TraceClass* find_trace_class(const std::string& name) {
  for (const TraceClass& c : trace_classes())
    if (name == c.name) return &c;
  return nullptr;
}

namespace {

// The spread of N(0, sigma^2) clamped to [-c, c], as the sensor model clips
// its stamp and period jitter: with a = c / sigma, the variance is
// sigma^2 (erf(a/√2) - a √(2/π) e^(-a²/2)) inside plus c² erfc(a/√2) at the clip.
double clamped_normal_sd(double sigma, double c) {
  if (sigma <= 0.0) return 0.0;
  const double a = c / sigma;
  const double inside = std::erf(a / std::sqrt(2.0)) - a * std::sqrt(2.0 / M_PI) * std::exp(-0.5 * a * a);
  return std::sqrt(sigma * sigma * inside + c * c * std::erfc(a / std::sqrt(2.0)));
}

}  // namespace

SensorProfile nominal_profile(const TraceOptions& o) {
  const SensorOptions& s = o.sensor;
  const double clip_us = kJitterClipOfPeriod * 1e6 / s.rate_hz;
  const double stamp_jitter_us = clamped_normal_sd(s.jitter_us, clip_us);
  const double period_jitter_us = clamped_normal_sd(s.period_jitter_us, clip_us);
  SensorProfile p;
  p.white_noise_px = static_cast<float>(std::sqrt(s.noise_px * s.noise_px + s.quantum_px * s.quantum_px / 12.0));
  p.correlated_noise_px = static_cast<float>(s.correlated_noise_px);
  p.correlation_time_ms = s.correlated_noise_px > 0.0 ? static_cast<float>(s.correlated_noise_tau_s * 1e3) : 0.0f;
  p.tremor_px = static_cast<float>(o.tremor.amplitude_px);
  p.report_rate_hz = static_cast<float>(s.rate_hz);
  p.jitter_us = static_cast<float>(
      std::sqrt(2.0 * stamp_jitter_us * stamp_jitter_us + period_jitter_us * period_jitter_us));
  p.latency_us = static_cast<uint32_t>(std::lround(s.latency_us + 0.5 * s.latency_spread_us));
  return p;
}

SensorProfile nominal_profile(const TraceOptions& o, const GeneratedTrace& trace) {
  SensorProfile p = nominal_profile(o);
  if (trace.tremor.enabled()) p.tremor_hz = static_cast<float>(trace.tremor.frequency_hz());
  return p;
}

SensorProfile class_profile(const std::string& class_name) {
  TraceOptions options;
  const TraceClass* c = find_trace_class(class_name);
  if (c == nullptr) {  // a misspelt name in a test: stop, rather than test the default sensor
    std::fprintf(stderr, "class_profile: no trace class \"%s\"\n", class_name.c_str());
    std::abort();
  }
  c->apply(options);
  return nominal_profile(options);
}

}  // namespace ff::tracegen
