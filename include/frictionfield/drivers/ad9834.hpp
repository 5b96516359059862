#pragma once
// AD9834 DDS: the ultrasonic carrier. Frequency and phase registers over SPI
// (mode 2), the reset-then-release start-up, sleep states and register
// selection. The amplitude is not here: it is the current set through
// FSADJUST by the DAC (fsadjust_amplitude.hpp).
#include <cstdint>

#include "frictionfield/bus/spi.hpp"
#include "frictionfield/drivers/ad9834_registers.hpp"

namespace ff {

class Ad9834 {
 public:
  enum class Power : uint8_t {
    Running,       // clock and DAC on
    ClockStopped,  // SLEEP1: the phase accumulator stops, the DAC holds a DC level
    DacOff,        // SLEEP12: DAC powered down, no output current (output off)
    Off,           // both
  };
  enum class Waveform : uint8_t { Sine, Triangle };

  Ad9834(SpiBus16& spi, uint8_t chip_select, uint32_t mclk_hz = ad9834::kMclkHz);

  // Start-up as the datasheet and AN-1070 prescribe: control with RESET (and
  // B28), both frequency registers, both phase registers (0), then control
  // with RESET cleared when `release` (output starts at `f_out_hz` from
  // FREQ0/PHASE0). Without `release` the part stays in reset (output at
  // mid-scale) until release_reset().
  BusStatus start(uint32_t f_out_hz, bool release = true);
  BusStatus release_reset();
  BusStatus hold_reset();

  // Both 14-bit halves (B28 pairing), LSBs first. word <= 2^28 - 1.
  BusStatus set_frequency_word(uint8_t reg, uint32_t word);
  BusStatus set_frequency_hz(uint8_t reg, uint32_t f_out_hz) {
    return set_frequency_word(reg, ad9834::frequency_word(f_out_hz, mclk_hz_));
  }
  // Only the 14 LSBs (B28 = 0, HLB = 0): the MSBs must already match.
  BusStatus set_frequency_lsbs(uint8_t reg, uint32_t word);
  BusStatus set_phase(uint8_t reg, uint16_t phase_word);  // 0..4095 = 0..2 pi
  BusStatus select(uint8_t freq_reg, uint8_t phase_reg);
  BusStatus set_power(Power power);
  BusStatus set_output_enabled(bool on) { return set_power(on ? Power::Running : Power::DacOff); }
  BusStatus set_waveform(Waveform w);

  uint16_t control() const { return control_; }  // the last control word the chip took
  uint32_t frequency_word_of(uint8_t reg) const { return freq_[reg & 1u]; }
  uint8_t selected_frequency() const { return (control_ & ad9834::kFsel) != 0 ? 1 : 0; }
  uint8_t selected_phase() const { return (control_ & ad9834::kPsel) != 0 ? 1 : 0; }
  uint32_t mclk_hz() const { return mclk_hz_; }
  uint32_t bus_errors() const { return bus_errors_; }

 private:
  BusStatus write(const uint16_t* words, uint32_t count);
  BusStatus write_control(uint16_t control);

  SpiBus16& spi_;
  uint8_t chip_select_;
  uint32_t mclk_hz_;
  uint16_t control_ = ad9834::kB28 | ad9834::kReset;
  uint32_t freq_[2] = {0, 0};
  uint32_t bus_errors_ = 0;
};

}  // namespace ff
