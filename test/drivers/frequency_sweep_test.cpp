// The 25-70 kHz, 30 s resonance chirp: every word by the closed form, played
// glitch-free through the emulated chip.
#include "frictionfield/drivers/frequency_sweep.hpp"

#include <gtest/gtest.h>

#include "frictionfield/emulated/ad9834_model.hpp"

namespace ff {
namespace {

using emulated::Ad9834Model;

// word(t) = w0 + (w1 - w0) t / T, truncated, w0 = 89478 (25 kHz), w1 = 250540 (70 kHz).
uint32_t closed_form(uint32_t t_us) { return 89478u + static_cast<uint32_t>(161062ull * t_us / 30000000ull); }

// The chip behind a bus that can be made to time out.
class FailingSpi final : public SpiBus16 {
 public:
  explicit FailingSpi(SpiBus16& chip) : chip_(chip) {}
  bool failing = false;

 private:
  BusStatus do_write(const SpiConfig& config, uint8_t chip_select, const uint16_t* words, size_t count) override {
    return failing ? BusStatus::Timeout : chip_.write(config, chip_select, words, count);
  }
  SpiBus16& chip_;
};

// The chip started at 34.9 kHz, as the firmware leaves it before a sweep.
class FrequencySweepTest : public ::testing::Test {
 protected:
  void SetUp() override { ASSERT_EQ(dds.start(34900), BusStatus::Ok); }
  Ad9834Model chip;
  FailingSpi bus{chip};
  Ad9834 dds{bus, 0};
  FrequencySweep sweep{dds};
};

TEST_F(FrequencySweepTest, ThesisChirpStepsEveryMillisecond) {
  const uint32_t t0 = 4294000000u;  // the sweep crosses the 32-bit clock wrap
  ASSERT_TRUE(sweep.begin(SweepConfig{}, t0));
  EXPECT_EQ(chip.output_word(), 89478u);
  uint32_t writes = 0;
  SweepStep step;
  for (uint32_t t = 0; t <= 30000000u + 5000u; t += 250u) {
    if (sweep.step(t0 + t, step)) {
      ++writes;
      ASSERT_EQ(step.word, closed_form(step.elapsed_us)) << step.elapsed_us;
      ASSERT_EQ(chip.output_word(), step.word);
    }
  }
  EXPECT_FALSE(sweep.running());
  EXPECT_EQ(writes, 30000u);
  EXPECT_EQ(sweep.steps_written(), 30001u);
  EXPECT_EQ(chip.output_word(), 250540u);
  EXPECT_EQ(step.millihz, ad9834::output_millihz(250540u));
  EXPECT_EQ(sweep.word_at(15000000u), 170009u);  // 47.5 kHz halfway
  // Every word played once, rising, and the chip never saw a half-written word.
  const auto& played = chip.played();
  ASSERT_EQ(played.size(), 30002u);  // the 34.9 kHz start tone, then the sweep
  for (size_t i = 2; i < played.size(); ++i) ASSERT_GT(played[i], played[i - 1]);
  EXPECT_EQ(chip.total_faults(), 0u) << chip.first_fault();
}

TEST_F(FrequencySweepTest, FallingBehindSkipsInsteadOfBursting) {
  ASSERT_TRUE(sweep.begin(SweepConfig{}, 0));
  SweepStep step;
  ASSERT_TRUE(sweep.step(100000, step));  // main loop stalled 100 ms
  EXPECT_EQ(step.word, closed_form(100000));
  EXPECT_FALSE(sweep.step(100000, step));
  EXPECT_FALSE(sweep.step(100999, step));
  EXPECT_TRUE(sweep.step(101000, step));
}

TEST_F(FrequencySweepTest, KeepsToItsScheduleWhenALoopPassIsLate) {
  ASSERT_TRUE(sweep.begin(SweepConfig{}, 0));
  SweepStep step;
  ASSERT_TRUE(sweep.step(1300, step));  // 300 us late: the next is still due at 2000, not 2300
  EXPECT_FALSE(sweep.step(1999, step));
  EXPECT_TRUE(sweep.step(2000, step));
}

TEST_F(FrequencySweepTest, TheLastStepIsDatedAtTheEndAndLandsOnTheStopWord) {
  SweepConfig c;
  c.duration_us = 10000;
  ASSERT_TRUE(sweep.begin(c, 0));
  SweepStep step;
  ASSERT_TRUE(sweep.step(25000, step));  // a loop pass long after the end
  EXPECT_EQ(step.elapsed_us, 10000u);
  EXPECT_EQ(step.word, 250540u);
  EXPECT_FALSE(sweep.running());
  EXPECT_EQ(sweep.word_at(40000u), 250540u) << "past the end: the stop word, not beyond it";
}

TEST_F(FrequencySweepTest, ABeginThatCannotWriteCountsNoSteps) {
  ASSERT_TRUE(sweep.begin(SweepConfig{}, 0));
  SweepStep step;
  ASSERT_TRUE(sweep.step(1000, step));
  ASSERT_EQ(sweep.steps_written(), 2u);
  bus.failing = true;
  EXPECT_FALSE(sweep.begin(SweepConfig{}, 5000));
  EXPECT_FALSE(sweep.running());
  EXPECT_EQ(sweep.steps_written(), 0u);
}

TEST_F(FrequencySweepTest, SweepsDownwardsToo) {
  SweepConfig c;
  c.start_hz = 70000;
  c.stop_hz = 25000;
  c.duration_us = 1000000;
  c.step_interval_us = 10000;
  ASSERT_TRUE(sweep.begin(c, 0));
  SweepStep step;
  for (uint32_t t = 0; t <= 1000000u; t += 10000u) sweep.step(t, step);
  EXPECT_EQ(chip.output_word(), 89478u);
  EXPECT_EQ(sweep.word_at(500000), 250540u - 80531u);  // -161062 / 2
  EXPECT_EQ(chip.total_faults(), 0u) << chip.first_fault();
}

TEST_F(FrequencySweepTest, RefusesUnusableConfigurations) {
  const uint32_t words = chip.words_accepted();
  SweepConfig c;
  c.duration_us = 0;
  EXPECT_FALSE(sweep.begin(c, 0));
  c = SweepConfig{};
  c.step_interval_us = 0;
  EXPECT_FALSE(sweep.begin(c, 0));
  c = SweepConfig{};
  c.stop_hz = 40000000;  // above MCLK / 2
  EXPECT_FALSE(sweep.begin(c, 0));
  EXPECT_EQ(chip.words_accepted(), words);
  SweepStep step;
  EXPECT_FALSE(sweep.step(1000, step));
}

TEST_F(FrequencySweepTest, ARefusedBeginEndsTheSweepBeforeIt) {
  ASSERT_TRUE(sweep.begin(SweepConfig{}, 0));
  SweepStep step;
  ASSERT_TRUE(sweep.step(1000, step));
  SweepConfig bad;
  bad.duration_us = 0;
  EXPECT_FALSE(sweep.begin(bad, 1500));
  EXPECT_FALSE(sweep.step(2000, step)) << "the old sweep must not go on";
  EXPECT_FALSE(sweep.running());
}

}  // namespace
}  // namespace ff
