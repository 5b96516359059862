#pragma once
// A frame over 64-byte USB HID reports: byte 0 = (last ? 0x80 : 0) | index,
// bytes 1..63 = the next 63 bytes of the frame (zero-padded in the last one).
#include <cstddef>
#include <cstdint>

#include "frictionfield/protocol/codec.hpp"

namespace ff::protocol {

constexpr size_t kHidReportBytes = 64;
constexpr size_t kHidChunkBytes = kHidReportBytes - 1;
constexpr size_t kMaxHidReports = (kMaxFrame + kHidChunkBytes - 1) / kHidChunkBytes;

// Splits `frame` into reports; returns how many were written to `reports`.
size_t split_into_reports(const uint8_t* frame, size_t size, uint8_t (*reports)[kHidReportBytes],
                          size_t max_reports);

// Collects reports back into a frame. push() returns true when a frame is
// complete (frame()/size()); out-of-order or overlong input resets it and is counted.
class HidReassembler {
 public:
  bool push(const uint8_t* report);
  const uint8_t* frame() const { return buffer_; }
  size_t size() const { return complete_size_; }  // of the last complete frame
  uint32_t errors() const { return errors_; }

 private:
  uint8_t buffer_[kMaxHidReports * kHidChunkBytes] = {};
  size_t filled_ = 0;
  size_t complete_size_ = 0;
  uint8_t next_index_ = 0;
  uint32_t errors_ = 0;
};

}  // namespace ff::protocol
