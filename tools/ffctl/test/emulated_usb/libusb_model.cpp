// libusb as ffctl calls it to flash, over the emulated bus: a root hub, the
// Teensy running its firmware (16c0:0482) or its bootloader (HalfKay,
// 16c0:0478). HalfKay for the MK66FX1M0, as teensy_loader_cli talks to it:
// - each block is one HID SET_REPORT on interface 0 (bmRequestType 0x21,
//   bRequest 9, wValue 0x0200, wIndex 0) of 1088 bytes: a 64-byte header
//   whose bytes 0..2 are the address (a multiple of 1024 below 1 MiB), then
//   1024 bytes of data; anything else stalls (LIBUSB_ERROR_PIPE);
// - the first block erases the whole flash first: it is answered only after
//   `erase_ms`, and a host that stops waiting sooner sees
//   LIBUSB_ERROR_TIMEOUT while the erase runs on (that block is not written);
// - the address 0xFFFFFF boots what the flash holds: the bootloader leaves
//   the bus and the firmware comes (as `firmware` after restart_ms);
// - Linux's usbhid holds its interface 0: claiming it, or a transfer without
//   the claim, is LIBUSB_ERROR_BUSY unless the kernel driver is detached
//   (libusb_set_auto_detach_kernel_driver); a context not from libusb_init is
//   refused; each enumeration is an `enumerate` event;
// - opening it without the udev rule is LIBUSB_ERROR_ACCESS; once the cable
//   is out every transfer is LIBUSB_ERROR_NO_DEVICE; one that stops
//   answering (hang_after_writes) lets every transfer time out, one that
//   refuses (stall_after_writes) stalls each at once.
#include <libusb.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "usb_bus.hpp"

using ff::ffctl::emulated_usb::kMk66FlashBytes;
using ff::ffctl::emulated_usb::UsbBus;

struct libusb_context {
  int unused = 0;
};
struct libusb_device {
  uint16_t vendor = 0, product = 0;
};
struct libusb_device_handle {
  bool auto_detach = false;  // libusb_set_auto_detach_kernel_driver
  bool claimed = false;
};

namespace {

constexpr size_t kBlock = 1024, kHeader = 64;

// Contexts libusb_init made and libusb_exit has not ended: any other (a null one without
// libusb_init(NULL) included) is API misuse, which libusb answers with an error at best.
// Kept inverted, so that a context never ended is still a leak to LeakSanitizer.
std::set<uintptr_t>& live_contexts() {
  static std::set<uintptr_t> live;
  return live;
}
uintptr_t key(const libusb_context* ctx) { return ~reinterpret_cast<uintptr_t>(ctx); }

void erase(const UsbBus& bus) {
  std::ofstream(bus.flash_path(), std::ios::binary | std::ios::trunc) << std::string(kMk66FlashBytes, '\xFF');
  bus.event("erase");
}

void write_block(const UsbBus& bus, size_t address, const unsigned char* data) {
  std::fstream f(bus.flash_path(), std::ios::binary | std::ios::in | std::ios::out);
  f.seekp(static_cast<std::streamoff>(address));
  f.write(reinterpret_cast<const char*>(data), kBlock);
  char line[32];
  std::snprintf(line, sizeof line, "write 0x%06zX", address);
  bus.event(line);
}

}  // namespace

