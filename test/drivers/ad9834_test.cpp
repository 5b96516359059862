// AD9834 driver: frequency words by hand (docs/spec.md#dac: 34.9 kHz both ways), the
// exact SPI words of the start-up (replayed), and every operation through the
// emulated chip, which must never see a word it would misread.
#include "frictionfield/drivers/ad9834.hpp"

#include <gtest/gtest.h>

#include <string>

#include "frictionfield/emulated/ad9834_model.hpp"
#include "frictionfield/emulated/replay_mocks.hpp"

namespace ff {
namespace {

using emulated::Ad9834Model;
using emulated::MockSpiBus16;
using emulated::SpiTransaction;

TEST(Ad9834Word, SpecCarrierRoundsToNearest) {
  // 34900 * 2^28 / 75e6 = 124911.97: nearest 124912 = 0x1E7F0.
  const uint32_t w = ad9834::frequency_word(34900);
  EXPECT_EQ(w, 124912u);
  EXPECT_EQ(ad9834::freq_lsb_word(0, w), 0x67F0);
  EXPECT_EQ(ad9834::freq_msb_word(0, w), 0x4007);
  EXPECT_EQ(ad9834::output_millihz(w), 34900010u);  // 34900.0096 Hz: 0.0096 Hz off
}

TEST(Ad9834Word, TruncationReproducesTheLinuxDriver) {
  // ad9834_calc_freqreg: (u64)fout << 28 / mclk = 124911 = 0x1E7EF; words 0x67EF, 0x4007 (docs/spec.md#dac).
  const uint32_t w = ad9834::frequency_word(34900, ad9834::kMclkHz, ad9834::Rounding::Truncate);
  EXPECT_EQ(w, 124911u);
  EXPECT_EQ(ad9834::freq_lsb_word(0, w), 0x67EF);
  EXPECT_EQ(ad9834::freq_msb_word(0, w), 0x4007);
  EXPECT_EQ(ad9834::output_millihz(w), 34899730u);  // 0.27 Hz low
}

TEST(Ad9834Word, EdgesAndOtherUnits) {
  EXPECT_EQ(ad9834::frequency_word(0), 0u);
  EXPECT_EQ(ad9834::frequency_word(1), 4u);  // 3.58 steps
  EXPECT_EQ(ad9834::frequency_word(1, ad9834::kMclkHz, ad9834::Rounding::Truncate), 3u);
  EXPECT_EQ(ad9834::frequency_word(37500000), 1u << 27);  // MCLK / 2
  EXPECT_EQ(ad9834::frequency_word(40000000), 1u << 27);  // above Nyquist: clamped
  EXPECT_EQ(ad9834::frequency_word(400, 25000000), 4295u);  // AN-1070's 0x10C7
  EXPECT_EQ(ad9834::frequency_word(1000, 0), 0u);           // no clock: no tone
  EXPECT_EQ(ad9834::frequency_word_millihz(1000000, 0), 0u);
  EXPECT_EQ(ad9834::frequency_word_millihz(1000000, 75000001), 0u);  // no AD9834 runs that fast
  EXPECT_EQ(ad9834::frequency_word(1000, 75000001), 0u);
  EXPECT_EQ(ad9834::frequency_word_millihz(34900000), 124912u);
  EXPECT_EQ(ad9834::frequency_word_millihz(34900500), 124914u);  // 124913.76
  EXPECT_EQ(ad9834::output_millihz(1u << 27), 37500000000u);
}

TEST(Ad9834, StartUpWordsAreResetRegistersRelease) {
  MockSpiBus16 spi({
      {SpiMode::Mode2, 4, {0x2100, 0x67F0, 0x4007, 0xA7F0, 0x8007, 0xC000, 0xE000}, BusStatus::Ok},
      {SpiMode::Mode2, 4, {0x2000}, BusStatus::Ok},
  });
  Ad9834 dds(spi, 4);
  EXPECT_EQ(dds.start(34900), BusStatus::Ok);
  std::string why;
  EXPECT_TRUE(spi.finished(&why)) << why;
  EXPECT_EQ(dds.control(), 0x2000);
}

TEST(Ad9834, StartUpThroughTheChip) {
  Ad9834Model chip;
  Ad9834 dds(chip, 0);
  ASSERT_EQ(dds.start(34900, false), BusStatus::Ok);
  EXPECT_TRUE(chip.in_reset());
  EXPECT_FALSE(chip.output_on());
  ASSERT_EQ(dds.release_reset(), BusStatus::Ok);
  EXPECT_TRUE(chip.output_on());
  EXPECT_EQ(chip.output_word(), 124912u);
  EXPECT_NEAR(chip.output_hz(), 34900.0096, 1e-3);
  EXPECT_EQ(chip.output_phase(), 0);
  EXPECT_FALSE(chip.triangle());
  EXPECT_EQ(chip.total_faults(), 0u) << chip.first_fault();
}

TEST(Ad9834, SleepStatesAndOutputOff) {
  Ad9834Model chip;
  Ad9834 dds(chip, 0);
  ASSERT_EQ(dds.start(34900), BusStatus::Ok);
  dds.set_output_enabled(false);
  EXPECT_FALSE(chip.output_on());
  EXPECT_EQ(chip.control() & 0x00C0, 0x0040);  // SLEEP12
  dds.set_power(Ad9834::Power::ClockStopped);
  EXPECT_EQ(chip.control() & 0x00C0, 0x0080);  // SLEEP1
  dds.set_power(Ad9834::Power::Off);
  EXPECT_EQ(chip.control() & 0x00C0, 0x00C0);
  dds.set_output_enabled(true);
  EXPECT_TRUE(chip.output_on());
  dds.hold_reset();
  EXPECT_FALSE(chip.output_on());
  dds.release_reset();
  EXPECT_TRUE(chip.output_on());
  EXPECT_EQ(chip.total_faults(), 0u) << chip.first_fault();
}

TEST(Ad9834, SelectsBetweenTheRegisters) {
  Ad9834Model chip;
  Ad9834 dds(chip, 0);
  ASSERT_EQ(dds.start(34900), BusStatus::Ok);
  ASSERT_EQ(dds.set_frequency_hz(1, 25000), BusStatus::Ok);
  ASSERT_EQ(dds.set_phase(1, 1024), BusStatus::Ok);  // 90 degrees
  EXPECT_EQ(chip.output_word(), 124912u);            // FREQ1 written while FREQ0 plays
  ASSERT_EQ(dds.select(1, 1), BusStatus::Ok);
  EXPECT_EQ(chip.output_word(), ad9834::frequency_word(25000));
  EXPECT_EQ(chip.output_phase(), 1024);
  EXPECT_EQ(dds.selected_frequency(), 1);
  EXPECT_EQ(chip.total_faults(), 0u) << chip.first_fault();
}

TEST(Ad9834, LsbOnlyWriteUsesHlbWithoutB28) {
  Ad9834Model chip;
  Ad9834 dds(chip, 0);
  ASSERT_EQ(dds.start(34900), BusStatus::Ok);
  ASSERT_EQ(dds.set_frequency_lsbs(0, 124912u + 5u), BusStatus::Ok);
  EXPECT_EQ(chip.output_word(), 124917u);
  EXPECT_EQ(chip.control() & ad9834::kB28, 0);
  ASSERT_EQ(dds.set_frequency_word(0, 124912u), BusStatus::Ok);  // B28 back on first
  EXPECT_EQ(chip.output_word(), 124912u);
  EXPECT_EQ(chip.total_faults(), 0u) << chip.first_fault();
}

TEST(Ad9834, AnLsbWriteKeepsTheMsbsInTheDriversCopy) {
  Ad9834Model chip;
  Ad9834 dds(chip, 0);
  ASSERT_EQ(dds.start(34900), BusStatus::Ok);  // 124912 = 0x1E7F0
  ASSERT_EQ(dds.set_frequency_lsbs(0, 5u), BusStatus::Ok);
  EXPECT_EQ(dds.frequency_word_of(0), 0x1C005u);  // the upper 14 bits 0x1C000 stay
  EXPECT_EQ(chip.output_word(), 0x1C005u);
  EXPECT_EQ(dds.frequency_word_of(1), 124912u);
}

TEST(Ad9834, ABadLsbWriteSendsNothing) {
  MockSpiBus16 spi({});
  Ad9834 dds(spi, 0);
  EXPECT_EQ(dds.set_frequency_lsbs(2, 1), BusStatus::InvalidArgument);
  EXPECT_EQ(dds.set_frequency_lsbs(0, 1u << 28), BusStatus::InvalidArgument);
  std::string why;
  EXPECT_TRUE(spi.finished(&why)) << why;
}

TEST(Ad9834, TriangleAndArgumentChecks) {
  Ad9834Model chip;
  Ad9834 dds(chip, 0);
  ASSERT_EQ(dds.start(1000), BusStatus::Ok);
  ASSERT_EQ(dds.set_waveform(Ad9834::Waveform::Triangle), BusStatus::Ok);
  EXPECT_TRUE(chip.triangle());
  EXPECT_EQ(dds.set_phase(0, 4096), BusStatus::InvalidArgument);
  EXPECT_EQ(dds.set_frequency_word(0, 1u << 28), BusStatus::InvalidArgument);
  EXPECT_EQ(dds.set_frequency_word(2, 1), BusStatus::InvalidArgument);
  EXPECT_EQ(dds.select(0, 2), BusStatus::InvalidArgument);
  EXPECT_EQ(chip.total_faults(), 0u) << chip.first_fault();
}

// The chip behind a bus whose next `fail_next` writes time out without reaching it.
class FlakySpi final : public SpiBus16 {
 public:
  explicit FlakySpi(SpiBus16& chip) : chip_(chip) {}
  uint32_t fail_next = 0;

