// The Teensyduino model: see teensy_model.hpp for what it follows and why.
#include "teensy_model.hpp"

#include <Arduino.h>
#include <Ethernet.h>
#include <EthernetUdp.h>
#include <IntervalTimer.h>
#include <SPI.h>
#include <Wire.h>
#include <usb_dev.h>

#include <algorithm>
#include <array>
#include <deque>
#include <map>
#include <new>

namespace teensy_model_regs {
volatile uint32_t sim_scgc2 = 0;
volatile uint8_t dac0[4] = {0, 0, 0, 0};
volatile uint32_t demcr = 0, dwt_ctrl = 0;
volatile uint16_t wdog_refresh = 0, wdog_unlock = 0, wdog_tovalh = 0, wdog_tovall = 0, wdog_presc = 0,
                  wdog_stctrlh = 0;
uint32_t dwt_cyccnt() { return static_cast<uint32_t>(teensy_model::now_us() * 180u); }
}  // namespace teensy_model_regs

uint8_t yield_active_check_flags = YIELD_CHECK_USB_SERIAL;  // yield.cpp's default
volatile uint8_t usb_configuration = 0;
usb_seremu_class Serial;
usb_mouse_class Mouse;
SPIClass SPI;
TwoWire Wire;
EthernetClass Ethernet;

// pins_teensy.c: startup_default_middle_hook does nothing.
extern "C" __attribute__((weak)) void startup_middle_hook(void) {}

