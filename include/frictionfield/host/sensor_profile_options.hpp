#pragma once
// The SensorProfile on a command line: the same flags in every tool
// (ffctl sensor-profile, ff-replay, ff-track-bench), and the line that
// ff-track-bench --calibrate prints for them.
#include <string>

#include "frictionfield/core/sensor_profile.hpp"

namespace CLI {
class App;
}

namespace ff::host {

// --white-noise-px, --correlated-noise-px, --correlation-time-ms, --tremor-px,
// --report-rate-hz, --jitter-us, --latency-us, each defaulting to `profile`'s value.
void add_sensor_profile_options(CLI::App& app, SensorProfile& profile);

// Whether the command line gave any of those flags (else a tool may take the
// profile a recording names).
bool sensor_profile_given(const CLI::App& app);

// `flags` as those options would take them (a recording's "sensor-profile"
// line); false with `error` for an unknown flag, a value out of its range, or
// a profile whose values contradict each other.
bool parse_sensor_profile_flags(const std::string& flags, SensorProfile& profile, std::string& error);

// Those flags with `profile`'s values, e.g. "--white-noise-px 1.02 ... --latency-us 0".
std::string sensor_profile_flags(const SensorProfile& profile);

}  // namespace ff::host
