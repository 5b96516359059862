#pragma once
// Elapsed time from the Cortex-M SysTick, extended past its 24 bits by
// counting wraps in the SysTick exception.
//
// Under qemu with -icount shift=0 every guest instruction advances virtual
// time by exactly 1 ns, and mps2-an386 clocks SysTick (CLKSOURCE = processor
// clock) at its 25 MHz SYSCLK: one count = 40 ns = 40 instructions. The
// harness measures that ratio at start-up (calibrate()) instead of trusting it.
#include <cstdint>

namespace ff::m4 {

class SystickCounter {
 public:
  static void start();       // reload 0xFFFFFF, processor clock, wrap interrupt
  static uint64_t counts();  // monotonic counts since start()
  static void on_wrap();     // the SysTick exception handler's job
};

// Runs a loop of known length (2 instructions per pass) and returns
// instructions per SysTick count, rounded; 0 if the loop read no time.
uint32_t calibrate_instructions_per_count();

}  // namespace ff::m4