namespace teensy_model {
namespace {

constexpr uint32_t kTxTimeoutUs = 30000;   // usb_seremu.c / usb_mouse.c TX_TIMEOUT_MSEC
constexpr uint32_t kSeremuTxLimit = 6;     // usb_seremu.c TX_PACKET_LIMIT
constexpr uint32_t kMouseTxLimit = 3;      // usb_mouse.c TX_PACKET_LIMIT
constexpr uint32_t kHostOutIntervalUs = 2000;  // SEREMU_RX_INTERVAL
constexpr uint32_t kHostInIntervalUs = 1000;   // SEREMU_TX_INTERVAL, MOUSE_INTERVAL

struct State {
  Options options;
  uint64_t now = 0;
  bool in_interrupt = false;
  bool irq_disabled = false;
  bool halted = false;  // rebooted
  uint32_t interrupts = 0;
  uint64_t longest_pass = 0;
  // Timer and pin interrupts.
  void (*timer_fn)() = nullptr;
  uint32_t timer_period = 0;
  uint64_t timer_next = 0;
  uint8_t timer_priority = 128;
  void (*pin_fn)() = nullptr;
  uint8_t pin_irq_pin = 0xFF;
  bool pin_level = false;
  std::function<bool(uint64_t)> dr_level;
  std::function<uint16_t(uint8_t, uint64_t)> analog;
  std::function<void(uint64_t)> pacer, time_hook;
  // Pins.
  std::array<uint8_t, 70> pin_mode{};
  std::array<uint8_t, 70> pin_out{};
  // Devices.
  std::map<uint8_t, ff::emulated::I2cTarget*> i2c;
  std::map<uint8_t, ff::SpiBus16*> spi;
  ff::SpiConfig spi_config;
  bool spi_in_transaction = false;
  uint8_t wire_address = 0;
  std::vector<uint8_t> wire_tx, wire_rx;
  size_t wire_rx_pos = 0;
  uint32_t wire_bit_hz = 416000;
  // DAC.
  std::vector<DacState> dac;
  // USB.
  std::array<usb_packet_t, NUM_USB_BUFFERS> buffers{};
  std::array<bool, NUM_USB_BUFFERS> buffer_free{};
  std::deque<usb_packet_t*> rx_held;  // buffers the SEREMU OUT endpoint holds for the next packets (2)
  int rx_memory_needed = 0;
  std::deque<usb_packet_t*> rx_queue;
  usb_packet_t* seremu_rx_packet = nullptr;  // usb_seremu.c's private rx_packet
  std::deque<usb_packet_t*> tx_queue[8];
  bool transmit_previous_timeout_seremu = false, transmit_previous_timeout_mouse = false;
  std::deque<std::vector<uint8_t>> host_out;
  uint64_t host_out_next = 0, host_in_next = 0;
  uint64_t usb_frame_next = 0;    // the next start of frame (every 1 ms while configured)
  uint8_t usb_reboot_timer = 0;   // usb_dev.c: frames until _reboot_Teensyduino_(), 0 idle
  bool usb_seremu_online = false;
  std::vector<std::vector<uint8_t>> host_seremu_in;
  std::vector<MouseReport> host_mouse;
  bool host_polls = true;
  uint32_t serial_available_calls = 0;
  uint16_t mouse_w = 800, mouse_h = 480;
  // Ethernet.
  uint32_t eth_cs = 10;  // Ethernet.h init() default
  uint16_t rtr_ms = 200;
  uint8_t rcr = 8;
  UdpNetwork* network = nullptr;
  bool udp_socket = false;  // EthernetUDP::begin() found one
  uint32_t udp_calls_without_socket = 0;
  std::vector<uint8_t> udp_in;
  size_t udp_in_pos = 0;
  uint32_t udp_in_ip = 0;
  uint16_t udp_in_port = 0;
  uint32_t udp_out_ip = 0;
  uint16_t udp_out_port = 0;
  std::vector<uint8_t> udp_out;
};

State& s() {
  static State state;
  return state;
}

void observe_dac() {
  State& st = s();
  DacState d;
  d.t_us = st.now;
  d.enabled = (teensy_model_regs::sim_scgc2 & SIM_SCGC2_DAC0) && (teensy_model_regs::dac0[2] & DAC_C0_DACEN);
  d.internal_ref = (teensy_model_regs::dac0[2] & DAC_C0_DACRFS) == 0;
  d.code = static_cast<uint16_t>(teensy_model_regs::dac0[0] | ((teensy_model_regs::dac0[1] & 0x0F) << 8));
  if (!st.dac.empty()) {
    const DacState& last = st.dac.back();
    if (last.enabled == d.enabled && last.internal_ref == d.internal_ref && last.code == d.code) return;
    if (!st.options.keep_dac_history) st.dac.clear();
  }
  st.dac.push_back(d);
}

// ---- USB buffers (usb_mem.c) ----
usb_packet_t* usb_malloc() {
  State& st = s();
  for (int i = 0; i < NUM_USB_BUFFERS; ++i) {
    if (st.buffer_free[i]) {
      st.buffer_free[i] = false;
      st.buffers[i].len = 0;
      st.buffers[i].index = 0;
      st.buffers[i].next = nullptr;
      return &st.buffers[i];
    }
  }
  return nullptr;
}

void release(usb_packet_t* p) {
  State& st = s();
  const long i = p - st.buffers.data();
  if (i < 0 || i >= NUM_USB_BUFFERS) return;
  if (st.rx_memory_needed > 0 && usb_configuration) {  // usb_free: a starving receive endpoint first
    --st.rx_memory_needed;
    st.rx_held.push_back(p);
    return;
  }
  st.buffer_free[i] = true;
}

// The USB host's side, at its own schedule: IN polls every 1 ms, an OUT packet every 2 ms.
void usb_host_step() {
  State& st = s();
  if (!usb_configuration) {
    if (st.now < st.options.usb_host_attach_ms * 1000ull) return;
    usb_configuration = 1;  // the host enumerated and configured the device
    for (int i = 0; i < 2; ++i) {  // usb_dev.c, SET_CONFIGURATION: two buffers per receive endpoint
      if (usb_packet_t* p = usb_malloc()) {
        st.rx_held.push_back(p);
      } else {
        ++st.rx_memory_needed;
      }
    }
    st.host_in_next = st.host_out_next = st.usb_frame_next = st.now;
  }
  while (st.now >= st.usb_frame_next && !st.halted) {  // usb_isr's SOF handler
    st.usb_frame_next += kHostInIntervalUs;
    if (st.usb_reboot_timer > 0 && --st.usb_reboot_timer == 0) _reboot_Teensyduino_();
  }
  while (st.host_polls && st.now >= st.host_in_next) {
    st.host_in_next += kHostInIntervalUs;
    if (!st.tx_queue[SEREMU_TX_ENDPOINT].empty()) {
      usb_packet_t* p = st.tx_queue[SEREMU_TX_ENDPOINT].front();
      st.tx_queue[SEREMU_TX_ENDPOINT].pop_front();
      st.host_seremu_in.emplace_back(p->buf, p->buf + 64);
      release(p);
    }
    if (!st.tx_queue[MOUSE_ENDPOINT].empty()) {
      usb_packet_t* p = st.tx_queue[MOUSE_ENDPOINT].front();
      st.tx_queue[MOUSE_ENDPOINT].pop_front();
      // usb_mouse.c: report id 2, x and y scaled to 0..32767 in bytes 1-4.
      const uint32_t x = p->buf[1] | (p->buf[2] << 8), y = p->buf[3] | (p->buf[4] << 8);
      st.host_mouse.push_back({st.now, static_cast<uint16_t>(x * st.mouse_w / 32768u),
                               static_cast<uint16_t>(y * st.mouse_h / 32768u)});
      release(p);
    }
  }
  if (!st.host_polls) st.host_in_next = st.now;
  while (st.now >= st.host_out_next) {
    st.host_out_next += kHostOutIntervalUs;
    if (st.host_out.empty() || st.rx_held.empty()) continue;  // nothing, or NAK: the host retries
    // The packet lands in a buffer the endpoint held; the USB interrupt queues it (usb_rx's list)
    // and gives the endpoint a new buffer (usb_dev.c usb_isr: usb_malloc, else usb_rx_memory_needed++).
    usb_packet_t* p = st.rx_held.front();
    st.rx_held.pop_front();
    const std::vector<uint8_t>& bytes = st.host_out.front();
    p->len = static_cast<uint16_t>(bytes.size());
    p->index = 0;
    std::copy(bytes.begin(), bytes.end(), p->buf);
    st.host_out.pop_front();
    st.rx_queue.push_back(p);
    if (usb_packet_t* replacement = usb_malloc()) {
      st.rx_held.push_back(replacement);
    } else {
      ++st.rx_memory_needed;
    }
  }
}

void dispatch_interrupts();

// Moves simulated time on by `us`, letting interrupts and the host act at their times.
void spend(uint64_t us) {
  State& st = s();
  const uint64_t end = st.now + us;
  while (!st.halted) {
    uint64_t next = end;
    if (st.timer_fn && !st.in_interrupt && !st.irq_disabled) next = std::min(next, st.timer_next);
    if (next > st.now) {
      st.now = next;
    }
    if (st.time_hook) st.time_hook(st.now);
    if (st.pacer) st.pacer(st.now);
    usb_host_step();
    dispatch_interrupts();
    if (st.now >= end) break;
  }
  observe_dac();
}

void dispatch_interrupts() {
  State& st = s();
  if (st.in_interrupt || st.irq_disabled || st.halted) return;
  // The DR pin: a rising edge interrupts (attachInterrupt RISING).
  if (st.dr_level) {
    const bool level = st.dr_level(st.now);
    if (level && !st.pin_level && st.pin_fn) {
      st.in_interrupt = true;
      ++st.interrupts;
      st.pin_fn();
      st.in_interrupt = false;
    }
    st.pin_level = level;
  }
  while (st.timer_fn && st.now >= st.timer_next && !st.halted) {
    st.timer_next += st.timer_period;
    st.in_interrupt = true;
    ++st.interrupts;
    st.timer_fn();
    st.in_interrupt = false;
    observe_dac();
  }
}

}  // namespace

// ---- controls ----
void reset(const Options& options) {
  State& st = s();
  st.~State();
  new (&st) State();
  st.options = options;
  st.host_polls = options.host_polls;
  st.buffer_free.fill(true);
  usb_configuration = 0;
  yield_active_check_flags = YIELD_CHECK_USB_SERIAL;
  teensy_model_regs::sim_scgc2 = 0;
  for (auto& r : teensy_model_regs::dac0) r = 0;
  observe_dac();
}
void attach_i2c(uint8_t address, ff::emulated::I2cTarget& target) { s().i2c[address] = &target; }
void attach_spi(uint8_t pin, ff::SpiBus16& device) { s().spi[pin] = &device; }
void set_data_ready_source(std::function<bool(uint64_t)> level) { s().dr_level = std::move(level); }
void set_analog_source(std::function<uint16_t(uint8_t, uint64_t)> counts) { s().analog = std::move(counts); }
void set_network(UdpNetwork* network) { s().network = network; }
void set_pacer(std::function<void(uint64_t)> pacer) { s().pacer = std::move(pacer); }
void set_time_hook(std::function<void(uint64_t)> hook) { s().time_hook = std::move(hook); }

void boot() {
  spend(500);  // ResetHandler up to analog_init (clocks, memory)
  startup_middle_hook();
  observe_dac();
  spend(20000);
  // usb_init: the endpoint's two receive buffers come from the pool when the host configures it.
  spend(280000);
  setup();
  observe_dac();
}

void run_until(uint64_t t_us) {
  State& st = s();
  while (st.now < t_us && !st.halted) {
    const uint64_t start = st.now;
    loop();
    spend(st.options.loop_pass_us);
    yield();  // teensy3/main.cpp: while (1) { loop(); yield(); }
    st.longest_pass = std::max(st.longest_pass, st.now - start);
  }
}

uint64_t now_us() { return s().now; }
bool rebooted() { return s().halted; }
void host_write_out_packet(const uint8_t* data, size_t len) { s().host_out.emplace_back(data, data + len); }
size_t host_out_backlog() { return s().host_out.size(); }
void host_set_seremu_feature_report(const uint8_t* data, size_t len) {
  // usb_dev.c usb_control: SET_REPORT (wValue 0x0300, wLength 4) on SEREMU_INTERFACE. The magic
  // restarts into the bootloader 5 frames later; any other 4 bytes mark the serial emulation online.
  State& st = s();
  if (!usb_configuration || len != 4) return;
  if (data[0] == 0xA9 && data[1] == 0x45 && data[2] == 0xC2 && data[3] == 0x6B) {
    st.usb_reboot_timer = 5;
  } else {
    st.usb_seremu_online = true;
  }
}
bool usb_seremu_online() { return s().usb_seremu_online; }
std::vector<std::vector<uint8_t>> host_take_seremu_in() {
  std::vector<std::vector<uint8_t>> out;
  out.swap(s().host_seremu_in);
  return out;
}
std::vector<MouseReport> host_take_mouse() {
  std::vector<MouseReport> out;
  out.swap(s().host_mouse);
  return out;
}
void set_host_polls(bool polls) { s().host_polls = polls; }
size_t usb_buffers_free() {
  const State& st = s();
  return static_cast<size_t>(std::count(st.buffer_free.begin(), st.buffer_free.end(), true));
}
const std::vector<DacState>& dac_history() { return s().dac; }
DacState dac_now() { return s().dac.empty() ? DacState{} : s().dac.back(); }
uint32_t interrupt_count() { return s().interrupts; }
uint64_t longest_loop_pass_us() { return s().longest_pass; }
uint32_t ethernet_chip_select() { return s().eth_cs; }
uint16_t retransmission_timeout_ms() { return s().rtr_ms; }
uint8_t retransmission_count() { return s().rcr; }
uint32_t udp_calls_without_socket() { return s().udp_calls_without_socket; }
uint8_t timer_priority() { return s().timer_priority; }
uint32_t serial_available_calls() { return s().serial_available_calls; }
std::vector<uint8_t> output_pins() {
  std::vector<uint8_t> out;
  for (size_t p = 0; p < s().pin_mode.size(); ++p) {
    if (s().pin_mode[p] == OUTPUT) out.push_back(static_cast<uint8_t>(p));
  }
  return out;
}

}  // namespace teensy_model

