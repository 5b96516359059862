#include "systick_counter.hpp"

namespace ff::m4 {

namespace {

volatile uint32_t& reg(uintptr_t address) { return *reinterpret_cast<volatile uint32_t*>(address); }
constexpr uintptr_t kSystCsr = 0xE000E010;  // control and status
constexpr uintptr_t kSystRvr = 0xE000E014;  // reload value
constexpr uintptr_t kSystCvr = 0xE000E018;  // current value (counts down)
constexpr uint32_t kEnable = 1u << 0, kTickInt = 1u << 1, kProcessorClock = 1u << 2;
constexpr uint32_t kReload = 0xFFFFFFu;

volatile uint32_t g_wraps = 0;

}  // namespace

void SystickCounter::start() {
  reg(kSystCsr) = 0;
  reg(kSystRvr) = kReload;
  reg(kSystCvr) = 0;  // any write clears the counter: it reloads on the next clock
  g_wraps = 0;
  reg(kSystCsr) = kEnable | kTickInt | kProcessorClock;
}

void SystickCounter::on_wrap() { g_wraps = g_wraps + 1; }

uint64_t SystickCounter::counts() {
  // Re-read if a wrap was handled in between, so wraps and value agree.
  uint32_t wraps, value;
  do {
    wraps = g_wraps;
    value = reg(kSystCvr);
  } while (wraps != g_wraps);
  return static_cast<uint64_t>(wraps) * (kReload + 1u) + (kReload - value);
}

uint32_t calibrate_instructions_per_count() {
  constexpr uint32_t kPasses = 1000000;  // 2 million instructions
  const uint64_t before = SystickCounter::counts();
  uint32_t n = kPasses;
  asm volatile(
      "1: subs %0, %0, #1\n"
      "   bne 1b\n"
      : "+r"(n)
      :
      : "cc");
  const uint64_t elapsed = SystickCounter::counts() - before;
  if (elapsed == 0) return 0;
  return static_cast<uint32_t>((2u * static_cast<uint64_t>(kPasses) + elapsed / 2u) / elapsed);
}

}  // namespace ff::m4
