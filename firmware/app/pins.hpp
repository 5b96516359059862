#pragma once
// The Teensy 3.6 pins the firmware uses, in one table, checked at compile
// time against the board's facts (Teensyduino teensy3/pins_arduino.h,
// __MK66FX1M0__): a chip select must not sit on a pin the load cells read,
// and every load cell must sit on an analog input. Change the table to match
// your PCB; the checks keep the mistakes that cost a board out.
#include <cstdint>

namespace ff::firmware::pins {

// Analog inputs of the Teensy 3.6 as digital pin numbers: A0-A9 = 14-23,
// A12-A20 = 31-39, A23-A24 = 49-50 (pins_arduino.h PIN_A*); A10, A11, A21-A22
// (the DACs), A25, A26 are pins 64-69, which are not digital pins.
constexpr bool is_analog_input(uint8_t pin) {
  return (pin >= 14 && pin <= 23) || (pin >= 31 && pin <= 39) || pin == 49 || pin == 50 || (pin >= 64 && pin <= 69);
}
constexpr bool is_digital_pin(uint8_t pin) { return pin <= 57; }  // 0..57 on the Teensy 3.6

// SPI0 (MOSI 11, MISO 12, SCK 13) and Wire (SDA 18, SCL 19) are taken by the buses.
constexpr bool is_bus_pin(uint8_t pin) { return pin == 11 || pin == 12 || pin == 13 || pin == 18 || pin == 19; }

constexpr uint8_t kDdsChipSelect = 10;       // AD9834 FSYNC
constexpr uint8_t kEthernetChipSelect = 9;   // W5200 on the WIZ820io (not 15: that is A1, a load cell)
constexpr uint8_t kZforceDataReady = 2;      // zForce DR: high while a message waits
constexpr int kLoadCellCount = 4;
constexpr uint8_t kLoadCells[kLoadCellCount] = {14, 15, 16, 17};  // A0-A3
constexpr uint8_t kLoadCellAdcBits = 13;     // analogReadResolution: the K66's 16-bit ADC, read at 13 bits
constexpr uint8_t kDac0 = 66;                // A21: DAC0 -> AD9834 FSADJUST

constexpr bool is_load_cell(uint8_t pin) {
  for (uint8_t p : kLoadCells) {
    if (p == pin) return true;
  }
  return false;
}

constexpr bool digital_pin_is_free(uint8_t pin) {
  return is_digital_pin(pin) && !is_bus_pin(pin) && !is_load_cell(pin);
}

constexpr bool load_cells_are_analog_and_distinct() {
  for (int i = 0; i < kLoadCellCount; ++i) {
    if (!is_analog_input(kLoadCells[i]) || is_bus_pin(kLoadCells[i])) return false;
    for (int j = 0; j < i; ++j) {
      if (kLoadCells[i] == kLoadCells[j]) return false;
    }
  }
  return true;
}

static_assert(load_cells_are_analog_and_distinct(), "each load cell needs its own analog input, off the buses");
static_assert(digital_pin_is_free(kDdsChipSelect), "AD9834 FSYNC must be a free digital pin");
static_assert(digital_pin_is_free(kEthernetChipSelect), "W5200 chip select must be a free digital pin");
static_assert(digital_pin_is_free(kZforceDataReady), "zForce DR must be a free digital pin");
static_assert(kDdsChipSelect != kEthernetChipSelect && kDdsChipSelect != kZforceDataReady &&
                  kEthernetChipSelect != kZforceDataReady,
              "one pin, one job");
static_assert(kDac0 == 66, "the AD9834 FSADJUST is driven by DAC0 (A21)");

}  // namespace ff::firmware::pins