extern "C" {

int LIBUSB_CALL libusb_init(libusb_context** ctx) {
  *ctx = new libusb_context;
  live_contexts().insert(key(*ctx));
  return LIBUSB_SUCCESS;
}
void LIBUSB_CALL libusb_exit(libusb_context* ctx) {
  live_contexts().erase(key(ctx));
  delete ctx;
}

const char* LIBUSB_CALL libusb_error_name(int code) {
  switch (code) {
    case LIBUSB_SUCCESS: return "LIBUSB_SUCCESS";
    case LIBUSB_ERROR_ACCESS: return "LIBUSB_ERROR_ACCESS";
    case LIBUSB_ERROR_NO_DEVICE: return "LIBUSB_ERROR_NO_DEVICE";
    case LIBUSB_ERROR_NOT_FOUND: return "LIBUSB_ERROR_NOT_FOUND";
    case LIBUSB_ERROR_TIMEOUT: return "LIBUSB_ERROR_TIMEOUT";
    case LIBUSB_ERROR_PIPE: return "LIBUSB_ERROR_PIPE";
    case LIBUSB_ERROR_BUSY: return "LIBUSB_ERROR_BUSY";
    case LIBUSB_ERROR_INVALID_PARAM: return "LIBUSB_ERROR_INVALID_PARAM";
    default: return "**UNKNOWN**";
  }
}

ssize_t LIBUSB_CALL libusb_get_device_list(libusb_context* ctx, libusb_device*** list) {
  const UsbBus bus = UsbBus::load();
  if (!live_contexts().count(key(ctx))) {
    bus.event("libusb: no context");
    return LIBUSB_ERROR_INVALID_PARAM;
  }
  bus.event("enumerate");
  const std::string device = bus.device_now();
  std::vector<libusb_device*> devices = {new libusb_device{0x1D6B, 0x0002}};  // the root hub
  if (device == "firmware" || device == "silent") devices.push_back(new libusb_device{0x16C0, 0x0482});
  if (device == "bootloader") devices.push_back(new libusb_device{0x16C0, 0x0478});
  *list = new libusb_device*[devices.size() + 1];
  for (size_t i = 0; i < devices.size(); ++i) (*list)[i] = devices[i];
  (*list)[devices.size()] = nullptr;
  return static_cast<ssize_t>(devices.size());
}

void LIBUSB_CALL libusb_free_device_list(libusb_device** list, int) {
  for (libusb_device** d = list; d && *d; ++d) delete *d;
  delete[] list;
}

int LIBUSB_CALL libusb_get_device_descriptor(libusb_device* dev, struct libusb_device_descriptor* desc) {
  *desc = libusb_device_descriptor{};
  desc->bLength = LIBUSB_DT_DEVICE_SIZE;
  desc->bDescriptorType = LIBUSB_DT_DEVICE;
  desc->bcdUSB = 0x0200;
  desc->idVendor = dev->vendor;
  desc->idProduct = dev->product;
  desc->bNumConfigurations = 1;
  return LIBUSB_SUCCESS;
}

int LIBUSB_CALL libusb_open(libusb_device* dev, libusb_device_handle** handle) {
  const UsbBus bus = UsbBus::load();
  if (dev->product != 0x0478) return LIBUSB_ERROR_ACCESS;  // ffctl opens only the bootloader
  if (bus.device_now() != "bootloader") return LIBUSB_ERROR_NO_DEVICE;
  if (bus.get("access", "ok") == "denied") {
    bus.event("open bootloader: permission denied");
    return LIBUSB_ERROR_ACCESS;
  }
  bus.event("open bootloader");
  *handle = new libusb_device_handle;
  return LIBUSB_SUCCESS;
}
void LIBUSB_CALL libusb_close(libusb_device_handle* handle) { delete handle; }

int LIBUSB_CALL libusb_set_auto_detach_kernel_driver(libusb_device_handle* handle, int enable) {
  handle->auto_detach = enable != 0;
  return LIBUSB_SUCCESS;
}
// Linux binds usbhid to HalfKay's interface 0: only a handle that detaches it may claim it.
// Another program that claimed it (the Teensy Loader, a second ffctl) keeps it from everyone else.
int LIBUSB_CALL libusb_claim_interface(libusb_device_handle* handle, int interface_number) {
  if (interface_number != 0) return LIBUSB_ERROR_NOT_FOUND;
  if (!handle->auto_detach || UsbBus::load().get("claimed_by_another", "no") == "yes") return LIBUSB_ERROR_BUSY;
  handle->claimed = true;
  return LIBUSB_SUCCESS;
}
int LIBUSB_CALL libusb_release_interface(libusb_device_handle* handle, int) {
  handle->claimed = false;
  return LIBUSB_SUCCESS;
}

int LIBUSB_CALL libusb_control_transfer(libusb_device_handle* handle, uint8_t request_type, uint8_t request,
                                        uint16_t value, uint16_t index, unsigned char* data, uint16_t length,
                                        unsigned int timeout) {
  UsbBus bus = UsbBus::load();
  if (bus.device_now() != "bootloader") return LIBUSB_ERROR_NO_DEVICE;
  // usbfs claims the interface of a class request itself, which fails while usbhid holds it.
  if (!handle->claimed && (!handle->auto_detach || bus.get("claimed_by_another", "no") == "yes"))
    return LIBUSB_ERROR_BUSY;
  const long writes = bus.get_long("writes", 0), unplug_after = bus.get_long("unplug_after_writes", 0);
  if (unplug_after > 0 && writes >= unplug_after) {
    bus.plug("absent", 0);
    bus.save();
    bus.event("unplugged");
    return LIBUSB_ERROR_NO_DEVICE;
  }
  const long hang_after = bus.get_long("hang_after_writes", 0);
  if (hang_after > 0 && writes >= hang_after) {  // it stops answering: every transfer times out
    std::this_thread::sleep_for(std::chrono::milliseconds(timeout));
    return LIBUSB_ERROR_TIMEOUT;
  }
  const long stall_after = bus.get_long("stall_after_writes", 0);
  if (stall_after > 0 && writes >= stall_after) {  // it refuses every block at once
    bus.event("stall");
    return LIBUSB_ERROR_PIPE;
  }
  const size_t address = data ? data[0] | (data[1] << 8) | (data[2] << 16) : 0;
  if (request_type != 0x21 || request != 9 || value != 0x0200 || index != 0 || length != kHeader + kBlock ||
      (address != 0xFFFFFF && (address % kBlock != 0 || address >= kMk66FlashBytes))) {
    bus.event("stall");
    return LIBUSB_ERROR_PIPE;
  }
  if (address == 0xFFFFFF) {
    bus.event("boot");
    bus.plug("firmware", bus.get_long("restart_ms", 300));
    bus.save();
    return length;
  }
  // The erase: started by the first block, answered when done.
  const long now = UsbBus::wall_ms();
  if (bus.get_long("erased", 0) == 0) {
    erase(bus);
    bus.set("erased", 1L);
    bus.set("erase_done_ms", now + bus.get_long("erase_ms", 150));
    bus.save();
  }
  const long done = bus.get_long("erase_done_ms", 0);
  if (now < done) {
    if (timeout != 0 && now + static_cast<long>(timeout) < done) {  // 0: no timeout
      std::this_thread::sleep_for(std::chrono::milliseconds(timeout));
      return LIBUSB_ERROR_TIMEOUT;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(done - now));
  }
  write_block(bus, address, data + kHeader);
  bus.set("writes", writes + 1);
  bus.save();
  return length;
}

}  // extern "C"
