#pragma once
// The Teensy bootloader (HalfKay) protocol for the MK66FX1M0, as
// teensy_loader_cli writes it: 1024-byte blocks, each sent as one HID report
// of a 64-byte header (block address in bytes 0..2, little-endian) followed by
// the 1024 data bytes; blank (all 0xFF) blocks are skipped except the first
// (its write erases the chip); then a boot command: header 0xFF 0xFF 0xFF.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "intel_hex.hpp"

namespace ff::ffctl {

constexpr uint16_t kHalfKayVendor = 0x16C0;
constexpr uint16_t kHalfKayProduct = 0x0478;
constexpr size_t kHalfKayBlock = 1024;
constexpr size_t kHalfKayHeader = 64;

struct HalfKayWrite {
  uint32_t address = 0;
  std::vector<uint8_t> report;  // header + data (kHalfKayHeader + kHalfKayBlock), or the boot command
};

// Every report to send, in order; the last one boots the new firmware.
std::vector<HalfKayWrite> halfkay_writes(const FlashImage& image);

// Whether the bootloader is on the bus (openable or not).
bool halfkay_present();

// Waits up to `wait_for_device_s` for the bootloader, then sends the writes
// over libusb with teensy_loader_cli's timing (45 s for each of the first five
// blocks: they erase; 0.5 s after); progress(done, total). false with a
// readable `error` (no bootloader, permissions, a failed block).
// wait_for_device_s <= 0: wait until the bootloader comes (Ctrl-C ends the program).
bool halfkay_flash(const std::vector<HalfKayWrite>& writes, const std::function<void(size_t, size_t)>& progress,
                   std::string& error, int wait_for_device_s = 10);

// HalfKay's boot command alone: run the firmware already in flash (teensy_loader_cli -b).
HalfKayWrite halfkay_boot_command();
bool halfkay_boot(std::string& error);

}  // namespace ff::ffctl
