// frictionfield firmware for the Teensy 3.6 (MK66FX1M0, 180 MHz), built by
// PlatformIO (platformio.ini, env teensy36, USB type USB_HID: absolute mouse
// + serial emulation over HID as the host channel). This file only binds the
// core's bus interfaces and the Board to Teensyduino, one call each; every
// decision is in firmware/app (pins, packet joining, transmit room, rest
// codes, link limits), tested natively. test/teensy_model compiles this file
// unchanged against a model of the Teensyduino calls it makes (each naming
// the core file it follows), and ff-sim runs it on a laptop.
// Our headers first: Arduino.h defines macros (bit, min, max, ...) that
// would rewrite the portable code.
#include "firmware/app/dac_wiring.hpp"
#include "firmware/app/firmware_app.hpp"
#include "firmware/app/host_link_limits.hpp"
#include "firmware/app/pins.hpp"
#include "firmware/app/seremu_joiner.hpp"
#include "frictionfield/core/fastrun.hpp"
#include "frictionfield/core/geometry.hpp"
#include "frictionfield/protocol/hid_channel.hpp"

#include <Arduino.h>
#include <Ethernet.h>
#include <EthernetUdp.h>
#include <IntervalTimer.h>
#include <SPI.h>
#include <Wire.h>
#include <usb_dev.h>  // usb_rx, usb_free, usb_tx_packet_count and the endpoints (usb_undef.h hides them from Arduino.h)