using teensy_model::s;
using teensy_model::spend;

// ---- core_pins.h ----
uint32_t micros() {
  spend(1);  // every call takes time: interrupts can land between any two (and the DWT counts)
  return static_cast<uint32_t>(s().now);
}
uint32_t millis() { return static_cast<uint32_t>(s().now / 1000); }
void delay(uint32_t ms) {  // pins_teensy.c: yield() while waiting
  const uint64_t end = s().now + 1000ull * ms;
  while (s().now < end && !s().halted) {
    yield();
    spend(std::min<uint64_t>(100, end - s().now));
  }
}
void yield() {
  if (yield_active_check_flags & YIELD_CHECK_USB_SERIAL) {
    if (Serial.available()) {
    }  // serialEvent() is the empty default
    // yield.cpp: with the default serialEvent (_serialEvent_default) the flag is cleared after the first check.
    yield_active_check_flags &= static_cast<uint8_t>(~YIELD_CHECK_USB_SERIAL);
  }
}
void pinMode(uint8_t pin, uint8_t mode) {
  if (pin < s().pin_mode.size()) s().pin_mode[pin] = mode;
}
void digitalWriteFast(uint8_t pin, uint8_t value) {
  if (pin < s().pin_out.size()) s().pin_out[pin] = value;
}
uint8_t digitalReadFast(uint8_t pin) {
  if (pin == s().pin_irq_pin && s().dr_level) return s().dr_level(s().now) ? HIGH : LOW;
  return pin < s().pin_out.size() ? s().pin_out[pin] : LOW;
}
void attachInterrupt(uint8_t pin, void (*function)(), int mode) {
  if (mode != RISING) return;
  s().pin_irq_pin = pin;
  s().pin_fn = function;
  s().pin_level = s().dr_level ? s().dr_level(s().now) : false;
}
int analogRead(uint8_t pin) {
  spend(10);  // a 13-bit conversion with the core's averaging
  // A pin the firmware drives (a chip select) reads its own level, not the load cell behind it.
  if (pin < s().pin_mode.size() && s().pin_mode[pin] == OUTPUT) return s().pin_out[pin] ? 8191 : 0;
  return s().analog ? s().analog(pin, s().now) : 0;
}
void analogReadResolution(unsigned int) {}
void analogWriteResolution(uint32_t) {}
void analogWrite(uint8_t pin, int value) {  // analog.c analogWriteDAC0: selects the 3.3 V reference
  if (pin != A21) return;
  teensy_model_regs::sim_scgc2 |= SIM_SCGC2_DAC0;
  teensy_model_regs::dac0[2] = DAC_C0_DACEN | DAC_C0_DACRFS;
  const int v = std::clamp(value, 0, 4095);
  teensy_model_regs::dac0[0] = static_cast<uint8_t>(v);
  teensy_model_regs::dac0[1] = static_cast<uint8_t>(v >> 8);
  teensy_model::observe_dac();
}
void analogReference(uint8_t) {}
void _reboot_Teensyduino_() {
  teensy_model::observe_dac();
  s().halted = true;
}
void __disable_irq() { s().irq_disabled = true; }
void __enable_irq() {
  s().irq_disabled = false;
  spend(0);
}

