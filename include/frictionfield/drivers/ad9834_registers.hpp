#pragma once
// The AD9834 DDS register map (Analog Devices datasheet, "Serial interface"
// and "Control register"). Every write is one 16-bit word; D15..D14 select
// the register:
//   00  control     D13 B28, D12 HLB, D11 FSEL, D10 PSEL, D9 PIN/SW,
//                   D8 RESET, D7 SLEEP1, D6 SLEEP12, D5 OPBITEN,
//                   D4 SIGN/PIB, D3 DIV2, D2 reserved 0, D1 MODE, D0 reserved 0
//   01  FREQ0       14 data bits
//   10  FREQ1       14 data bits
//   110 PHASE0      D11..D0 (D12 reserved 0)
//   111 PHASE1      D11..D0
// A 28-bit frequency word goes in as two 14-bit halves: with B28 = 1 two
// consecutive writes to the same FREQ register, LSBs first, then MSBs; with
// B28 = 0 one half only, chosen by HLB (1 = MSBs). Data is clocked on SCLK's
// falling edge with the clock idling high: SPI mode 2.
#include <cstdint>

#include "frictionfield/bus/spi.hpp"

namespace ff::ad9834 {

constexpr uint16_t kAddressMask = 0xC000;
constexpr uint16_t kControl = 0x0000;
constexpr uint16_t kFreq0 = 0x4000;
constexpr uint16_t kFreq1 = 0x8000;
constexpr uint16_t kPhaseMask = 0xE000;
constexpr uint16_t kPhase0 = 0xC000;
constexpr uint16_t kPhase1 = 0xE000;

constexpr uint16_t kB28 = 1u << 13;
constexpr uint16_t kHlb = 1u << 12;
constexpr uint16_t kFsel = 1u << 11;
constexpr uint16_t kPsel = 1u << 10;
constexpr uint16_t kPinSw = 1u << 9;
constexpr uint16_t kReset = 1u << 8;
constexpr uint16_t kSleep1 = 1u << 7;   // internal MCLK stopped: the DAC holds its value
constexpr uint16_t kSleep12 = 1u << 6;  // on-chip DAC powered down: no output current
constexpr uint16_t kOpbiten = 1u << 5;  // SIGN BIT OUT pin enabled
constexpr uint16_t kSignPib = 1u << 4;  // SIGN BIT OUT: 1 = DAC MSB, 0 = comparator
constexpr uint16_t kDiv2 = 1u << 3;     // with SIGN/PIB = 1: 1 = MSB, 0 = MSB/2
constexpr uint16_t kMode = 1u << 1;     // 1 = triangle (needs OPBITEN = 0)
constexpr uint16_t kControlReserved = (1u << 2) | (1u << 0);

constexpr uint32_t kFrequencyBits = 28;
constexpr uint32_t kFrequencyWordMax = (1u << kFrequencyBits) - 1u;
constexpr uint16_t kHalfMask = 0x3FFF;  // 14 bits
constexpr uint16_t kPhaseWordMax = 0x0FFF;  // 12 bits: 2 pi / 4096 per step

constexpr uint32_t kMclkHz = 75000000;  // docs/spec.md#dac: the board's master clock
constexpr uint32_t kMaxSclkHz = 40000000;
constexpr SpiConfig kSpiConfig{SpiMode::Mode2, 10000000};

constexpr uint16_t freq_register(uint8_t index) { return index == 0 ? kFreq0 : kFreq1; }
constexpr uint16_t phase_register(uint8_t index) { return index == 0 ? kPhase0 : kPhase1; }
constexpr uint16_t freq_lsb_word(uint8_t index, uint32_t word) {
  return static_cast<uint16_t>(freq_register(index) | (word & kHalfMask));
}
constexpr uint16_t freq_msb_word(uint8_t index, uint32_t word) {
  return static_cast<uint16_t>(freq_register(index) | ((word >> 14) & kHalfMask));
}
constexpr uint16_t phase_word(uint8_t index, uint16_t phase) {
  return static_cast<uint16_t>(phase_register(index) | (phase & kPhaseWordMax));
}

// FREQREG = f_out 2^28 / MCLK, integer arithmetic only (uint64).
// Nearest is the default: its error is at most half a step (MCLK / 2^29,
// 0.14 Hz at 75 MHz) either way. Truncate reproduces the Linux driver
// (ad9834_calc_freqreg), always low by up to one step (0.28 Hz).
// At 34.9 kHz: exact 124911.97; Nearest 124912 (34900.008 Hz, words 0x67F0
// 0x4007), Truncate 124911 (34899.729 Hz, words 0x67EF 0x4007).
// f_out above MCLK / 2 (Nyquist) is clamped to the word for MCLK / 2.
enum class Rounding : uint8_t { Nearest, Truncate };
uint32_t frequency_word(uint32_t f_out_hz, uint32_t mclk_hz = kMclkHz, Rounding rounding = Rounding::Nearest);
// The same from milli-hertz, for sweeps with sub-hertz steps.
uint32_t frequency_word_millihz(uint64_t f_out_mhz, uint32_t mclk_hz = kMclkHz,
                                Rounding rounding = Rounding::Nearest);
// What a word puts out, in milli-hertz, rounded to nearest: word MCLK / 2^28.
uint64_t output_millihz(uint32_t word, uint32_t mclk_hz = kMclkHz);

}  // namespace ff::ad9834
