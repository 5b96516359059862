#include "frictionfield/host/cli_conventions.hpp"

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>

namespace ff::host {

const char* project_version() { return FF_PROJECT_VERSION; }

std::string non_finite_option(const CLI::App& app) {
  for (const CLI::Option* o : app.get_options()) {
    if (o->get_positional() || o->count() == 0) continue;  // a file may be called "nan"
    for (const std::string& value : o->results()) {
      char* end = nullptr;
      const double v = std::strtod(value.c_str(), &end);
      if (end != value.c_str() && *end == '\0' && !std::isfinite(v)) {
        return o->get_name() + " " + value + ": not a finite number";
      }
    }
  }
  for (const CLI::App* sub : app.get_subcommands()) {
    if (std::string why = non_finite_option(*sub); !why.empty()) return why;
  }
  return "";
}

int parse_command_line(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);  // prints help or the error
    return code == 0 ? kExitOk : kExitBadUsage;
  }
  if (const std::string why = non_finite_option(app); !why.empty()) {
    const std::string tool = std::filesystem::path(argc > 0 ? argv[0] : "").filename().string();
    std::fprintf(stderr, "%s: %s\n", tool.c_str(), why.c_str());
    return kExitBadUsage;
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