// ---- usb_dev.c ----
usb_packet_t* usb_rx(uint32_t endpoint) {
  if (endpoint != SEREMU_RX_ENDPOINT || s().rx_queue.empty()) return nullptr;
  usb_packet_t* p = s().rx_queue.front();
  s().rx_queue.pop_front();
  return p;
}
void usb_free(usb_packet_t* p) { teensy_model::release(p); }
uint32_t usb_tx_packet_count(uint32_t endpoint) {
  return endpoint < 8 ? static_cast<uint32_t>(s().tx_queue[endpoint].size()) : 0;
}

// ---- usb_seremu.c ----
int usb_seremu_class::available() {
  auto& st = s();
  ++st.serial_available_calls;
  if (!st.seremu_rx_packet) {
    if (usb_configuration) st.seremu_rx_packet = usb_rx(SEREMU_RX_ENDPOINT);
    if (!st.seremu_rx_packet) return 0;
  }
  int count = 0;
  for (int i = st.seremu_rx_packet->index; i < st.seremu_rx_packet->len; ++i) {
    if (st.seremu_rx_packet->buf[i] == 0) break;
    ++count;
  }
  if (count == 0) {
    usb_free(st.seremu_rx_packet);
    st.seremu_rx_packet = nullptr;
  }
  return count;
}
int usb_seremu_class::read() {  // usb_seremu_getchar
  auto& st = s();
  for (;;) {
    if (!usb_configuration) return -1;
    if (!st.seremu_rx_packet) st.seremu_rx_packet = usb_rx(SEREMU_RX_ENDPOINT);
    if (!st.seremu_rx_packet) return -1;
    usb_packet_t* p = st.seremu_rx_packet;
    const int c = p->buf[p->index++];
    if (c) {
      if (p->index >= p->len) {
        usb_free(p);
        st.seremu_rx_packet = nullptr;
      }
      return c;
    }
    usb_free(p);
    st.seremu_rx_packet = nullptr;
  }
}
size_t usb_seremu_class::readBytes(char* buffer, size_t length) {  // Stream::readBytes, 1000 ms timeout
  size_t n = 0;
  const uint64_t deadline = s().now + 1000000;
  while (n < length && s().now < deadline && !s().halted) {
    const int c = read();
    if (c < 0) {
      spend(100);
      continue;
    }
    buffer[n++] = static_cast<char>(c);
  }
  return n;
}
size_t usb_seremu_class::write(const uint8_t* buffer, size_t size) {  // usb_seremu_write (whole packets)
  auto& st = s();
  size_t done = 0;
  while (done < size) {
    usb_packet_t* p = nullptr;
    const uint64_t start = st.now;
    for (;;) {
      if (!usb_configuration) return done;
      if (usb_tx_packet_count(SEREMU_TX_ENDPOINT) < teensy_model::kSeremuTxLimit) p = teensy_model::usb_malloc();
      if (p) break;
      if (st.now - start > teensy_model::kTxTimeoutUs || st.transmit_previous_timeout_seremu) {
        st.transmit_previous_timeout_seremu = true;
        return done;
      }
      yield();
      spend(5);
    }
    st.transmit_previous_timeout_seremu = false;
    const size_t n = std::min<size_t>(64, size - done);
    std::fill(p->buf, p->buf + 64, 0);
    std::copy(buffer + done, buffer + done + n, p->buf);
    p->len = 64;
    st.tx_queue[SEREMU_TX_ENDPOINT].push_back(p);
    done += n;
    spend(1);
  }
  return done;
}
int usb_seremu_class::availableForWrite() {
  return usb_configuration && usb_tx_packet_count(SEREMU_TX_ENDPOINT) < teensy_model::kSeremuTxLimit ? 64 : 0;
}

