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

// Those flags with `profile`'s values, e.g. "--white-noise-px 1.02 ... --latency-us 0".
std::string sensor_profile_flags(const SensorProfile& profile);

}  // namespace ff::host
