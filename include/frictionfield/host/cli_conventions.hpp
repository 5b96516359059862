#pragma once
// What every frictionfield tool shares on its command line (docs/tools.md):
// exit codes 0 ok, 1 a check failed, 2 bad usage or input; the version; and
// the output file checks (never overwrite the input, write atomically).
#include <string>

namespace CLI {
class App;
}

namespace ff::host {

constexpr int kExitOk = 0;
constexpr int kExitCheckFailed = 1;
constexpr int kExitBadUsage = 2;

// The project version (CMake's PROJECT_VERSION), e.g. "0.1.0".
const char* project_version();

// Parses argv; -1 to go on, otherwise the code to exit with (0 after --help,
// 2 after a usage error, which CLI11 or this has printed). An option's value
// that reads as nan or inf (or overflows, 1e999) is a usage error in every
// tool: CLI11's Range check lets NaN through, as every comparison with it is false.
int parse_command_line(CLI::App& app, int argc, char** argv);

// The first option given a value that reads as a non-finite number, as
// "--name value: not a finite number"; "" if none.
std::string non_finite_option(const CLI::App& app);

// True if `output` names the same file as `input` (also through a symlink,
// a hard link or another relative path); false when either does not exist.
bool same_file(const std::string& input, const std::string& output);

// The current UTC time as 2026-11-23T16:04:05Z, for metadata.
std::string utc_timestamp();

}  // namespace ff::host
