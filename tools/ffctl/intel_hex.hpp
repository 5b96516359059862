#pragma once
// Intel HEX into a flash image (MK66FX1M0: 1 MiB), every record checked.
#include <cstdint>
#include <string>
#include <vector>

namespace ff::ffctl {

constexpr size_t kMk66FlashBytes = 1024 * 1024;

struct FlashImage {
  std::vector<uint8_t> bytes = std::vector<uint8_t>(kMk66FlashBytes, 0xFF);  // erased flash reads 0xFF
  size_t highest = 0;  // one past the last byte written
};

// false with "line N: why" in `error`.
bool parse_intel_hex(const std::string& text, FlashImage& image, std::string& error);

}  // namespace ff::ffctl
