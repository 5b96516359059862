#pragma once
// An AD9834 as its SPI port sees it: decodes every 16-bit word into the
// control, frequency and phase registers and reports what the output is
// doing. Written independently of the driver, from the datasheet's register
// description, and strict: whatever the real chip would misread or take
// differently from what was evidently meant is rejected and counted.
#include <cstdint>
#include <string>
#include <vector>

#include "frictionfield/bus/spi.hpp"

namespace ff::emulated {

class Ad9834Model final : public SpiBus16 {
 public:
  enum class Fault : uint8_t {
    WrongSpiMode,          // not mode 2: the chip samples on the other edge, words arrive shifted
    SclkTooFast,           // above 40 MHz
    ReservedBitSet,        // control D0/D2 or phase D12 set (must be 0)
    HalfFrequencyWrite,    // B28 pairing broken: MSB half missing, another write between the halves
    TriangleWithSignBit,   // MODE = 1 with OPBITEN = 1 (not allowed)
    PinControl,            // PIN/SW = 1: FSEL/PSEL/RESET/SLEEP bits would be ignored on this board
    ReleasedUninitialised, // RESET released before the selected registers were written
    kCount
  };
  static const char* name(Fault f);

  explicit Ad9834Model(uint32_t mclk_hz = 75000000, uint8_t chip_select = 0)
      : mclk_hz_(mclk_hz), chip_select_(chip_select) {}

  // Register state.
  uint16_t control() const { return control_; }
  uint32_t frequency_register(int i) const { return freq_[i & 1]; }
  uint16_t phase_register(int i) const { return phase_[i & 1]; }
  bool in_reset() const { return (control_ & kReset) != 0; }

  // The output.
  bool output_on() const;  // a sine is coming out
  uint32_t output_word() const { return freq_[(control_ & kFsel) ? 1 : 0]; }
  uint16_t output_phase() const { return phase_[(control_ & kPsel) ? 1 : 0]; }
  double output_hz() const { return static_cast<double>(output_word()) * mclk_hz_ / 268435456.0; }
  bool triangle() const { return (control_ & kMode) != 0; }

  uint32_t fault_count(Fault f) const { return faults_[static_cast<int>(f)]; }
  uint32_t total_faults() const;
  const std::string& first_fault() const { return first_fault_; }
  uint32_t words_accepted() const { return words_; }
  // Output frequency words in the order they started playing (with the output on).
  const std::vector<uint32_t>& played() const { return played_; }

 private:
  static constexpr uint16_t kB28 = 1u << 13, kHlb = 1u << 12, kFsel = 1u << 11, kPsel = 1u << 10,
                            kPinSw = 1u << 9, kReset = 1u << 8, kSleep1 = 1u << 7, kSleep12 = 1u << 6,
                            kOpbiten = 1u << 5, kMode = 1u << 1;

  BusStatus do_write(const SpiConfig& config, uint8_t chip_select, const uint16_t* words, size_t count) override;
  void word(uint16_t w);
  void fault(Fault f, uint16_t w);
  void note_output();

  uint32_t mclk_hz_;
  uint8_t chip_select_;
  uint16_t control_ = 0;
  uint32_t freq_[2] = {0, 0};
  uint16_t phase_[2] = {0, 0};
  uint8_t halves_[2] = {0, 0};  // bit 0: LSBs written since power-up, bit 1: MSBs
  bool reset_seen_ = false;
  bool pending_lsb_ = false;  // B28: LSB half written, MSB half due
  int pending_reg_ = 0;
  uint16_t pending_bits_ = 0;
  uint32_t faults_[static_cast<int>(Fault::kCount)] = {};
  std::string first_fault_;
  uint32_t words_ = 0;
  std::vector<uint32_t> played_;
  bool was_on_ = false;
  uint32_t last_played_ = 0;
};

}  // namespace ff::emulated