// ---- usb_mouse.c ----
void usb_mouse_class::screenSize(uint16_t width, uint16_t height, bool) {
  s().mouse_w = width;
  s().mouse_h = height;
}
void usb_mouse_class::moveTo(uint16_t x, uint16_t y) {  // usb_mouse_position
  auto& st = s();
  if (x >= st.mouse_w) x = static_cast<uint16_t>(st.mouse_w - 1);
  if (y >= st.mouse_h) y = static_cast<uint16_t>(st.mouse_h - 1);
  usb_packet_t* p = nullptr;
  const uint64_t start = st.now;
  for (;;) {
    if (!usb_configuration) return;
    if (usb_tx_packet_count(MOUSE_ENDPOINT) < teensy_model::kMouseTxLimit) p = teensy_model::usb_malloc();
    if (p) break;
    if (st.now - start > teensy_model::kTxTimeoutUs || st.transmit_previous_timeout_mouse) {
      st.transmit_previous_timeout_mouse = true;
      return;
    }
    yield();
    spend(5);
  }
  st.transmit_previous_timeout_mouse = false;
  const uint32_t vx = (static_cast<uint32_t>(x) * 32768u + st.mouse_w / 2) / st.mouse_w;
  const uint32_t vy = (static_cast<uint32_t>(y) * 32768u + st.mouse_h / 2) / st.mouse_h;
  p->buf[0] = 2;
  p->buf[1] = static_cast<uint8_t>(vx);
  p->buf[2] = static_cast<uint8_t>(vx >> 8);
  p->buf[3] = static_cast<uint8_t>(vy);
  p->buf[4] = static_cast<uint8_t>(vy >> 8);
  p->len = 5;
  st.tx_queue[MOUSE_ENDPOINT].push_back(p);
  spend(1);
}

