#pragma once
// Teensyduino's serial emulation (SEREMU, USB type USB_HID) takes host data
// in 32-byte OUT reports (teensy3/usb_desc.h: SEREMU_RX_SIZE 32), while the
// protocol's host channel moves 64-byte reports: the host writes each as two
// OUT reports, bytes 0-31 then 32-63, and this joins them again. The packets
// must be read raw (usb_rx): usb_seremu.c's available()/getchar() take a
// packet's first 0x00 for the end of its data, and frames are binary.
#include <cstddef>
#include <cstdint>

#include "frictionfield/protocol/hid_channel.hpp"

namespace ff::firmware {

class SeremuJoiner {
 public:
  static constexpr size_t kPacketBytes = protocol::kHostPacketBytes;  // SEREMU_RX_SIZE
  static constexpr size_t kReportBytes = protocol::kHidReportBytes;
  // A first half left alone this long is stale: the host writes both halves
  // back to back, so a lost second half must not pair the next report's halves wrongly.
  static constexpr uint32_t kHalfTimeoutUs = 20000;

  // One OUT packet as usb_rx() delivered it. True when it completed a report (copied to report64).
  bool push(const uint8_t* data, size_t len, uint32_t now_us, uint8_t* report64);

  uint32_t packets_dropped() const { return dropped_; }  // wrong size or a stale first half

 private:
  uint8_t first_[kPacketBytes] = {};
  bool have_first_ = false;
  uint32_t first_us_ = 0;
  uint32_t dropped_ = 0;
};

}  // namespace ff::firmware
