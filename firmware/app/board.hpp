#pragma once
// What only the Teensy has, behind one small interface so that the firmware's
// main loop and tick run natively against emulated devices in tests.
#include <cstddef>
#include <cstdint>

namespace ff::firmware {

class Board {
 public:
  // USB absolute mouse (Mouse.moveTo on a screenSize(800, 480) mouse).
  virtual void mouse_move_to(int x, int y) = 0;
  // One UDP datagram from the experiment host, if one is waiting.
  virtual bool udp_receive(uint8_t* buffer, size_t capacity, size_t& size) = 0;
  virtual void udp_send(const uint8_t* data, size_t size) = 0;
  // One 64-byte report of the USB HID host channel, if one is waiting.
  virtual bool hid_receive(uint8_t* report64) = 0;
  virtual void hid_send(const uint8_t* report64) = 0;
  // Free-running cycle counter (DWT->CYCCNT at 180 MHz).
  virtual uint32_t cycles() = 0;
  virtual void reboot_to_bootloader() = 0;

 protected:
  ~Board() = default;
};

}  // namespace ff::firmware
