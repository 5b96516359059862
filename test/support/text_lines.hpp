// A text's lines, without their '\n': for tests that check a tool's tables.
#pragma once

#include <sstream>
#include <string>
#include <vector>

namespace ff::support {

inline std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

}  // namespace ff::support
