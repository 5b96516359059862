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

// The MK66FX1M0's memory (reference manual, memory map): 1 MiB of program
// flash from 0, SRAM_L + SRAM_U 0x1FFF0000..0x20030000 (256 KiB).
constexpr uint32_t kMk66RamStart = 0x1FFF0000u;
constexpr uint32_t kMk66RamEnd = 0x20030000u;

// Whether the image is for this chip, as TyTools' model check asks: its
// vector table (word 0: the initial stack pointer, inside the RAM or at its
// end; word 1: the reset handler, inside the flash and odd, i.e. Thumb code),
// and it fits the flash. false with a readable `error`.
bool check_mk66_image(const FlashImage& image, std::string& error);

}  // namespace ff::ffctl
