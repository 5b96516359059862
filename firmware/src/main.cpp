// frictionfield firmware for the Teensy 3.6 (MK66FX1M0, 180 MHz), built by
// PlatformIO (platformio.ini, env teensy36, USB type USB_HID: absolute mouse
// + serial emulation over HID as the host channel). This file only binds the
// core's bus interfaces and the Board to Teensyduino; everything it runs is
// in firmware/app (tested natively against emulated devices).
// Our headers first: Arduino.h defines macros (bit, min, max, ...) that
// would rewrite the portable code.
#include "firmware/app/firmware_app.hpp"

#include <Arduino.h>
#include <Ethernet.h>
#include <EthernetUdp.h>
#include <IntervalTimer.h>
#include <SPI.h>
#include <Wire.h>

namespace {

// ---- pins (thesis setup) -----------------------------------------------------
constexpr uint8_t kDdsChipSelect = 10;   // AD9834 FSYNC
constexpr uint8_t kZforceDataReady = 2;  // zForce DR: high while a message waits
constexpr uint8_t kLoadCellPins[4] = {A0, A1, A2, A3};
constexpr uint8_t kWiz820ChipSelect = 15;  // second SPI device: the W5200
constexpr uint16_t kUdpPort = 8888;
uint8_t kMac[6] = {0x04, 0xE9, 0xE5, 0x00, 0x00, 0x01};
const IPAddress kIp(192, 168, 1, 177);  // the lab's fixed address; set for your network

// ---- bus interfaces ------------------------------------------------------------

class TeensySpi final : public ff::SpiBus16 {
  ff::BusStatus do_write(const ff::SpiConfig& config, uint8_t cs, const uint16_t* words, size_t count) override {
    const uint8_t mode = config.mode == ff::SpiMode::Mode2 ? SPI_MODE2
                         : config.mode == ff::SpiMode::Mode1 ? SPI_MODE1
                         : config.mode == ff::SpiMode::Mode3 ? SPI_MODE3 : SPI_MODE0;
    SPI.beginTransaction(SPISettings(config.max_clock_hz, MSBFIRST, mode));
    for (size_t i = 0; i < count; ++i) {  // FSYNC framed per 16-bit word
      digitalWriteFast(cs == 0 ? kDdsChipSelect : cs, LOW);
      SPI.transfer16(words[i]);
      digitalWriteFast(cs == 0 ? kDdsChipSelect : cs, HIGH);
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
  bool asserted() const override { return digitalReadFast(kZforceDataReady) == HIGH; }
  bool take_edge(uint32_t& t_us, uint32_t& edges) override { return data_ready_edges.take(t_us, edges); }
};

class TeensyDac final : public ff::Dac12 {
  ff::BusStatus do_write(uint16_t code) override {
    analogWrite(A21, code);  // DAC0 -> AD9834 FSADJUST
    return ff::BusStatus::Ok;
  }
};

class TeensyAdc final : public ff::Adc {
  uint8_t channel_count() const override { return 4; }
  uint8_t resolution_bits() const override { return 13; }
  ff::BusStatus do_read(uint8_t channel, uint16_t& value) override {
    if (channel >= 4) return ff::BusStatus::InvalidArgument;
    value = static_cast<uint16_t>(analogRead(kLoadCellPins[channel]));
    return ff::BusStatus::Ok;
  }
};

// ---- the board --------------------------------------------------------------------

EthernetUDP udp;

class TeensyBoard final : public ff::firmware::Board {
 public:
  void mouse_move_to(int x, int y) override { Mouse.moveTo(x, y); }
  bool udp_receive(uint8_t* buffer, size_t capacity, size_t& size) override {
    const int n = udp.parsePacket();
    if (n <= 0) return false;
    if (static_cast<size_t>(n) > capacity) {  // too long for any message: read and drop
      while (udp.available()) udp.read();
      size = 0;
      return true;  // an empty frame: answered as malformed
    }
    reply_ip_ = udp.remoteIP();
    reply_port_ = udp.remotePort();
    size = static_cast<size_t>(udp.read(buffer, capacity));
    return true;
  }
  void udp_send(const uint8_t* data, size_t size) override {
    if (reply_port_ == 0) return;  // nobody has spoken to us yet
    udp.beginPacket(reply_ip_, reply_port_);
    udp.write(data, size);
    udp.endPacket();
  }
  // Host channel: 64-byte reports carried over the serial emulation (SEREMU).
  bool hid_receive(uint8_t* report) override {
    if (Serial.available() < 64) return false;
    return Serial.readBytes(reinterpret_cast<char*>(report), 64) == 64;
  }
  void hid_send(const uint8_t* report) override { Serial.write(report, 64); }
  uint32_t cycles() override { return ARM_DWT_CYCCNT; }
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
  IPAddress reply_ip_;
  uint16_t reply_port_ = 0;
  uint32_t last_kick_ms_ = 0;
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
void on_tick() { app.tick(micros()); }

// The K66's hardware watchdog as the last resort: a main loop that hangs for a
// second resets the MCU (setup() rests the plate first thing). The tick's 50 ms
// software watchdog has rested the plate long before. Teensyduino's startup
// disables the WDOG but leaves ALLOWUPDATE set, so it can be armed here.
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

void setup() {
  ARM_DEMCR |= ARM_DEMCR_TRCENA;  // DWT cycle counter for the tick's cost
  ARM_DWT_CTRL |= ARM_DWT_CTRL_CYCCNTENA;
  analogWriteResolution(12);
  analogReadResolution(13);
  analogWrite(A21, 0);  // the plate rests from the first microsecond
  pinMode(kDdsChipSelect, OUTPUT);
  digitalWriteFast(kDdsChipSelect, HIGH);
  pinMode(kZforceDataReady, INPUT);
  SPI.begin();
  Wire.begin();
  Wire.setClock(400000);
  attachInterrupt(digitalPinToInterrupt(kZforceDataReady), on_data_ready, RISING);
  Ethernet.init(kWiz820ChipSelect);
  Ethernet.begin(kMac, kIp);
  udp.begin(kUdpPort);
  Mouse.screenSize(800, 480);
  pipeline.set_clock(micros_for_core);
  app.begin(micros());
  // Above USB (112): with the default 128, USB traffic would delay every tick.
  tick_timer.priority(64);
  tick_timer.begin(on_tick, ff::kTickPeriodUs);
  arm_hardware_watchdog();  // last: Ethernet.begin() may take its time
}

void loop() { app.loop(micros()); }
