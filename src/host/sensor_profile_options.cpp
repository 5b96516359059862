#include "frictionfield/host/sensor_profile_options.hpp"

#include <CLI/CLI.hpp>
#include <cstdio>

#include "frictionfield/host/cli_conventions.hpp"

namespace ff::host {

namespace {
constexpr const char* kGroup = "Sensor profile (docs/tracking.md#calibration)";
}  // namespace

void add_sensor_profile_options(CLI::App& app, SensorProfile& p) {
  using L = SensorProfileLimits;
  const char* group = kGroup;
  app.add_option("--white-noise-px", p.white_noise_px, "report noise independent from report to report, 1 sigma per axis")
      ->check(CLI::Range(1e-3f, L::kMaxNoisePx))->capture_default_str()->group(group);
  app.add_option("--correlated-noise-px", p.correlated_noise_px, "slow noise wander (Gauss-Markov), 1 sigma per axis")
      ->check(CLI::Range(0.0f, L::kMaxNoisePx))->capture_default_str()->group(group);
  app.add_option("--correlation-time-ms", p.correlation_time_ms, "the wander's time constant")
      ->check(CLI::Range(0.0f, L::kMaxCorrelationTimeMs))->capture_default_str()->group(group);
  app.add_option("--tremor-px", p.tremor_px, "8-12 Hz tremor of a resting finger, peak per axis")
      ->check(CLI::Range(0.0f, L::kMaxNoisePx))->capture_default_str()->group(group);
  app.add_option("--tremor-hz", p.tremor_hz, "the tremor's measured frequency (0: not measured, taken as anywhere in 8-12 Hz)")
      ->check(CLI::IsMember({0.0f}) | CLI::Range(L::kMinTremorHz, L::kMaxTremorHz))->capture_default_str()->group(group);
  app.add_option("--report-rate-hz", p.report_rate_hz, "mean sensor reports per second")
      ->check(CLI::Range(L::kMinRateHz, L::kMaxRateHz))->capture_default_str()->group(group);
  app.add_option("--jitter-us", p.jitter_us, "1 sigma of the report interval")
      ->check(CLI::Range(0.0f, L::kMaxJitterUs))->capture_default_str()->group(group);
  app.add_option("--latency-us", p.latency_us, "from the sensor's scan to the report's stamp")
      ->check(CLI::Range(0u, L::kMaxLatencyUs))->capture_default_str()->group(group);
}

bool sensor_profile_given(const CLI::App& app) {
  for (const CLI::Option* o : app.get_options()) {
    if (o->get_group() == kGroup && o->count() > 0) return true;
  }
  return false;
}

bool parse_sensor_profile_flags(const std::string& flags, SensorProfile& profile, std::string& error) {
  CLI::App app;
  SensorProfile p;
  add_sensor_profile_options(app, p);
  try {
    app.parse(flags, false);
  } catch (const CLI::ParseError& e) {
    return error = e.what(), false;
  }
  if (std::string why = non_finite_option(app); !why.empty()) return error = why, false;
  if (!is_valid(p)) return error = "the profile's values contradict each other (" + flags + ")", false;
  profile = p;
  return true;
}

std::string sensor_profile_flags(const SensorProfile& p) {
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "--white-noise-px %.3g --correlated-noise-px %.3g --correlation-time-ms %.3g --tremor-px %.3g "
                "--tremor-hz %.4g --report-rate-hz %.4g --jitter-us %.3g --latency-us %u",
                static_cast<double>(p.white_noise_px), static_cast<double>(p.correlated_noise_px),
                static_cast<double>(p.correlation_time_ms), static_cast<double>(p.tremor_px),
                static_cast<double>(p.tremor_hz), static_cast<double>(p.report_rate_hz),
                static_cast<double>(p.jitter_us),
                static_cast<unsigned>(p.latency_us));
  return buf;
}

}  // namespace ff::host
