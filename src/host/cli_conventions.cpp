#include "frictionfield/host/cli_conventions.hpp"

#include <CLI/CLI.hpp>
#include <ctime>
#include <filesystem>

namespace ff::host {

const char* project_version() { return FF_PROJECT_VERSION; }

int parse_command_line(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);  // prints help or the error
    return code == 0 ? kExitOk : kExitBadUsage;
  }
  return -1;
}

bool same_file(const std::string& input, const std::string& output) {
  std::error_code ec;
  const bool same = std::filesystem::equivalent(input, output, ec);
  return !ec && same;
}

std::string utc_timestamp() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return buf;
}

}  // namespace ff::host
