#include "frictionfield/drivers/ad9834.hpp"

namespace ff {
namespace ad9834 {
namespace {

constexpr uint32_t kMaxMclkHz = 75000000;  // the fastest AD9834 grade; also keeps f 2^28 inside uint64

}  // namespace

uint32_t frequency_word_millihz(uint64_t f_out_mhz, uint32_t mclk_hz, Rounding rounding) {
  if (mclk_hz == 0 || mclk_hz > kMaxMclkHz) return 0;
  const uint64_t denominator = static_cast<uint64_t>(mclk_hz) * 1000u;
  const uint64_t nyquist_mhz = denominator / 2u;
  if (f_out_mhz > nyquist_mhz) f_out_mhz = nyquist_mhz;
  // <= 37.5e9 mHz * 2^28 ~ 1.0e19 < 2^64 = 1.8e19.
  const uint64_t numerator = f_out_mhz << kFrequencyBits;
  const uint64_t word = rounding == Rounding::Nearest ? (numerator + denominator / 2u) / denominator
                                                      : numerator / denominator;
  return word > kFrequencyWordMax ? kFrequencyWordMax : static_cast<uint32_t>(word);
}

uint32_t frequency_word(uint32_t f_out_hz, uint32_t mclk_hz, Rounding rounding) {
  if (mclk_hz == 0 || mclk_hz > kMaxMclkHz) return 0;
  uint64_t f = f_out_hz;
  if (2u * f > mclk_hz) f = mclk_hz / 2u;
  const uint64_t numerator = f << kFrequencyBits;
  const uint64_t word = rounding == Rounding::Nearest ? (numerator + mclk_hz / 2u) / mclk_hz : numerator / mclk_hz;
  return word > kFrequencyWordMax ? kFrequencyWordMax : static_cast<uint32_t>(word);
}

uint64_t output_millihz(uint32_t word, uint32_t mclk_hz) {
  const uint64_t product = static_cast<uint64_t>(word & kFrequencyWordMax) * mclk_hz;  // < 2^60
  const uint64_t low = product & ((uint64_t{1} << kFrequencyBits) - 1u);
  return (product >> kFrequencyBits) * 1000u + ((low * 1000u + (uint64_t{1} << (kFrequencyBits - 1))) >> kFrequencyBits);
}

}  // namespace ad9834

using namespace ad9834;

Ad9834::Ad9834(SpiBus16& spi, uint8_t chip_select, uint32_t mclk_hz)
    : spi_(spi), chip_select_(chip_select), mclk_hz_(mclk_hz) {}

BusStatus Ad9834::write(const uint16_t* words, uint32_t count) {
  const BusStatus s = spi_.write(kSpiConfig, chip_select_, words, count);
  if (s != BusStatus::Ok && bus_errors_ != UINT32_MAX) ++bus_errors_;
  return s;
}

// control_ is what the chip holds: a word is recorded only once it was written
// (after a failed select the chip still plays the other register).
BusStatus Ad9834::write_control(uint16_t control) {
  const uint16_t c = static_cast<uint16_t>(control & ~(kAddressMask | kControlReserved));
  const BusStatus s = write(&c, 1);
  if (s == BusStatus::Ok) control_ = c;
  return s;
}

BusStatus Ad9834::start(uint32_t f_out_hz, bool release) {
  const uint32_t word = frequency_word(f_out_hz, mclk_hz_);
  // Software control (PIN/SW = 0), sine, SIGN BIT OUT off, FREQ0/PHASE0, in reset.
  const uint16_t control = kB28 | kReset;
  const uint16_t words[] = {
      control,
      freq_lsb_word(0, word), freq_msb_word(0, word),
      freq_lsb_word(1, word), freq_msb_word(1, word),  // a stray FSEL plays the same tone
      phase_word(0, 0), phase_word(1, 0),
  };
  const BusStatus s = write(words, sizeof(words) / sizeof(words[0]));
  if (s != BusStatus::Ok) return s;
  control_ = control;
  freq_[0] = freq_[1] = word;
  return release ? release_reset() : BusStatus::Ok;
}

BusStatus Ad9834::release_reset() { return write_control(static_cast<uint16_t>(control_ & ~kReset)); }
BusStatus Ad9834::hold_reset() { return write_control(static_cast<uint16_t>(control_ | kReset)); }

BusStatus Ad9834::set_frequency_word(uint8_t reg, uint32_t word) {
  if (reg > 1 || word > kFrequencyWordMax) return BusStatus::InvalidArgument;
  if ((control_ & kB28) == 0) {
    const BusStatus s = write_control(static_cast<uint16_t>(control_ | kB28));
    if (s != BusStatus::Ok) return s;
  }
  const uint16_t words[] = {freq_lsb_word(reg, word), freq_msb_word(reg, word)};
  const BusStatus s = write(words, 2);
  if (s == BusStatus::Ok) freq_[reg] = word;
  return s;
}

BusStatus Ad9834::set_frequency_lsbs(uint8_t reg, uint32_t word) {
  if (reg > 1 || word > kFrequencyWordMax) return BusStatus::InvalidArgument;
  if ((control_ & (kB28 | kHlb)) != 0) {
    const BusStatus s = write_control(static_cast<uint16_t>(control_ & ~(kB28 | kHlb)));
    if (s != BusStatus::Ok) return s;
  }
  const uint16_t lsb = freq_lsb_word(reg, word);
  const BusStatus s = write(&lsb, 1);
  if (s == BusStatus::Ok) freq_[reg] = (freq_[reg] & ~uint32_t{kHalfMask}) | (word & kHalfMask);
  return s;
}

BusStatus Ad9834::set_phase(uint8_t reg, uint16_t phase) {
  if (reg > 1 || phase > kPhaseWordMax) return BusStatus::InvalidArgument;
  const uint16_t w = phase_word(reg, phase);
  return write(&w, 1);
}

BusStatus Ad9834::select(uint8_t freq_reg, uint8_t phase_reg) {
  if (freq_reg > 1 || phase_reg > 1) return BusStatus::InvalidArgument;
  uint16_t c = static_cast<uint16_t>(control_ & ~(kFsel | kPsel));
  if (freq_reg == 1) c |= kFsel;
  if (phase_reg == 1) c |= kPsel;
  return write_control(c);
}

BusStatus Ad9834::set_power(Power power) {
  uint16_t c = static_cast<uint16_t>(control_ & ~(kSleep1 | kSleep12));
  if (power == Power::ClockStopped || power == Power::Off) c |= kSleep1;
  if (power == Power::DacOff || power == Power::Off) c |= kSleep12;
  return write_control(c);
}

BusStatus Ad9834::set_waveform(Waveform w) {
  // Triangle needs the SIGN BIT OUT pin off (OPBITEN = 0); this driver never enables it.
  uint16_t c = static_cast<uint16_t>(control_ & ~(kMode | kOpbiten));
  if (w == Waveform::Triangle) c |= kMode;
  return write_control(c);
}

}  // namespace ff
