// The AD9834 model against the datasheet and AN-1070 by hand: decoding,
// output state, and every sequence the real chip would misread.
#include "frictionfield/emulated/ad9834_model.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace ff::emulated {
namespace {

constexpr SpiConfig kMode2{SpiMode::Mode2, 10000000};

void send(Ad9834Model& m, std::vector<uint16_t> words, SpiConfig c = kMode2) {
  ASSERT_EQ(m.write(c, 0, words.data(), words.size()), BusStatus::Ok);
}

TEST(Ad9834Model, DecodesTheAn1070ExampleTo400HzAt25MHz) {
  // AN-1070: reset, FREQ0 LSB 0x50C7, FREQ0 MSB 0x4000, PHASE0 0, release.
  // FREQREG = 0x10C7 = 4295; 4295 * 25 MHz / 2^28 = 400.0 Hz.
  Ad9834Model m(25000000);
  send(m, {0x2100, 0x50C7, 0x4000, 0xC000, 0x2000});
  EXPECT_EQ(m.frequency_register(0), 4295u);
  EXPECT_TRUE(m.output_on());
  EXPECT_NEAR(m.output_hz(), 400.0, 0.01);
  EXPECT_EQ(m.output_phase(), 0);
  EXPECT_EQ(m.total_faults(), 0u) << m.first_fault();
  EXPECT_EQ(m.words_accepted(), 5u);
}

TEST(Ad9834Model, ResetHoldsTheOutputOffUntilReleased) {
  Ad9834Model m;
  send(m, {0x2100, 0x4000 | 0x27F0, 0x4000 | 0x0007});
  EXPECT_FALSE(m.output_on());
  EXPECT_TRUE(m.in_reset());
  send(m, {0x2000});
  EXPECT_TRUE(m.output_on());
  EXPECT_EQ(m.output_word(), 124912u);  // 0x1E7F0
}

TEST(Ad9834Model, SleepBitsTurnTheOutputOff) {
  Ad9834Model m;
  send(m, {0x2100, 0x4001, 0x4000, 0x2000});
  ASSERT_TRUE(m.output_on());
  send(m, {0x2000 | 0x0040});  // SLEEP12: DAC powered down
  EXPECT_FALSE(m.output_on());
  send(m, {0x2000 | 0x0080});  // SLEEP1: clock stopped
  EXPECT_FALSE(m.output_on());
  send(m, {0x2000});
  EXPECT_TRUE(m.output_on());
}

TEST(Ad9834Model, FselAndPselChooseTheRegisters) {
  Ad9834Model m;
  send(m, {0x2100, 0x4005, 0x4000, 0x8009, 0x8000, 0xC00A, 0xE00B, 0x2000});
  EXPECT_EQ(m.output_word(), 5u);
  EXPECT_EQ(m.output_phase(), 0x00A);
  send(m, {0x2000 | 0x0800 | 0x0400});
  EXPECT_EQ(m.output_word(), 9u);
  EXPECT_EQ(m.output_phase(), 0x00B);
  EXPECT_EQ(m.total_faults(), 0u) << m.first_fault();
}

TEST(Ad9834Model, HlbWritesOneHalfWithoutB28) {
  Ad9834Model m;
  send(m, {0x2100, 0x7FFF, 0x7FFF, 0x2000});  // 0x0FFFFFFF
  send(m, {0x0000, 0x4001});                  // B28 = 0, HLB = 0: LSBs only
  EXPECT_EQ(m.frequency_register(0), 0x0FFFC001u);
  send(m, {0x1000, 0x4002});                  // HLB = 1: MSBs only
  EXPECT_EQ(m.frequency_register(0), (2u << 14) | 1u);
  EXPECT_EQ(m.total_faults(), 0u) << m.first_fault();
}

TEST(Ad9834Model, RejectsWordsOutsideSpiMode2) {
  for (SpiMode mode : {SpiMode::Mode0, SpiMode::Mode1, SpiMode::Mode3}) {
    Ad9834Model m;
    send(m, {0x2100, 0x4001, 0x4000, 0x2000}, SpiConfig{mode, 1000000});
    EXPECT_EQ(m.fault_count(Ad9834Model::Fault::WrongSpiMode), 1u);
    EXPECT_EQ(m.words_accepted(), 0u);
    EXPECT_FALSE(m.output_on());
  }
}

TEST(Ad9834Model, RejectsAClockAbove40MHz) {
  Ad9834Model m;
  send(m, {0x2100}, SpiConfig{SpiMode::Mode2, 50000000});
  EXPECT_EQ(m.fault_count(Ad9834Model::Fault::SclkTooFast), 1u);
}

TEST(Ad9834Model, RejectsAHalfFrequencyWriteWithB28) {
  Ad9834Model m;
  send(m, {0x2100, 0x4001, 0x2000});  // LSBs, then control instead of the MSBs
  EXPECT_EQ(m.fault_count(Ad9834Model::Fault::HalfFrequencyWrite), 1u);
  Ad9834Model n;
  send(n, {0x2100, 0x4001, 0x8000});  // LSBs of FREQ0, "MSBs" to FREQ1
  EXPECT_EQ(n.fault_count(Ad9834Model::Fault::HalfFrequencyWrite), 1u);
  Ad9834Model p;
  send(p, {0x2100, 0x4001, 0xC000});  // a phase write in between
  EXPECT_EQ(p.fault_count(Ad9834Model::Fault::HalfFrequencyWrite), 1u);
}

TEST(Ad9834Model, RejectsReservedBitsTriangleWithSignBitAndPinControl) {
  Ad9834Model m;
  send(m, {0x2104});  // D2
  send(m, {0x2101});  // D0
  send(m, {0xD000});  // PHASE0 with D12
  EXPECT_EQ(m.fault_count(Ad9834Model::Fault::ReservedBitSet), 3u);
  send(m, {0x2000 | 0x0020 | 0x0002});  // OPBITEN with MODE
  EXPECT_EQ(m.fault_count(Ad9834Model::Fault::TriangleWithSignBit), 1u);
  send(m, {0x2000 | 0x0200});
  EXPECT_EQ(m.fault_count(Ad9834Model::Fault::PinControl), 1u);
}

TEST(Ad9834Model, RejectsReleasingResetBeforeTheRegistersAreWritten) {
  Ad9834Model m;
  send(m, {0x2100, 0x2000});
  EXPECT_EQ(m.fault_count(Ad9834Model::Fault::ReleasedUninitialised), 1u);
  EXPECT_FALSE(m.output_on());
}

TEST(Ad9834Model, IgnoresOtherChipSelects) {
  Ad9834Model m(75000000, 3);
  const uint16_t w[] = {0x2100};
  ASSERT_EQ(m.write(kMode2, 0, w, 1), BusStatus::Ok);
  EXPECT_EQ(m.words_accepted(), 0u);
  ASSERT_EQ(m.write(kMode2, 3, w, 1), BusStatus::Ok);
  EXPECT_EQ(m.words_accepted(), 1u);
}

}  // namespace
}  // namespace ff::emulated
