#pragma once
// What only the Teensy has, behind one small interface so that the firmware's
// main loop and tick run natively against emulated devices in tests.
// Everything here is called from the main loop except cycles(), which the
// tick also calls. Nothing may block for long: the loop feeds the tracker.
#include <cstddef>
#include <cstdint>

namespace ff::firmware {

struct UdpEndpoint {
  uint32_t ip = 0;  // as the bytes stand on the wire, first octet lowest
  uint16_t port = 0;
};

class Board {
 public:
  // USB absolute mouse (Mouse.moveTo on a screenSize(800, 480) mouse).
  // False: not sent, because it would have waited for a host that does not poll.
  virtual bool mouse_move_to(int x, int y) = 0;
  // One UDP datagram from the experiment host, if one is waiting, and who sent it.
  virtual bool udp_receive(uint8_t* buffer, size_t capacity, size_t& size, UdpEndpoint& from) = 0;
  // False: the send timed out (no ARP answer), after a bounded wait (host_link_limits.hpp).
  virtual bool udp_send(const UdpEndpoint& to, const uint8_t* data, size_t size) = 0;
  // False: no network chip answered at start-up; UDP is off until reset.
  virtual bool udp_available() const { return true; }
  // One 64-byte report of the USB HID host channel, if one is waiting.
  virtual bool hid_receive(uint8_t* report64) = 0;
  virtual void hid_send(const uint8_t* report64) = 0;
  // Reports hid_send() can queue now without waiting for the host to read.
  // The app sends a frame only when all its reports fit, so that a host that
  // stopped reading costs dropped frames, never a blocked loop.
  virtual size_t hid_tx_room() { return SIZE_MAX; }
  // Free-running cycle counter (DWT->CYCCNT at 180 MHz).
  virtual uint32_t cycles() = 0;
  virtual void reboot_to_bootloader() = 0;
  // The MCU's hardware watchdog, kicked once per main-loop pass while the
  // tick is alive too: the last resort (a reset) if either hangs for good.
  // The software watchdogs rest the plate long before that.
  virtual void watchdog_kick() {}  // default: a board without one

 protected:
  ~Board() = default;
};

}  // namespace ff::firmware
