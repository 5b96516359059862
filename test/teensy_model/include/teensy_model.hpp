#pragma once
// The controls of the Teensyduino model: simulated time, the interrupts, the
// USB host, the network and the devices on the pins. firmware/src/main.cpp
// is compiled unchanged against the model's Arduino.h & co.; a test or
// ff-sim drives it from here. One thread: the IntervalTimer and pin
// interrupts run to completion inside the model call during which their time
// comes (as on the one-core MK66, where they preempt the loop at any
// instruction; here at any Teensyduino call, including the micros() the
// pipeline calls while it prepares a scene).
//
// Each behaviour follows the core's source (PaulStoffregen/cores teensy3/,
// Wire, SPI, Ethernet):
// - start-up (pins_teensy.c _init_Teensyduino_internal_): analog_init (VREF
//   on), startup_middle_hook(), 20 ms, usb_init, 280 ms, then setup(); DAC0
//   is off until something enables it; main.cpp: loop() then yield() forever.
// - USB (usb_mem.c, usb_dev.c): 24 packet buffers shared by every endpoint;
//   the SEREMU OUT endpoint holds two for the hardware and NAKs the host
//   while usb_malloc() has none to replace them (usb_rx_memory_needed);
//   usb_free() gives a buffer back to a starving receive endpoint first.
// - SEREMU (usb_seremu.c): OUT reports of 32 bytes; available()/getchar()
//   count and read a packet only up to its first 0x00, and drop the rest;
//   write() queues 64-byte IN packets, at most 6 (TX_PACKET_LIMIT), waiting
//   up to 30 ms (TX_TIMEOUT) for room, then failing at once until the host reads.
//   A 4-byte feature report (usb_dev.c) of A9 45 C2 6B restarts into the
//   bootloader 5 ms (five start-of-frame interrupts) later, whatever the loop does.
// - Mouse (usb_mouse.c): at most 3 queued reports, the same 30 ms wait.
// - The host polls each IN endpoint every 1 ms (bInterval 1) and may send one
//   OUT packet every 2 ms (SEREMU_RX_INTERVAL 2).
// - yield() (yield.cpp): Serial.available() while YIELD_CHECK_USB_SERIAL is set.
// - Ethernet (w5100.cpp init: delay(560); socket.cpp socketSendUDP: waits
//   for SEND_OK or TIMEOUT, calling yield()): an unanswered ARP costs
//   RTR x (RCR + 1), defaults 200 ms x 9. Without a chip (w5200_present
//   false) Ethernet.begin() returns after w5100.cpp's delay and
//   EthernetUDP::begin() returns 0 (socket.cpp socketBegin: no socket); any
//   later call on that socket would index the library's socket state past its
//   end (socketRecvAvailable), so the model counts them instead.
//   parsePacket() discards what the last datagram left unread in one SPI
//   transaction (read(NULL, remaining)); read() of one byte is one SPI
//   transaction (~5 us at 30 MHz with its address phase).
// - Wire at 416 kHz (WireKinetis.cpp, F_BUS 60 MHz): 9 bit times a byte.
// - analogRead on a pin the firmware drives as an output reads that level.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "frictionfield/bus/spi.hpp"
#include "frictionfield/emulated/i2c_bus.hpp"

namespace teensy_model {

// The network beyond the W5200: a test's script or ff-sim's real socket.
class UdpNetwork {
 public:
  virtual ~UdpNetwork() = default;
  // A datagram for the device, if one is waiting (payload, sender ip as in IPAddress, port).
  virtual bool receive(std::vector<uint8_t>& payload, uint32_t& ip, uint16_t& port) = 0;
  // False: nobody answers ARP for that address.
  virtual bool deliver(uint32_t ip, uint16_t port, const std::vector<uint8_t>& payload) = 0;
};

struct DacState {
  uint64_t t_us;
  bool enabled;      // DAC0_C0.DACEN
  bool internal_ref; // DACRFS clear: 1.2 V
  uint16_t code;
};

struct Options {
  uint32_t loop_pass_us = 20;        // simulated cost of one loop() pass beyond its calls
  uint32_t usb_host_attach_ms = 150; // when the host configures the device (usb_configuration)
  bool host_polls = true;            // the USB host reads IN endpoints every 1 ms
  bool keep_dac_history = true;      // false (ff-sim): only the latest state, memory bounded
  bool w5200_present = true;         // false: no WIZ820io answers on the SPI bus
};

// ---- set-up ----
void reset(const Options& options = Options());
void attach_i2c(uint8_t address, ff::emulated::I2cTarget& target);
void attach_spi(uint8_t chip_select_pin, ff::SpiBus16& device);
void set_data_ready_source(std::function<bool(uint64_t now_us)> level);  // DR pin level at a time
void set_analog_source(std::function<uint16_t(uint8_t pin, uint64_t now_us)> counts);  // 13-bit counts
void set_network(UdpNetwork* network);
void set_pacer(std::function<void(uint64_t now_us)> pacer);  // ff-sim: hold simulated time to the wall clock
void set_time_hook(std::function<void(uint64_t now_us)> hook);  // called as time moves (device models)

// ---- running ----
void boot();                          // start-up up to and including setup()
void run_until(uint64_t t_us);        // loop() passes (with yield()) until simulated time reaches t_us
uint64_t now_us();
bool rebooted();                      // _reboot_Teensyduino_() was called (the run stops there)

// ---- USB host ----
void host_write_out_packet(const uint8_t* data, size_t len);  // queued; sent one per 2 ms while not NAKed
size_t host_out_backlog();
// A SET_REPORT feature report of `len` bytes (report id 0 not counted) on the SEREMU interface.
void host_set_seremu_feature_report(const uint8_t* data, size_t len);
bool usb_seremu_online();  // a feature report other than the reboot magic arrived
std::vector<std::vector<uint8_t>> host_take_seremu_in();      // 64-byte IN packets read so far
struct MouseReport { uint64_t t_us; uint16_t x, y; };
std::vector<MouseReport> host_take_mouse();
void set_host_polls(bool polls);
size_t usb_buffers_free();

// ---- observations ----
const std::vector<DacState>& dac_history();  // every change, from reset (only the latest without keep_dac_history)
DacState dac_now();
uint32_t interrupt_count();
uint64_t longest_loop_pass_us();          // the longest loop() call, interrupts included
uint32_t ethernet_chip_select();
uint16_t retransmission_timeout_ms();
uint8_t retransmission_count();
uint32_t udp_calls_without_socket();    // EthernetUDP calls after begin() found no socket
uint8_t timer_priority();
uint32_t serial_available_calls();       // from anywhere: yield() or the binding
std::vector<uint8_t> output_pins();       // pins set to OUTPUT

}  // namespace teensy_model
