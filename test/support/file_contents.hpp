// A whole file's bytes as a string (empty if it cannot be read): for tests
// that check what a tool wrote.
#pragma once

#include <fstream>
#include <sstream>
#include <string>

namespace ff::support {

inline std::string file_contents(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace ff::support