 private:
  BusStatus do_write(const SpiConfig& config, uint8_t chip_select, const uint16_t* words, size_t count) override {
    if (fail_next > 0) {
      --fail_next;
      return BusStatus::Timeout;
    }
    return chip_.write(config, chip_select, words, count);
  }
  SpiBus16& chip_;
};

// A select that did not reach the chip selects nothing: the driver still
// names the register the chip plays, so the next word (a sweep's step) goes
// to the other one and never changes the tone while it plays.
TEST(Ad9834, ASelectThatFailsChangesNothing) {
  Ad9834Model chip;
  FlakySpi bus(chip);
  Ad9834 dds(bus, 0);
  ASSERT_EQ(dds.start(34900), BusStatus::Ok);  // FREQ0 plays 124912
  const uint16_t before = dds.control();
  ASSERT_EQ(dds.set_frequency_word(1, 100000u), BusStatus::Ok);
  bus.fail_next = 1;
  EXPECT_EQ(dds.select(1, 0), BusStatus::Timeout);
  EXPECT_EQ(dds.control(), before);
  EXPECT_EQ(dds.selected_frequency(), 0);
  ASSERT_EQ(chip.output_word(), 124912u);
  // The sweep's next step: the register not playing, then select it.
  const uint8_t idle = static_cast<uint8_t>(1u - dds.selected_frequency());
  ASSERT_EQ(dds.set_frequency_word(idle, 100001u), BusStatus::Ok);
  EXPECT_EQ(chip.output_word(), 124912u);  // still the start tone, untouched
  ASSERT_EQ(dds.select(idle, 0), BusStatus::Ok);
  EXPECT_EQ(chip.output_word(), 100001u);
  EXPECT_EQ(dds.bus_errors(), 1u);
  EXPECT_EQ(chip.total_faults(), 0u) << chip.first_fault();
}

// B28 set in a control word that never arrived is not set: the next full
// word writes it first, so the chip takes the two halves as a pair.
TEST(Ad9834, AB28ThatNeverArrivedIsWrittenAgain) {
  Ad9834Model chip;
  FlakySpi bus(chip);
  Ad9834 dds(bus, 0);
  ASSERT_EQ(dds.start(34900), BusStatus::Ok);
  ASSERT_EQ(dds.set_frequency_lsbs(1, 124912u), BusStatus::Ok);  // B28 off on the chip
  ASSERT_EQ(chip.control() & ad9834::kB28, 0);
  bus.fail_next = 1;  // the control word that sets B28 again
  EXPECT_EQ(dds.set_frequency_word(1, 0x2ABCDEu), BusStatus::Timeout);
  EXPECT_EQ(dds.control() & ad9834::kB28, 0);
  ASSERT_EQ(dds.set_frequency_word(1, 0x2ABCDEu), BusStatus::Ok);
  EXPECT_NE(chip.control() & ad9834::kB28, 0);
  EXPECT_EQ(chip.frequency_register(1), 0x2ABCDEu);
  EXPECT_EQ(chip.total_faults(), 0u) << chip.first_fault();
}

// A start-up that failed has not put the chip in reset: the driver does not
// claim it did.
TEST(Ad9834, AStartThatFailsRecordsNoControlWord) {
  Ad9834Model chip;
  FlakySpi bus(chip);
  Ad9834 dds(bus, 0);
  ASSERT_EQ(dds.start(34900), BusStatus::Ok);  // 0x2000: B28, running
  bus.fail_next = 1;
  EXPECT_EQ(dds.start(25000, false), BusStatus::Timeout);
  EXPECT_EQ(dds.control(), 0x2000);
  EXPECT_EQ(dds.control(), chip.control());
}

TEST(Ad9834, CountsBusErrors) {
  MockSpiBus16 spi({{SpiMode::Mode2, 0, {0x2100, 0x4000, 0x4000, 0x8000, 0x8000, 0xC000, 0xE000}, BusStatus::Timeout}});
  Ad9834 dds(spi, 0);
  EXPECT_EQ(dds.start(0), BusStatus::Timeout);
  EXPECT_EQ(dds.bus_errors(), 1u);
}

}  // namespace
}  // namespace ff
