#pragma once
// How ffctl reaches a device: frames out, frames in. HidTransport talks to a
// real Teensy; tests use a fake that runs the firmware on emulated devices.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace ff::ffctl {

struct DeviceInfo {
  std::string path;
  std::string serial;
  std::string product;
  uint16_t vendor_id = 0;
  uint16_t product_id = 0;
};

enum class ReceiveResult { Frame, Timeout, Disconnected };

class Transport {
 public:
  virtual ~Transport() = default;
  virtual bool send(const uint8_t* frame, size_t size) = 0;
  // One whole frame into `frame`, or nothing within `timeout_ms`.
  virtual ReceiveResult receive(std::vector<uint8_t>& frame, int timeout_ms) = 0;
  // Restart into the bootloader below the protocol (the USB stack's own
  // request, answered even by a firmware whose main loop hangs); false if
  // this transport has none or the device did not take it.
  virtual bool request_bootloader() { return false; }
};

}  // namespace ff::ffctl
