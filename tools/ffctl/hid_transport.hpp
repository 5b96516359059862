#pragma once
// The device's USB HID host channel through hidapi: Teensy USB type USB_HID
// (vendor 0x16C0, product 0x0482), serial-emulation interface (usage page
// 0xFFC9), 64-byte reports carrying our fragmented frames.
#include <memory>

#include "frictionfield/protocol/hid_channel.hpp"
#include "transport.hpp"

struct hid_device_;

namespace ff::ffctl {

constexpr uint16_t kTeensyVendor = 0x16C0;
constexpr uint16_t kTeensyHidProduct = 0x0482;
constexpr uint16_t kSeremuUsagePage = 0xFFC9;

std::vector<DeviceInfo> list_devices();

class HidTransport final : public Transport {
 public:
  // Opens the device with this serial number (empty: the first one); throws
  // std::runtime_error with a readable message (missing device, permissions).
  explicit HidTransport(const std::string& serial = "");
  ~HidTransport() override;
  bool send(const uint8_t* frame, size_t size) override;
  ReceiveResult receive(std::vector<uint8_t>& frame, int timeout_ms) override;

 private:
  hid_device_* device_ = nullptr;
  protocol::HidReassembler reassembler_;
};

}  // namespace ff::ffctl
