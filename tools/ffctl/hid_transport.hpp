#pragma once
// The device's USB HID host channel through hidapi: Teensy USB type USB_HID
// (vendor 0x16C0, product 0x0482), serial-emulation interface (SEREMU, usage
// page 0xFFC9). Frames travel in 64-byte report fragments
// (frictionfield/protocol/hid_channel.hpp): read as 64-byte IN reports,
// written as two 32-byte OUT reports each (SEREMU_RX_SIZE is 32).
#include <memory>

#include "frictionfield/protocol/hid_channel.hpp"
#include "transport.hpp"

struct hid_device_;

namespace ff::ffctl {

constexpr uint16_t kTeensyVendor = 0x16C0;
constexpr uint16_t kTeensyHidProduct = 0x0482;
constexpr uint16_t kSeremuUsagePage = 0xFFC9;
constexpr size_t kSeremuOutReportBytes = 32;
// Teensyduino's usb_dev.c restarts into the bootloader 5 ms after a 4-byte
// feature report (SET_REPORT, wValue 0x0300) with these bytes on the SEREMU
// interface; it is the USB interrupt's doing, not the firmware's loop.
constexpr uint8_t kSeremuRebootMagic[4] = {0xA9, 0x45, 0xC2, 0x6B};

std::vector<DeviceInfo> list_devices();

class HidTransport final : public Transport {
 public:
  // Opens the device with this serial number (empty: the first one); throws
  // std::runtime_error with a readable message (missing device, permissions).
  explicit HidTransport(const std::string& serial = "");
  ~HidTransport() override;
  bool send(const uint8_t* frame, size_t size) override;
  ReceiveResult receive(std::vector<uint8_t>& frame, int timeout_ms) override;
  bool request_bootloader() override;

 private:
  hid_device_* device_ = nullptr;
  protocol::HidReassembler reassembler_;
};

}  // namespace ff::ffctl
