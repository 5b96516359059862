#pragma once
// One Intel HEX record as a line, checksum included: for tests that write HEX files.
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace ff::ffctl {

inline std::string hex_record(uint16_t offset, uint8_t type, const std::vector<uint8_t>& data) {
  std::vector<uint8_t> rec = {static_cast<uint8_t>(data.size()), static_cast<uint8_t>(offset >> 8),
                              static_cast<uint8_t>(offset), type};
  rec.insert(rec.end(), data.begin(), data.end());
  uint8_t sum = 0;
  for (uint8_t b : rec) sum = static_cast<uint8_t>(sum + b);
  rec.push_back(static_cast<uint8_t>(-sum));
  std::string line = ":";
  char buf[3];
  for (uint8_t b : rec) {
    std::snprintf(buf, sizeof buf, "%02X", b);
    line += buf;
  }
  return line + "\n";
}

}  // namespace ff::ffctl
