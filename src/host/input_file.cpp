#include "frictionfield/host/input_file.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <system_error>

namespace ff::host {

bool open_input_file(const std::string& path, std::ifstream& in, std::string& why) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return why = "is a folder, not a file", false;
  in.open(path);
  if (in) return true;
  why = std::string("cannot open: ") + std::strerror(errno);
  return false;
}

}  // namespace ff::host