// ---- IntervalTimer.cpp ----
bool IntervalTimer::begin(void (*function)(), uint32_t microseconds) {
  s().timer_fn = function;
  s().timer_period = microseconds;
  s().timer_next = s().now + microseconds;
  return true;
}
void IntervalTimer::priority(uint8_t n) { s().timer_priority = n; }
void IntervalTimer::end() { s().timer_fn = nullptr; }

// ---- SPI ----
void SPIClass::begin() {}
void SPIClass::beginTransaction(const SPISettings& settings) {
  auto& st = s();
  st.spi_in_transaction = true;
  st.spi_config.max_clock_hz = settings.clock;
  st.spi_config.mode = settings.mode == SPI_MODE2   ? ff::SpiMode::Mode2
                       : settings.mode == SPI_MODE1 ? ff::SpiMode::Mode1
                       : settings.mode == SPI_MODE3 ? ff::SpiMode::Mode3
                                                    : ff::SpiMode::Mode0;
}
uint16_t SPIClass::transfer16(uint16_t data) {
  auto& st = s();
  for (auto& [pin, device] : st.spi) {
    if (st.pin_out[pin] == LOW && st.pin_mode[pin] == OUTPUT) device->write(st.spi_config, 0, &data, 1);
  }
  spend(1);
  return 0;
}
void SPIClass::endTransaction() { s().spi_in_transaction = false; }

