// hidapi (its Linux hidraw backend, 0.13) as ffctl calls it, over the emulated
// bus: the Teensy running the frictionfield firmware is firmware/src/main.cpp,
// unchanged, on the Teensyduino model (test/teensy_model) with the emulated
// zForce, AD9834, DAC and load cells, booted when ffctl opens it and paced to
// the wall clock (as ff-sim is). What hidraw does is kept where ffctl depends
// on it:
// - hid_enumerate lists one entry per HID interface of Teensyduino's USB_HID
//   type (usb_desc.h: keyboard 0, mouse 1, SEREMU 2 on usage page 0xFFC9,
//   joystick 3, media keys 4), product "Keyboard/Mouse/Joystick".
// - hid_open_path fails (NULL, errno EACCES) without the udev rule.
// - hid_write sends its bytes after the report id 0 as one interrupt OUT
//   transfer, in 32-byte packets (SEREMU_RX_SIZE); the device NAKs what it
//   has no buffer for, so a write never fails while the device is there.
// - The kernel reads every IN report while the device is open and keeps the
//   newest 64 (hidraw.c, HIDRAW_BUFFER_SIZE: a report that finds the buffer
//   full is dropped); hid_read_timeout returns one, 0 at the timeout, or -1
//   once the device has left the bus.
// - A feature report goes to usb_dev.c's SET_REPORT handler (the model's).
// - With unplug_after_ms in the bus file, the cable comes out that long after
//   the open: reads and writes fail from then on.
// - With sigint_after_ms, Ctrl-C comes that long after the open, during a
//   read: the signal's handler runs and hidraw's poll() returns -1 with EINTR
//   (poll is never restarted), so hid_read_timeout returns -1 with errno EINTR
//   (hidapi linux/hid.c), the device still there.
#include <hidapi.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstring>
#include <deque>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "frictionfield/core/sensor_sample.hpp"
#include "sim_devices.hpp"
#include "teensy_model.hpp"
#include "usb_bus.hpp"

using ff::ffctl::emulated_usb::UsbBus;

namespace {

constexpr unsigned short kVendor = 0x16C0, kProduct = 0x0482;
constexpr int kSeremuInterface = 2;
constexpr size_t kHidrawBufferReports = 64;  // hidraw.c HIDRAW_BUFFER_SIZE
constexpr size_t kSeremuRxSize = 32;         // usb_desc.h SEREMU_RX_SIZE

struct Interface {
  int number;
  unsigned short usage_page, usage;
};
constexpr Interface kInterfaces[] = {
    {0, 0x01, 0x06}, {1, 0x01, 0x02}, {2, 0xFFC9, 0x04}, {3, 0x01, 0x04}, {4, 0x0C, 0x01}};

std::string path_of(int interface) { return "/dev/hidraw" + std::to_string(3 + interface); }

wchar_t* wide(const std::string& s) {
  wchar_t* w = new wchar_t[s.size() + 1];
  for (size_t i = 0; i < s.size(); ++i) w[i] = static_cast<wchar_t>(s[i]);
  w[s.size()] = 0;
  return w;
}

// The finger: strokes along the middle path, 0.6 s down and 0.2 s lifted, pressing 0.3 N.
bool finger_down(uint64_t t_us) { return t_us % 800000 < 600000; }
ff::SensorSample finger_at(uint64_t t_us) {
  const float phase = static_cast<float>(t_us % 800000);
  return {static_cast<uint32_t>(t_us), 100.0f + 600.0f * phase / 600000.0f,
          240.0f + 40.0f * std::sin(static_cast<float>(t_us) * 1e-6f), finger_down(t_us)};
}

// The Teensy on the bus, in this process: booted at the first open.
class EmulatedTeensy {
 public:
  bool running() const { return running_; }

  void boot() {
    teensy_model::Options options;
    options.keep_dac_history = false;
    teensy_model::reset(options);
    devices_ = std::make_unique<teensy_model::SimDevices>();
    devices_->wire(network_);
    std::vector<ff::SensorSample> trace;
    for (uint64_t t = 0; t <= 600000000; t += 5000) trace.push_back(finger_at(t));
    devices_->zforce.load_trace(trace);
    teensy_model::set_time_hook([this](uint64_t now) { devices_->set_force_mN(finger_down(now) ? 300.0f : 0.0f); });
    // Start-up and setup() as fast as the host runs them, then the wall clock.
    teensy_model::boot();
    teensy_model::run_until(teensy_model::now_us() + 200000);
    t0_ = teensy_model::now_us();
    wall0_ = std::chrono::steady_clock::now();
    teensy_model::set_pacer([this](uint64_t now) {
      if (now < t0_ || now - t0_ < 1000) return;
      std::this_thread::sleep_until(wall0_ + std::chrono::microseconds(now - t0_));
    });
    running_ = true;
  }