namespace {

namespace pins = ff::firmware::pins;
constexpr uint16_t kUdpPort = 8888;
uint8_t kMac[6] = {0x04, 0xE9, 0xE5, 0x00, 0x00, 0x01};
const IPAddress kIp(192, 168, 1, 177);  // the lab's fixed address; set for your network
constexpr uint32_t kI2cClockHz = 400000;  // Wire on a 60 MHz bus gives 416 kHz (WireKinetis.cpp divider table)

// ---- DAC0 on the 1.2 V reference (firmware/app/dac_wiring.hpp) ----------------
// analogWrite() would select the 3.3 V reference at every call (analog.c
// analogWriteDAC0); the same 16-bit data write, with DACREF_1 chosen once.
typedef int16_t __attribute__((__may_alias__)) dac_data_t;
void dac0_enable_on_internal_reference() {
  SIM_SCGC2 |= SIM_SCGC2_DAC0;
  DAC0_C0 = DAC_C0_DACEN;  // DACRFS clear: DACREF_1 = VREF_OUT, 1.2 V (analog_init enabled VREF)
}
FF_FASTRUN void dac0_write(uint16_t code) { *(volatile dac_data_t*)&(DAC0_DAT0L) = static_cast<int16_t>(code); }

// ---- bus interfaces ------------------------------------------------------------

class TeensySpi final : public ff::SpiBus16 {
  ff::BusStatus do_write(const ff::SpiConfig& config, uint8_t cs, const uint16_t* words, size_t count) override {
    const uint8_t mode = config.mode == ff::SpiMode::Mode2 ? SPI_MODE2
                         : config.mode == ff::SpiMode::Mode1 ? SPI_MODE1
                         : config.mode == ff::SpiMode::Mode3 ? SPI_MODE3 : SPI_MODE0;
    const uint8_t pin = cs == 0 ? pins::kDdsChipSelect : cs;
    SPI.beginTransaction(SPISettings(config.max_clock_hz, MSBFIRST, mode));
    for (size_t i = 0; i < count; ++i) {  // FSYNC framed per 16-bit word
      digitalWriteFast(pin, LOW);
      SPI.transfer16(words[i]);
      digitalWriteFast(pin, HIGH);
    }
    SPI.endTransaction();
    return ff::BusStatus::Ok;
  }
};

class TeensyI2c final : public ff::I2cInitiator {
  ff::BusStatus do_write_read(uint8_t address, const uint8_t* tx, size_t tx_len, uint8_t* rx, size_t rx_len,
                              uint32_t /*timeout_us*/) override {
    if (tx_len > 0) {
      Wire.beginTransmission(address);
      Wire.write(tx, tx_len);
      const uint8_t e = Wire.endTransmission(rx_len == 0);
      if (e == 2 || e == 3) return ff::BusStatus::Nack;
      if (e != 0) return ff::BusStatus::BusError;
    }
    if (rx_len > 0) {
      if (Wire.requestFrom(address, static_cast<uint8_t>(rx_len)) != rx_len) return ff::BusStatus::Nack;
      for (size_t i = 0; i < rx_len; ++i) rx[i] = static_cast<uint8_t>(Wire.read());
    }
    return ff::BusStatus::Ok;
  }
};

ff::EdgeLatch data_ready_edges;
void on_data_ready() { data_ready_edges.on_edge(micros()); }  // timestamp only: the read is in the loop

class TeensyDataReady final : public ff::DataReadyInput {
  bool asserted() const override { return digitalReadFast(pins::kZforceDataReady) == HIGH; }
  bool take_edge(uint32_t& t_us, uint32_t& edges) override { return data_ready_edges.take(t_us, edges); }
};

class TeensyDac final : public ff::Dac12 {
  FF_FASTRUN ff::BusStatus do_write(uint16_t code) override {
    dac0_write(code);  // DAC0 (A21) -> AD9834 FSADJUST
    return ff::BusStatus::Ok;
  }
};

class TeensyAdc final : public ff::Adc {
  uint8_t channel_count() const override { return pins::kLoadCellCount; }
  uint8_t resolution_bits() const override { return pins::kLoadCellAdcBits; }
  ff::BusStatus do_read(uint8_t channel, uint16_t& value) override {
    if (channel >= pins::kLoadCellCount) return ff::BusStatus::InvalidArgument;
    value = static_cast<uint16_t>(analogRead(pins::kLoadCells[channel]));
    return ff::BusStatus::Ok;
  }
};

// ---- the board --------------------------------------------------------------------

EthernetUDP udp;
ff::firmware::SeremuJoiner seremu_in;

class TeensyBoard final : public ff::firmware::Board {
 public:
  bool mouse_move_to(int x, int y) override {
    if (!ff::firmware::mouse_can_send(usb_configuration, usb_tx_packet_count(MOUSE_ENDPOINT))) return false;
    Mouse.moveTo(static_cast<uint16_t>(x), static_cast<uint16_t>(y));
    return true;
  }
  // Without a W5200 (absent, unpowered, or hung: it needs a reset pulse this
  // board cannot give, w5100.cpp) udp.begin() finds no socket, and every later
  // EthernetUDP call would index the library's socket state past its end
  // (socket.cpp socketRecvAvailable): the socket is left alone until reset.
  void open_udp() { udp_open_ = udp.begin(kUdpPort) == 1; }
  bool udp_available() const override { return udp_open_; }
  bool udp_receive(uint8_t* buffer, size_t capacity, size_t& size, ff::firmware::UdpEndpoint& from) override {
    if (!udp_open_) return false;
    const int n = udp.parsePacket();
    if (n <= 0) return false;
    const IPAddress ip = udp.remoteIP();
    from = {static_cast<uint32_t>(ip), udp.remotePort()};
    if (static_cast<size_t>(n) > capacity) {  // too long for any message: dropped by the next parsePacket()
      size = 0;  // in one SPI transaction (EthernetUdp.cpp read(NULL, remaining)), not a byte at a time
      return true;  // an empty frame: answered as malformed
    }
    size = static_cast<size_t>(udp.read(buffer, capacity));
    return true;
  }
  bool udp_send(const ff::firmware::UdpEndpoint& to, const uint8_t* data, size_t size) override {
    if (!udp_open_) return false;
    if (!udp.beginPacket(IPAddress(to.ip), to.port)) return false;
    udp.write(data, size);
    return udp.endPacket() == 1;  // bounded by Ethernet.setRetransmissionTimeout/Count (setup)
  }
  // Host channel: raw 32-byte SEREMU OUT packets, joined in pairs.
  bool hid_receive(uint8_t* report) override {
    while (usb_packet_t* packet = usb_rx(SEREMU_RX_ENDPOINT)) {
      const bool whole = seremu_in.push(packet->buf, packet->len, micros(), report);
      usb_free(packet);  // at once: the 24 USB buffers are shared by every endpoint
      if (whole) return true;
    }
    return false;
  }
  void hid_send(const uint8_t* report) override { Serial.write(report, ff::protocol::kHidReportBytes); }
  size_t hid_tx_room() override {
    return ff::firmware::seremu_tx_room(usb_configuration, usb_tx_packet_count(SEREMU_TX_ENDPOINT));
  }
  FF_FASTRUN uint32_t cycles() override { return ARM_DWT_CYCCNT; }
  void reboot_to_bootloader() override { _reboot_Teensyduino_(); }
  void watchdog_kick() override {
    // The loop passes every few microseconds; a refresh every 100 ms is plenty
    // for a 1 s timeout and keeps the interrupts-off window rare.
    const uint32_t now_ms = millis();
    if (now_ms - last_kick_ms_ < 100) return;
    last_kick_ms_ = now_ms;
    // The refresh sequence must not be split by an interrupt (K66 manual 23.3.2).
    __disable_irq();
    WDOG_REFRESH = 0xA602;
    WDOG_REFRESH = 0xB480;
    __enable_irq();
  }

