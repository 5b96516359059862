#include "frictionfield/emulated/ad9834_model.hpp"

#include <cstdio>

namespace ff::emulated {

const char* Ad9834Model::name(Fault f) {
  switch (f) {
    case Fault::WrongSpiMode: return "wrong SPI mode";
    case Fault::SclkTooFast: return "SCLK too fast";
    case Fault::ReservedBitSet: return "reserved bit set";
    case Fault::HalfFrequencyWrite: return "half frequency write";
    case Fault::TriangleWithSignBit: return "triangle with sign bit out";
    case Fault::PinControl: return "pin control";
    case Fault::ReleasedUninitialised: return "reset released before the registers were written";
    case Fault::kCount: break;
  }
  return "?";
}

uint32_t Ad9834Model::total_faults() const {
  uint32_t n = 0;
  for (uint32_t f : faults_) n += f;
  return n;
}

bool Ad9834Model::output_on() const {
  const int f = (control_ & kFsel) ? 1 : 0;
  return reset_seen_ && halves_[f] == 3 && (control_ & (kReset | kSleep1 | kSleep12)) == 0 &&
         (control_ & kPinSw) == 0;
}

void Ad9834Model::fault(Fault f, uint16_t w) {
  ++faults_[static_cast<int>(f)];
  if (first_fault_.empty()) {
    char b[96];
    std::snprintf(b, sizeof(b), "%s at word %u (0x%04X)", name(f), static_cast<unsigned>(words_ + 1), w);
    first_fault_ = b;
  }
}

void Ad9834Model::note_output() {
  const bool on = output_on();
  if (on && (!was_on_ || output_word() != last_played_)) {
    played_.push_back(output_word());
    last_played_ = output_word();
  }
  was_on_ = on;
}

BusStatus Ad9834Model::do_write(const SpiConfig& config, uint8_t chip_select, const uint16_t* words, size_t count) {
  if (chip_select != chip_select_) return BusStatus::Ok;  // another device's transfer
  if (config.mode != SpiMode::Mode2) {
    fault(Fault::WrongSpiMode, words[0]);
    return BusStatus::Ok;  // the wire cannot tell; the chip latched garbage, modelled as nothing
  }
  if (config.max_clock_hz > 40000000) {
    fault(Fault::SclkTooFast, words[0]);
    return BusStatus::Ok;
  }
  for (size_t i = 0; i < count; ++i) word(words[i]);
  return BusStatus::Ok;
}

void Ad9834Model::word(uint16_t w) {
  const unsigned address = w >> 14;
  if (address == 0) {  // control
    if (w & 0x0005u) {
      fault(Fault::ReservedBitSet, w);
      ++words_;
      return;
    }
    if (pending_lsb_) {
      fault(Fault::HalfFrequencyWrite, w);
      pending_lsb_ = false;
    }
    const bool was_reset = (control_ & kReset) != 0;
    control_ = static_cast<uint16_t>(w & 0x3FFF);
    if (control_ & kReset) reset_seen_ = true;
    if ((control_ & kMode) && (control_ & kOpbiten)) fault(Fault::TriangleWithSignBit, w);
    if (control_ & kPinSw) fault(Fault::PinControl, w);
    if (was_reset && !(control_ & kReset) && halves_[(control_ & kFsel) ? 1 : 0] != 3) {
      fault(Fault::ReleasedUninitialised, w);
    }
  } else if (address == 1 || address == 2) {  // FREQ0, FREQ1
    const int reg = static_cast<int>(address) - 1;
    const uint16_t bits = w & 0x3FFF;
    if (control_ & kB28) {
      if (!pending_lsb_) {
        pending_lsb_ = true;
        pending_reg_ = reg;
        pending_bits_ = bits;
      } else if (pending_reg_ != reg) {
        fault(Fault::HalfFrequencyWrite, w);  // MSBs went to the other register
        pending_reg_ = reg;
        pending_bits_ = bits;
      } else {
        freq_[reg] = (static_cast<uint32_t>(bits) << 14) | pending_bits_;
        halves_[reg] = 3;
        pending_lsb_ = false;
      }
    } else if (control_ & kHlb) {
      freq_[reg] = (freq_[reg] & 0x3FFFu) | (static_cast<uint32_t>(bits) << 14);
      halves_[reg] |= 2;
    } else {
      freq_[reg] = (freq_[reg] & ~0x3FFFu) | bits;
      halves_[reg] |= 1;
    }
  } else {  // PHASE0/1
    if (pending_lsb_) {
      fault(Fault::HalfFrequencyWrite, w);
      pending_lsb_ = false;
    }
    if (w & 0x1000u) {
      fault(Fault::ReservedBitSet, w);
      ++words_;
      return;
    }
    phase_[(w & 0x2000u) ? 1 : 0] = w & 0x0FFFu;
  }
  ++words_;
  note_output();
}

}  // namespace ff::emulated
