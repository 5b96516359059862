#include "hid_transport.hpp"

#include <hidapi.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <stdexcept>

#include "frictionfield/protocol/hid_channel.hpp"

namespace ff::ffctl {

namespace {

std::string narrow(const wchar_t* w) {
  std::string s;
  for (; w && *w; ++w) s += static_cast<char>(*w < 128 ? *w : '?');
  return s;
}

struct HidInit {
  HidInit() { hid_init(); }
  ~HidInit() { hid_exit(); }
};
HidInit& hid() {
  static HidInit init;
  return init;
}

}  // namespace

std::vector<DeviceInfo> list_devices() {
  hid();
  std::vector<DeviceInfo> out;
  hid_device_info* all = hid_enumerate(kTeensyVendor, kTeensyHidProduct);
  for (hid_device_info* d = all; d; d = d->next) {
    if (d->usage_page != kSeremuUsagePage) continue;
    out.push_back({d->path, narrow(d->serial_number), narrow(d->product_string), d->vendor_id, d->product_id});
  }
  hid_free_enumeration(all);
  return out;
}

HidTransport::HidTransport(const std::string& serial) {
  for (const DeviceInfo& d : list_devices()) {
    if (!serial.empty() && d.serial != serial) continue;
    device_ = hid_open_path(d.path.c_str());
    if (!device_) {
      throw std::runtime_error("found " + d.path + " but cannot open it: permission denied? Install udev/49-frictionfield.rules "
                               "(see docs/ffctl.md) and replug the device");
    }
    return;
  }
  throw std::runtime_error(serial.empty() ? "no frictionfield device on USB (vendor 16c0, product 0482): is it plugged in "
                                            "and flashed with the USB_HID firmware? `ffctl list` shows what is there"
                                          : "no frictionfield device with serial number " + serial);
}

HidTransport::~HidTransport() {
  if (device_) hid_close(device_);
}

bool HidTransport::send(const uint8_t* frame, size_t size) {
  static_assert(2 * kSeremuOutReportBytes == protocol::kHidReportBytes, "a report is two OUT reports");
  uint8_t reports[protocol::kMaxHidReports][protocol::kHidReportBytes];
  const size_t n = protocol::split_into_reports(frame, size, reports, protocol::kMaxHidReports);
  for (size_t i = 0; i < n; ++i) {
    for (size_t half = 0; half < 2; ++half) {
      uint8_t packet[1 + kSeremuOutReportBytes] = {0};  // report id 0
      const uint8_t* from = reports[i] + half * kSeremuOutReportBytes;
      std::copy(from, from + kSeremuOutReportBytes, packet + 1);
      if (hid_write(device_, packet, sizeof packet) < 0) return false;
    }
  }
  return n > 0;
}

bool HidTransport::request_bootloader() {
  const uint8_t report[5] = {0, kSeremuRebootMagic[0], kSeremuRebootMagic[1], kSeremuRebootMagic[2],
                             kSeremuRebootMagic[3]};  // report id 0: wValue 0x0300, wLength 4
  return hid_send_feature_report(device_, report, sizeof report) >= 0;
}

ReceiveResult HidTransport::receive(std::vector<uint8_t>& frame, int timeout_ms) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
  uint8_t report[protocol::kHidReportBytes];
  for (;;) {
    const int left = static_cast<int>(
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now()).count());
    if (left <= 0) return ReceiveResult::Timeout;
    const int n = hid_read_timeout(device_, report, sizeof report, left);
    // A signal (Ctrl-C ending a recording) interrupts hidraw's poll(), which is
    // never restarted: -1 with EINTR, the device still there. Read on; the
    // caller sees the stop at its next frame.
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return ReceiveResult::Disconnected;
    if (n == 0) return ReceiveResult::Timeout;
    if (reassembler_.push(report)) {
      frame.assign(reassembler_.frame(), reassembler_.frame() + reassembler_.size());
      return ReceiveResult::Frame;
    }
  }
}

}  // namespace ff::ffctl