  // Runs the device up to the wall clock, or `extra_us` beyond it (paced: that waits).
  void run(uint64_t extra_us = 0) {
    const auto wall = std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now() - wall0_);
    teensy_model::run_until(t0_ + static_cast<uint64_t>(wall.count()) + extra_us);
    for (std::vector<uint8_t>& report : teensy_model::host_take_seremu_in()) {
      if (hidraw_.size() < kHidrawBufferReports) hidraw_.push_back(std::move(report));
    }
  }
  // The cable comes out this long after the device was opened (0: never).
  void unplug_after(long ms) {
    if (ms > 0) unplug_at_ = std::chrono::steady_clock::now() + std::chrono::milliseconds(ms);
  }
  bool unplugged() const {
    return unplug_at_ != std::chrono::steady_clock::time_point{} && std::chrono::steady_clock::now() >= unplug_at_;
  }
  bool gone() const { return teensy_model::rebooted() || unplugged(); }
  void interrupt_after(long ms) {
    if (ms > 0) interrupt_at_ = std::chrono::steady_clock::now() + std::chrono::milliseconds(ms);
  }
  // True once, when Ctrl-C is due: it is raised here, as if during poll().
  bool interrupted_now() {
    if (interrupt_at_ == std::chrono::steady_clock::time_point{} || std::chrono::steady_clock::now() < interrupt_at_) {
      return false;
    }
    interrupt_at_ = {};
    std::raise(SIGINT);
    return true;
  }
  std::deque<std::vector<uint8_t>>& hidraw() { return hidraw_; }

 private:
  bool running_ = false;
  teensy_model::ScriptedNetwork network_;
  std::unique_ptr<teensy_model::SimDevices> devices_;
  std::deque<std::vector<uint8_t>> hidraw_;
  uint64_t t0_ = 0;
  std::chrono::steady_clock::time_point wall0_, unplug_at_{}, interrupt_at_{};
};

EmulatedTeensy& teensy() {
  static EmulatedTeensy t;
  return t;
}

bool is_reboot_magic(const unsigned char* data, size_t length) {
  return length == 5 && data[0] == 0 && data[1] == 0xA9 && data[2] == 0x45 && data[3] == 0xC2 && data[4] == 0x6B;
}

}  // namespace

struct hid_device_ {
  int interface = 0;
  bool silent = false;  // another USB_HID sketch: it never reads the channel
  bool chatty = false;  // ... and prints a line of text every 10 ms (Serial.println on SEREMU)
  std::chrono::steady_clock::time_point next_line{};
  std::chrono::steady_clock::time_point feature_reboot_at{};  // silent: when the feature report restarts it
  bool feature_reboot = false;
};

