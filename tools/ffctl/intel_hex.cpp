#include "intel_hex.hpp"

#include <cstdio>

#include <sstream>
#include <vector>

namespace ff::ffctl {

namespace {

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

}  // namespace

bool parse_intel_hex(const std::string& text, FlashImage& image, std::string& error) {
  std::istringstream in(text);
  std::string line;
  uint32_t base = 0;  // extended segment (type 02) or linear (type 04) address
  int line_no = 0, records = 0;
  // Which bytes a record wrote (a bit each: 128 KiB, cheap to clear per file),
  // and each data record's span, to name the line an overlap disagrees with.
  std::vector<bool> written(image.bytes.size());
  struct Span {
    uint32_t address, count;
    int line;
  };
  std::vector<Span> spans;
  bool ended = false;
  auto fail = [&](const std::string& why) {
    error = "line " + std::to_string(line_no) + ": " + why;
    return false;
  };
  while (std::getline(in, line)) {
    ++line_no;
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    if (line.empty()) continue;
    if (ended) return fail("data after the end-of-file record");
    if (line[0] != ':' || line.size() < 11 || (line.size() - 1) % 2 != 0) return fail("not an Intel HEX record");
    ++records;
    std::vector<uint8_t> rec;
    for (size_t i = 1; i + 1 < line.size(); i += 2) {
      const int hi = hex_value(line[i]), lo = hex_value(line[i + 1]);
      if (hi < 0 || lo < 0) return fail("not a hex digit");
      rec.push_back(static_cast<uint8_t>(hi * 16 + lo));
    }
    const size_t count = rec[0];
    if (rec.size() != count + 5) return fail("byte count does not match the record length");
    uint8_t sum = 0;
    for (uint8_t b : rec) sum = static_cast<uint8_t>(sum + b);
    if (sum != 0) return fail("checksum mismatch");
    const uint32_t offset = static_cast<uint32_t>(rec[1] << 8 | rec[2]);
    const uint8_t type = rec[3];
    switch (type) {
      case 0x00: {
        const uint32_t address = base + offset;
        if (address + count > image.bytes.size()) return fail("data beyond the 1 MiB flash");
        for (size_t i = 0; i < count; ++i) {
          const size_t at = address + i;
          if (written[at] && image.bytes[at] != rec[4 + i]) {
            int earlier = 0;
            for (const Span& sp : spans) {
              if (at >= sp.address && at < sp.address + sp.count) earlier = sp.line;
            }
            char where[16];
            std::snprintf(where, sizeof where, "0x%06zX", at);
            return fail(std::string("overlaps line ") + std::to_string(earlier) + " at " + where +
                        " with different data");
          }
          image.bytes[at] = rec[4 + i];
          written[at] = true;
        }
        spans.push_back({address, static_cast<uint32_t>(count), line_no});
        if (address + count > image.highest) image.highest = address + count;
        break;
      }
      case 0x01:
        ended = true;
        break;
      case 0x02:
        if (count != 2) return fail("extended segment address needs 2 bytes");
        base = static_cast<uint32_t>(rec[4] << 8 | rec[5]) << 4;
        break;
      case 0x04:
        if (count != 2) return fail("extended linear address needs 2 bytes");
        base = static_cast<uint32_t>(rec[4] << 8 | rec[5]) << 16;
        break;
      case 0x03:
      case 0x05:
        break;  // start address: the bootloader starts from the reset vector
      default:
        return fail("unknown record type " + std::to_string(type));
    }
  }
  // Whole-file faults: no line to name.
  if (records == 0) return error = "no Intel HEX records (an empty file?)", false;
  if (!ended)
    return error = "no end-of-file record after line " + std::to_string(line_no) + " (a truncated file?)", false;
  if (image.highest == 0) return error = "an end-of-file record but no data", false;
  return true;
}

bool check_mk66_image(const FlashImage& image, std::string& error) {
  if (image.highest > kMk66FlashBytes) return error = "larger than the MK66's 1 MiB flash", false;
  if (image.highest < 8) return error = "no vector table at address 0 (not a Teensy 3.6 image)", false;
  const auto word = [&](size_t at) {
    return static_cast<uint32_t>(image.bytes[at]) | static_cast<uint32_t>(image.bytes[at + 1]) << 8 |
           static_cast<uint32_t>(image.bytes[at + 2]) << 16 | static_cast<uint32_t>(image.bytes[at + 3]) << 24;
  };
  const uint32_t sp = word(0), reset = word(4);
  char buf[200];
  // The stack grows down from its initial value: the end of RAM is a valid start.
  if (sp <= kMk66RamStart || sp > kMk66RamEnd) {
    std::snprintf(buf, sizeof buf,
                  "initial stack pointer 0x%08X is outside the MK66's RAM (0x%08X..0x%08X): not a Teensy 3.6 image", sp,
                  kMk66RamStart, kMk66RamEnd);
    return error = buf, false;
  }
  if ((reset & 1u) == 0 || (reset & ~1u) >= image.highest) {
    std::snprintf(buf, sizeof buf,
                  "reset vector 0x%08X is not an odd (Thumb) address inside the image (0..0x%zX): not a Teensy 3.6 image",
                  reset, image.highest);
    return error = buf, false;
  }
  return true;
}

}  // namespace ff::ffctl
