#pragma once
// Frames over the USB host channel: the Teensy's serial emulation (SEREMU,
// USB type USB_HID, interface 2), in 64-byte reports both ways: byte 0 =
// (last ? 0x80 : 0) | index, bytes 1..63 = the next 63 bytes of the frame
// (zero-padded in the last one). docs/protocol.md.
//
// Device -> host: one 64-byte IN report per report (one Serial.write of 64
// bytes fills one packet exactly); the host reads reports whole (hidapi).
// Host -> device: the OUT endpoint takes 32-byte reports (SEREMU_RX_SIZE), so
// the host sends each 64-byte report as two: bytes 0..31, then 32..63. The
// firmware must read these raw packets (usb_rx on the SEREMU endpoint) and
// join them: Serial.read() ends a packet at its first 0x00 (it takes zero
// as padding), and frames are binary.
#include <cstddef>
#include <cstdint>

#include "frictionfield/protocol/codec.hpp"

namespace ff::protocol {

constexpr size_t kHidReportBytes = 64;
constexpr size_t kHidChunkBytes = kHidReportBytes - 1;

// How many reports a frame of `size` bytes takes.
constexpr size_t reports_for(size_t size) { return (size + kHidChunkBytes - 1) / kHidChunkBytes; }
constexpr size_t kMaxHidReports = reports_for(kMaxFrame);

// Report `index` of `frame` (index < reports_for(size) <= 0x7F).
void fill_report(const uint8_t* frame, size_t size, size_t index, uint8_t* report);

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

// Host -> device reports travel as two OUT packets of this size (SEREMU_RX_SIZE).
constexpr size_t kHostPacketBytes = 32;
static_assert(2 * kHostPacketBytes == kHidReportBytes, "a report is two OUT packets");

}  // namespace ff::protocol