extern "C" {

int HID_API_EXPORT hid_init(void) { return 0; }
int HID_API_EXPORT hid_exit(void) { return 0; }

struct hid_device_info HID_API_EXPORT* HID_API_CALL hid_enumerate(unsigned short vendor_id, unsigned short product_id) {
  const UsbBus bus = UsbBus::load();
  const std::string device = bus.device_now();
  if (device != "firmware" && device != "silent" && device != "chatty") return nullptr;
  if ((vendor_id && vendor_id != kVendor) || (product_id && product_id != kProduct)) return nullptr;
  hid_device_info* head = nullptr;
  for (int i = 4; i >= 0; --i) {
    auto* d = new hid_device_info{};
    const std::string path = path_of(kInterfaces[i].number);
    d->path = new char[path.size() + 1];
    std::memcpy(d->path, path.c_str(), path.size() + 1);
    d->vendor_id = kVendor;
    d->product_id = kProduct;
    d->serial_number = wide(bus.get("serial", "4810620"));
    d->release_number = 0x0280;
    d->manufacturer_string = wide("Teensyduino");
    d->product_string = wide("Keyboard/Mouse/Joystick");
    d->usage_page = kInterfaces[i].usage_page;
    d->usage = kInterfaces[i].usage;
    d->interface_number = kInterfaces[i].number;
    d->bus_type = HID_API_BUS_USB;
    d->next = head;
    head = d;
  }
  return head;
}

void HID_API_EXPORT HID_API_CALL hid_free_enumeration(struct hid_device_info* devs) {
  while (devs) {
    hid_device_info* next = devs->next;
    delete[] devs->path;
    delete[] devs->serial_number;
    delete[] devs->manufacturer_string;
    delete[] devs->product_string;
    delete devs;
    devs = next;
  }
}

HID_API_EXPORT hid_device* HID_API_CALL hid_open_path(const char* path) {
  const UsbBus bus = UsbBus::load();
  const std::string device = bus.device_now();
  int interface = -1;
  for (const Interface& i : kInterfaces) {
    if (path_of(i.number) == path) interface = i.number;
  }
  if ((device != "firmware" && device != "silent" && device != "chatty") || interface < 0) {
    errno = ENOENT;
    return nullptr;
  }
  if (bus.get("access", "ok") == "denied") {
    bus.event(std::string("open ") + path + ": permission denied");
    errno = EACCES;
    return nullptr;
  }
  bus.event(std::string("open ") + path);
  auto* d = new hid_device_;
  d->interface = interface;
  d->silent = device == "silent" || device == "chatty";
  d->chatty = device == "chatty";
  d->next_line = std::chrono::steady_clock::now();
  if (!d->silent && interface == kSeremuInterface && !teensy().running()) {
    teensy().boot();
    teensy().unplug_after(bus.get_long("unplug_after_ms", 0));
    teensy().interrupt_after(bus.get_long("sigint_after_ms", 0));
  }
  return d;
}

int HID_API_EXPORT HID_API_CALL hid_write(hid_device* dev, const unsigned char* data, size_t length) {
  if (length < 1 || data[0] != 0 || dev->interface != kSeremuInterface) {
    errno = EINVAL;  // report id 0 is the only one; the other interfaces take no output here
    return -1;
  }
  if (dev->silent) return dev->feature_reboot ? -1 : static_cast<int>(length);
  teensy().run();
  if (teensy().gone()) {
    errno = ENODEV;
    return -1;
  }
  for (size_t at = 1; at < length; at += kSeremuRxSize) {
    teensy_model::host_write_out_packet(data + at, std::min(kSeremuRxSize, length - at));
  }
  return static_cast<int>(length);
}

int HID_API_EXPORT HID_API_CALL hid_read_timeout(hid_device* dev, unsigned char* data, size_t length,
                                                 int milliseconds) {
  // A negative timeout blocks until a report comes (hid_read), as hidraw's backend does.
  const bool blocking = milliseconds < 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(blocking ? 0 : milliseconds);
  if (dev->silent || dev->interface != kSeremuInterface) {  // nothing for the protocol ever comes
    const bool text = dev->chatty && dev->interface == kSeremuInterface;
    if (dev->feature_reboot && (blocking || dev->feature_reboot_at <= deadline) &&
        (!text || dev->feature_reboot_at <= dev->next_line)) {
      std::this_thread::sleep_until(dev->feature_reboot_at);
      return -1;
    }
    if (text && (blocking || dev->next_line <= deadline)) {
      std::this_thread::sleep_until(dev->next_line);
      dev->next_line += std::chrono::milliseconds(10);
      static const char kLine[] = "another sketch, printing\r\n";  // usb_seremu.c pads a flushed packet with 0
      const size_t n = std::min(length, size_t{64});
      std::memset(data, 0, n);
      std::memcpy(data, kLine, std::min(n, sizeof kLine - 1));
      return static_cast<int>(n);
    }
    while (blocking) std::this_thread::sleep_for(std::chrono::seconds(1));
    std::this_thread::sleep_until(deadline);
    return 0;
  }
  for (;;) {
    teensy().run();
    auto& reports = teensy().hidraw();
    if (!reports.empty()) {
      const size_t n = std::min(length, reports.front().size());
      std::memcpy(data, reports.front().data(), n);
      reports.pop_front();
      return static_cast<int>(n);
    }
    if (teensy().gone()) return -1;
    if (teensy().interrupted_now()) {
      errno = EINTR;
      return -1;
    }
    if (!blocking && std::chrono::steady_clock::now() >= deadline) return 0;
    teensy().run(1000);
  }
}

int HID_API_EXPORT HID_API_CALL hid_send_feature_report(hid_device* dev, const unsigned char* data, size_t length) {
  if (length < 1 || data[0] != 0 || dev->interface != kSeremuInterface) {
    errno = EINVAL;
    return -1;
  }
  UsbBus::load().event(is_reboot_magic(data, length) ? "feature report: reboot" : "feature report");
  if (dev->silent) {
    if (is_reboot_magic(data, length)) {
      dev->feature_reboot = true;
      dev->feature_reboot_at = std::chrono::steady_clock::now() + std::chrono::milliseconds(5);
    }
    return static_cast<int>(length);
  }
  teensy().run();
  if (teensy().gone()) {
    errno = ENODEV;
    return -1;
  }
  teensy_model::host_set_seremu_feature_report(data + 1, length - 1);
  return static_cast<int>(length);
}

void HID_API_EXPORT HID_API_CALL hid_close(hid_device* dev) {
  bool restarted = false;
  if (dev->silent) {
    if (dev->feature_reboot) std::this_thread::sleep_until(dev->feature_reboot_at);
    restarted = dev->feature_reboot;
  } else if (dev->interface == kSeremuInterface && teensy().running()) {
    // The board runs on after the host lets go; a restart it was asked for comes within
    // 20 ms of its Ack (kRebootDelayUs) or 5 ms of the feature report.
    for (int ms = 0; ms < 50 && !teensy().gone(); ++ms) teensy().run(1000);
    restarted = teensy().gone();
  }
  if (dev->interface == kSeremuInterface && teensy().unplugged()) {
    UsbBus bus = UsbBus::load();
    bus.plug("absent", 0);
    bus.save();
    bus.event("unplugged");
  } else if (restarted) {
    UsbBus bus = UsbBus::load();
    if (bus.get("device") != "bootloader") {
      bus.plug("bootloader", bus.get_long("restart_ms", 300));
      bus.save();
      bus.event("restarted into the bootloader");
    }
  }
  delete dev;
}

}  // extern "C"