 private:
  uint32_t last_kick_ms_ = 0;
  bool udp_open_ = false;
};

TeensySpi spi_bus;
TeensyI2c i2c_bus;
TeensyDataReady data_ready;
TeensyDac dac;
TeensyAdc adc;
TeensyBoard board;
ff::HapticPipeline pipeline;  // static: two table slots (FF_TABLE_SLOT_BYTES each)
ff::firmware::FirmwareApp app({spi_bus, 0, i2c_bus, data_ready, dac, adc}, board, pipeline);
IntervalTimer tick_timer;

uint32_t micros_for_core() { return micros(); }
// The interrupt's own code in RAM too (docs/cycle-model.md): only
// Teensyduino's pit0_isr and micros() run from flash.
FF_FASTRUN void on_tick() {
  const uint32_t entry = ARM_DWT_CYCCNT;
  app.tick(micros());
  app.note_interrupt_cycles(ARM_DWT_CYCCNT - entry);
}

// The K66's hardware watchdog as the last resort: a main loop that hangs for a
// second resets the MCU (the plate rests from startup_middle_hook on). The
// tick's 50 ms software watchdog has rested the plate long before.
// Teensyduino's startup disables the WDOG but leaves ALLOWUPDATE set, so it
// can be armed here.
constexpr uint32_t kHardwareWatchdogMs = 1000;
void arm_hardware_watchdog() {
  __disable_irq();
  WDOG_UNLOCK = WDOG_UNLOCK_SEQ1;  // then 20 bus clocks to start the update
  WDOG_UNLOCK = WDOG_UNLOCK_SEQ2;
  __asm__ volatile("nop");
  __asm__ volatile("nop");
  // LPO clock (1 kHz), prescaler 1: the timeout is in milliseconds.
  WDOG_TOVALH = static_cast<uint16_t>(kHardwareWatchdogMs >> 16);
  WDOG_TOVALL = static_cast<uint16_t>(kHardwareWatchdogMs & 0xFFFF);
  WDOG_PRESC = 0;
  WDOG_STCTRLH = WDOG_STCTRLH_ALLOWUPDATE | WDOG_STCTRLH_WDOGEN;
  __enable_irq();
}

}  // namespace

// Teensyduino calls this right after analog_init(), ~300 ms before setup()
// (pins_teensy.c _init_Teensyduino_internal_: then 20 ms, usb_init, 280 ms):
// the plate rests from the first millisecond after any reset, whatever the
// AD9834 kept playing.
extern "C" void startup_middle_hook(void) {
  dac0_enable_on_internal_reference();
  dac0_write(ff::firmware::kBootRestCode);
}

void setup() {
  // No Serial.available() from yield(): it would park or drop a binary host packet (yield.cpp).
  yield_active_check_flags &= ~YIELD_CHECK_USB_SERIAL;
  ARM_DEMCR |= ARM_DEMCR_TRCENA;  // DWT cycle counter for the tick's cost
  ARM_DWT_CTRL |= ARM_DWT_CTRL_CYCCNTENA;
  analogReadResolution(pins::kLoadCellAdcBits);
  pinMode(pins::kDdsChipSelect, OUTPUT);
  digitalWriteFast(pins::kDdsChipSelect, HIGH);
  pinMode(pins::kZforceDataReady, INPUT);
  SPI.begin();
  Wire.begin();
  Wire.setClock(kI2cClockHz);
  attachInterrupt(digitalPinToInterrupt(pins::kZforceDataReady), on_data_ready, RISING);
  Ethernet.init(pins::kEthernetChipSelect);
  Ethernet.begin(kMac, kIp);
  Ethernet.setRetransmissionTimeout(ff::firmware::kW5200RetransmissionMs);
  Ethernet.setRetransmissionCount(ff::firmware::kW5200Retries);
  board.open_udp();
  Mouse.screenSize(static_cast<uint16_t>(ff::kScreenWidthPx), static_cast<uint16_t>(ff::kScreenHeightPx));
  pipeline.set_clock(micros_for_core);
  app.begin(micros(), ff::firmware::wiring_calibration());
  // Above USB (112): with the default 128, USB traffic would delay every tick.
  tick_timer.priority(64);
  tick_timer.begin(on_tick, ff::kTickPeriodUs);
  arm_hardware_watchdog();  // last: Ethernet.begin() may take its time
}

void loop() { app.loop(micros()); }