// ---- Wire ----
void TwoWire::begin() {}
void TwoWire::setClock(uint32_t frequency) {  // WireKinetis.cpp, F_BUS 60 MHz: 104, 416 or 938 kHz
  s().wire_bit_hz = frequency < 400000 ? 104000 : frequency < 1000000 ? 416000 : 938000;
}
void TwoWire::beginTransmission(uint8_t address) {
  s().wire_address = address;
  s().wire_tx.clear();
}
size_t TwoWire::write(const uint8_t* data, size_t quantity) {
  s().wire_tx.insert(s().wire_tx.end(), data, data + quantity);
  return quantity;
}
uint8_t TwoWire::endTransmission(uint8_t) {
  auto& st = s();
  spend((st.wire_tx.size() + 1) * 9ull * 1000000ull / st.wire_bit_hz);
  auto it = st.i2c.find(st.wire_address);
  if (it == st.i2c.end()) return 2;  // address NACK
  return it->second->on_write(st.wire_tx.data(), st.wire_tx.size()) == ff::BusStatus::Ok ? 0 : 3;
}
uint8_t TwoWire::requestFrom(uint8_t address, uint8_t quantity) {
  auto& st = s();
  spend((quantity + 1u) * 9ull * 1000000ull / st.wire_bit_hz);
  st.wire_rx.assign(quantity, 0);
  st.wire_rx_pos = 0;
  auto it = st.i2c.find(address);
  if (it == st.i2c.end() || it->second->on_read(st.wire_rx.data(), quantity) != ff::BusStatus::Ok) {
    st.wire_rx.clear();
    return 0;
  }
  return quantity;
}
int TwoWire::read() {
  auto& st = s();
  return st.wire_rx_pos < st.wire_rx.size() ? st.wire_rx[st.wire_rx_pos++] : -1;
}

