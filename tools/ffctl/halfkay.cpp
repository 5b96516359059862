#include "halfkay.hpp"

#include <libusb.h>

#include <chrono>
#include <thread>

namespace ff::ffctl {

std::vector<HalfKayWrite> halfkay_writes(const FlashImage& image) {
  std::vector<HalfKayWrite> out;
  for (size_t addr = 0; addr < image.highest; addr += kHalfKayBlock) {
    bool blank = true;
    for (size_t i = 0; i < kHalfKayBlock && blank; ++i) blank = image.bytes[addr + i] == 0xFF;
    if (blank && addr != 0) continue;
    HalfKayWrite w;
    w.address = static_cast<uint32_t>(addr);
    w.report.assign(kHalfKayHeader + kHalfKayBlock, 0);
    w.report[0] = static_cast<uint8_t>(addr);
    w.report[1] = static_cast<uint8_t>(addr >> 8);
    w.report[2] = static_cast<uint8_t>(addr >> 16);
    std::copy(image.bytes.begin() + static_cast<long>(addr), image.bytes.begin() + static_cast<long>(addr + kHalfKayBlock),
              w.report.begin() + kHalfKayHeader);
    out.push_back(std::move(w));
  }
  HalfKayWrite boot;
  boot.address = 0xFFFFFF;
  boot.report.assign(kHalfKayHeader + kHalfKayBlock, 0);
  boot.report[0] = boot.report[1] = boot.report[2] = 0xFF;
  out.push_back(std::move(boot));
  return out;
}

bool halfkay_flash(const std::vector<HalfKayWrite>& writes, const std::function<void(size_t, size_t)>& progress,
                   std::string& error, int wait_for_device_s) {
  libusb_context* ctx = nullptr;
  if (libusb_init(&ctx) != 0) return error = "cannot initialise libusb", false;
  libusb_device_handle* dev = nullptr;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(wait_for_device_s);
  while (!(dev = libusb_open_device_with_vid_pid(ctx, kHalfKayVendor, kHalfKayProduct)) &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(250));
  }
  if (!dev) {
    libusb_exit(ctx);
    return error = "no Teensy bootloader (16c0:0478) found: press the Teensy's button or run `ffctl reboot`; "
                   "if it is there, check permissions (udev/49-frictionfield.rules)",
           false;
  }
  libusb_set_auto_detach_kernel_driver(dev, 1);
  libusb_claim_interface(dev, 0);
  bool ok = true;
  for (size_t i = 0; i < writes.size() && ok; ++i) {
    // SET_REPORT (class, interface): the first write erases the chip, give it time.
    const unsigned timeout = i == 0 ? 45000u : 500u;
    int r = -1;
    for (int attempt = 0; attempt < 10 && r < 0; ++attempt) {
      r = libusb_control_transfer(dev, 0x21, 9, 0x0200, 0, const_cast<uint8_t*>(writes[i].report.data()),
                                  static_cast<uint16_t>(writes[i].report.size()), timeout);
      if (r < 0 && i + 1 == writes.size()) r = 0;  // the boot command may not be acknowledged
      if (r < 0) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    if (r < 0) {
      error = "write of block at 0x" + std::to_string(writes[i].address) + " failed: " + libusb_error_name(r);
      ok = false;
    }
    if (progress) progress(i + 1, writes.size());
  }
  libusb_release_interface(dev, 0);
  libusb_close(dev);
  libusb_exit(ctx);
  return ok;
}

}  // namespace ff::ffctl
