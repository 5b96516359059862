// libFuzzer target: ffctl's Intel HEX reader (tools/ffctl/intel_hex), which
// takes whatever file a user hands `ffctl flash`. Whatever the text: no crash;
// a rejected file says why (never naming a line 0 it does not have); an accepted
// one holds data inside the MK66's 1 MiB, and written out again as plain data
// records (by the HEX writer ffctl's tests use) reads back to the same image;
// the model check never reads past what was written.
//
// Build: clang++ -fsanitize=fuzzer,address,undefined with intel_hex.cpp.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "hex_record.hpp"  // tools/ffctl/test
#include "intel_hex.hpp"

namespace ff::fuzz {

namespace {

void check(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "intel_hex_fuzz: %s\n", what);
    std::abort();
  }
}

// The image's bytes [0, highest) as 16-byte data records, an extended linear
// address record at every 64 KiB, and the end record.
std::string written_out(const ffctl::FlashImage& image) {
  std::string text;
  for (size_t at = 0; at < image.highest; at += 16) {
    if (at % 0x10000 == 0 && at != 0) {
      text += ffctl::hex_record(0, 0x04, {static_cast<uint8_t>(at >> 24), static_cast<uint8_t>(at >> 16)});
    }
    const size_t count = image.highest - at < 16 ? image.highest - at : 16;
    const auto first = image.bytes.begin() + static_cast<std::ptrdiff_t>(at);
    text += ffctl::hex_record(static_cast<uint16_t>(at), 0x00,
                              std::vector<uint8_t>(first, first + static_cast<std::ptrdiff_t>(count)));
  }
  return text + ffctl::hex_record(0, 0x01, {});
}

// A fresh image, as `ffctl flash` reads into: erased, nothing written. The
// two images live across inputs: a new 1 MiB per input cost AddressSanitizer's
// allocator an mmap and 256 page faults, 26 of the smoke run's 31 s in the kernel.
ffctl::FlashImage& erased(ffctl::FlashImage& image) {
  std::fill(image.bytes.begin(), image.bytes.end(), uint8_t{0xFF});
  image.highest = 0;
  return image;
}

}  // namespace

int intel_hex_one_input(const uint8_t* data, size_t size) {
  static ffctl::FlashImage read_image, read_again;
  const std::string text(reinterpret_cast<const char*>(data), size);
  ffctl::FlashImage& image = erased(read_image);
  std::string error;
  if (!ffctl::parse_intel_hex(text, image, error)) {
    check(!error.empty(), "a rejected file has no reason");
    check(error.rfind("line 0:", 0) != 0, "a rejection names a line the file does not have");
    return 0;
  }
  check(image.highest >= 1 && image.highest <= ffctl::kMk66FlashBytes, "accepted data outside the 1 MiB flash");
  check(image.bytes.size() == ffctl::kMk66FlashBytes, "the image changed size");
  ffctl::FlashImage& again = erased(read_again);
  check(ffctl::parse_intel_hex(written_out(image), again, error), "the image written out does not read back");
  check(again.highest == image.highest && again.bytes == image.bytes, "the image written out reads back different");
  if (ffctl::check_mk66_image(image, error)) {
    check(image.highest >= 8, "a vector table shorter than two words passed the model check");
  } else {
    check(!error.empty(), "a refused image has no reason");
  }
  return 0;
}

}  // namespace ff::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return ff::fuzz::intel_hex_one_input(data, size);
}