// ---- Ethernet ----
void EthernetClass::init(uint8_t sspin) { s().eth_cs = sspin; }
void EthernetClass::begin(uint8_t*, IPAddress) {
  delay(560);  // w5100.cpp init(): for the reset chip on many shields, chip or not
  pinMode(static_cast<uint8_t>(s().eth_cs), OUTPUT);  // w5100.h initSS()
  digitalWriteFast(static_cast<uint8_t>(s().eth_cs), HIGH);
}
void EthernetClass::setRetransmissionTimeout(uint16_t milliseconds) { s().rtr_ms = milliseconds; }
void EthernetClass::setRetransmissionCount(uint8_t num) { s().rcr = num; }

namespace {
// socket.cpp indexes its socket state with the socket number, unchecked: a
// call without a socket reads and writes past the array on the board.
bool udp_socket_or_count() {
  if (s().udp_socket) return true;
  ++s().udp_calls_without_socket;
  return false;
}
}  // namespace

uint8_t EthernetUDP::begin(uint16_t) {
  s().udp_socket = s().options.w5200_present;  // socket.cpp socketBegin: none without a chip
  return s().udp_socket ? 1 : 0;
}
int EthernetUDP::parsePacket() {
  auto& st = s();
  if (!udp_socket_or_count()) return 0;
  spend(5);
  if (st.udp_in_pos < st.udp_in.size()) spend(5);  // the rest of the last datagram dropped: read(NULL, remaining)
  st.udp_in.clear();
  st.udp_in_pos = 0;
  if (!st.network || !st.network->receive(st.udp_in, st.udp_in_ip, st.udp_in_port)) return 0;
  return static_cast<int>(st.udp_in.size());
}
int EthernetUDP::available() {
  if (!udp_socket_or_count()) return 0;
  return static_cast<int>(s().udp_in.size() - s().udp_in_pos);
}
int EthernetUDP::read() {
  if (available() <= 0) return -1;
  spend(5);  // one socketRecv of one byte: a whole SPI transaction
  return s().udp_in[s().udp_in_pos++];
}
int EthernetUDP::read(uint8_t* buffer, size_t len) {
  const size_t n = std::min(len, static_cast<size_t>(std::max(available(), 0)));
  if (buffer != nullptr) {  // NULL: skipped (socket.cpp socketRecv)
    std::copy(s().udp_in.begin() + static_cast<long>(s().udp_in_pos),
              s().udp_in.begin() + static_cast<long>(s().udp_in_pos + n), buffer);
  }
  s().udp_in_pos += n;
  spend(n / 8 + 1);
  return n > 0 ? static_cast<int>(n) : -1;
}
IPAddress EthernetUDP::remoteIP() { return IPAddress(s().udp_in_ip); }
uint16_t EthernetUDP::remotePort() { return s().udp_in_port; }
int EthernetUDP::beginPacket(IPAddress ip, uint16_t port) {
  if (!udp_socket_or_count()) return 0;
  s().udp_out_ip = ip;
  s().udp_out_port = port;
  s().udp_out.clear();
  return 1;
}
size_t EthernetUDP::write(const uint8_t* buffer, size_t size) {
  if (!udp_socket_or_count()) return 0;
  s().udp_out.insert(s().udp_out.end(), buffer, buffer + size);
  return size;
}
int EthernetUDP::endPacket() {  // socket.cpp socketSendUDP
  auto& st = s();
  if (!udp_socket_or_count()) return 0;
  spend(20 + st.udp_out.size() / 8);
  if (st.network && st.network->deliver(st.udp_out_ip, st.udp_out_port, st.udp_out)) return 1;
  // No ARP answer: the W5200 retries RCR times every RTR while the library busy-waits, yielding.
  const uint64_t end = st.now + static_cast<uint64_t>(st.rtr_ms) * 1000u * (st.rcr + 1u);
  while (st.now < end && !st.halted) {
    yield();
    spend(100);
  }
  return 0;
}
