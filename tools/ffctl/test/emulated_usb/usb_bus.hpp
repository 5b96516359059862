#pragma once
// The USB bus that ffctl_emulated_usb sees: which Teensy is plugged in (its
// firmware, or the HalfKay bootloader, or nothing) and what its flash holds,
// kept in a folder (the FF_EMULATED_USB environment variable) so that it
// outlives one ffctl run, as a board on the desk does. A test writes the
// folder's `bus` file to set the scene; the models of hidapi and libusb read
// and update it, write the bootloader's flash to `flash.bin` and append what
// the device did to `events`, one line each.
//
// `bus` holds key=value lines:
//   device=firmware|silent|chatty|bootloader|absent  silent: a USB_HID sketch that never reads the
//                                            channel; chatty: one that prints a text line every 10 ms
//   serial=4810620                           the USB serial number
//   access=ok|denied                         denied: the udev rule is missing (open fails, EACCES)
//   restart_ms=300                           from a restart until the next device (HalfKay, firmware) is there
//   erase_ms=150                             HalfKay's chip erase, answered only when done
//   unplug_after_writes=0                    the cable comes out after this many blocks (0: never)
//   hang_after_writes=0                      HalfKay stops answering after this many blocks (0: never)
//   stall_after_writes=0                     HalfKay stalls every request after this many blocks (0: never)
//   unplug_after_ms=0                        the cable comes out this long after ffctl opens the firmware
//   sigint_after_ms=0                        Ctrl-C this long after ffctl opens the firmware, during a read
//   appears_at_ms, erased, writes            kept by the models
#include <cstdint>
#include <map>
#include <string>

namespace ff::ffctl::emulated_usb {

constexpr size_t kMk66FlashBytes = 1024 * 1024;

class UsbBus {
 public:
  // The folder from FF_EMULATED_USB; a missing variable or file is an empty bus.
  static UsbBus load();
  static UsbBus load_from(const std::string& folder);  // the tests' side
  void save() const;  // whole, by rename

  std::string get(const std::string& key, const std::string& fallback = "") const;
  long get_long(const std::string& key, long fallback) const;
  void set(const std::string& key, const std::string& value) { values_[key] = value; }
  void set(const std::string& key, long value) { values_[key] = std::to_string(value); }

  // The device on the bus now: "absent" until its appears_at_ms has come.
  std::string device_now() const;
  // Replaces the device, on the bus after `delay_ms`.
  void plug(const std::string& device, long delay_ms);

  void event(const std::string& line) const;  // appended to `events`
  std::string flash_path() const { return folder_ + "/flash.bin"; }
  const std::string& folder() const { return folder_; }

  static long wall_ms();

 private:
  std::string folder_;
  std::map<std::string, std::string> values_;
};

}  // namespace ff::ffctl::emulated_usb
