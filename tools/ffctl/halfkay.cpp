#include "halfkay.hpp"

#include <libusb.h>

#include <chrono>
#include <cstdio>
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
  out.push_back(halfkay_boot_command());
  return out;
}

HalfKayWrite halfkay_boot_command() {
  HalfKayWrite boot;
  boot.address = 0xFFFFFF;
  boot.report.assign(kHalfKayHeader + kHalfKayBlock, 0);
  boot.report[0] = boot.report[1] = boot.report[2] = 0xFF;
  return boot;
}

namespace {

// The bootloader if it is on the bus; `open_error` says why it could not be opened.
libusb_device_handle* open_halfkay(libusb_context* ctx, int& open_error) {
  libusb_device** list = nullptr;
  const ssize_t n = libusb_get_device_list(ctx, &list);
  libusb_device_handle* handle = nullptr;
  for (ssize_t i = 0; i < n && !handle; ++i) {
    libusb_device_descriptor d;
    if (libusb_get_device_descriptor(list[i], &d) != 0) continue;
    if (d.idVendor != kHalfKayVendor || d.idProduct != kHalfKayProduct) continue;
    open_error = libusb_open(list[i], &handle);  // sets handle only on success
  }
  if (list) libusb_free_device_list(list, 1);
  return handle;
}

// SET_REPORT (class, interface 0), retried every 10 ms until `budget` is spent,
// as teensy_loader_cli does.
int write_report(libusb_device_handle* dev, const std::vector<uint8_t>& report, std::chrono::milliseconds budget) {
  const auto deadline = std::chrono::steady_clock::now() + budget;
  int r = LIBUSB_ERROR_TIMEOUT;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) return r;
    r = libusb_control_transfer(dev, 0x21, 9, 0x0200, 0, const_cast<uint8_t*>(report.data()),
                                static_cast<uint16_t>(report.size()), static_cast<unsigned>(left.count()));
    if (r >= 0 || r == LIBUSB_ERROR_NO_DEVICE) return r;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

}  // namespace

bool halfkay_present() {
  libusb_context* ctx = nullptr;
  if (libusb_init(&ctx) != 0) return false;
  int open_error = 0;
  libusb_device_handle* dev = open_halfkay(ctx, open_error);
  const bool found = dev != nullptr || open_error != 0;
  if (dev) libusb_close(dev);
  libusb_exit(ctx);
  return found;
}

bool halfkay_flash(const std::vector<HalfKayWrite>& writes, const std::function<void(size_t, size_t)>& progress,
                   std::string& error, int wait_for_device_s) {
  libusb_context* ctx = nullptr;
  if (libusb_init(&ctx) != 0) return error = "cannot initialise libusb", false;
  libusb_device_handle* dev = nullptr;
  int open_error = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(wait_for_device_s);
  while (!(dev = open_halfkay(ctx, open_error)) && open_error != LIBUSB_ERROR_ACCESS &&
         (wait_for_device_s <= 0 || std::chrono::steady_clock::now() < deadline)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(250));
  }
  if (!dev) {
    libusb_exit(ctx);
    if (open_error == LIBUSB_ERROR_ACCESS) {
      return error = "found the Teensy bootloader (16c0:0478) but may not open it: install the udev rule "
                     "(sudo cp udev/49-frictionfield.rules /etc/udev/rules.d/ && sudo udevadm control "
                     "--reload-rules), then press the Teensy's button again",
             false;
    }
    return error = "no Teensy bootloader (16c0:0478) within " + std::to_string(wait_for_device_s) +
                   " s: run `ffctl reboot`, or press the button on the Teensy",
           false;
  }
  libusb_set_auto_detach_kernel_driver(dev, 1);
  // Unclaimed, every write would be refused for the whole of its 45 s budget.
  const int claimed = libusb_claim_interface(dev, 0);
  if (claimed != 0) {
    error = std::string("the Teensy bootloader is in use by another program (the Teensy Loader, a second ffctl?): "
                        "close it and flash again (") + libusb_error_name(claimed) + ")";
    libusb_close(dev);
    libusb_exit(ctx);
    return false;
  }
  bool ok = true;
  for (size_t i = 0; i < writes.size() && ok; ++i) {
    const bool boot = i + 1 == writes.size();
    // The first writes erase the flash: teensy_loader_cli allows the first five 45 s.
    const auto budget = std::chrono::milliseconds(i < 5 && !boot ? 45000 : 500);
    const int r = write_report(dev, writes[i].report, budget);
    if (r < 0 && !boot) {  // the boot command may go unanswered: the chip is already restarting
      char where[16];
      std::snprintf(where, sizeof where, "0x%06X", static_cast<unsigned>(writes[i].address));
      error = std::string("writing the block at ") + where + " failed: " + libusb_error_name(r) +
              (r == LIBUSB_ERROR_NO_DEVICE ? " (the Teensy left the bus: cable?)" : "");
      ok = false;
    }
    if (progress) progress(i + 1, writes.size());
  }
  libusb_release_interface(dev, 0);
  libusb_close(dev);
  libusb_exit(ctx);
  return ok;
}

bool halfkay_boot(std::string& error) {
  if (!halfkay_present()) {
    return error = "no Teensy bootloader (16c0:0478) on USB: `ffctl reset` starts the firmware from the bootloader "
                   "(a running device is already running it)",
           false;
  }
  return halfkay_flash({halfkay_boot_command()}, nullptr, error, 2);
}

}  // namespace ff::ffctl
