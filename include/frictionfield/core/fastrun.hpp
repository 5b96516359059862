#pragma once
// FF_FASTRUN puts a function of the 2 kHz tick's path into RAM on the
// Cortex-M4 (section .fastrun, which Teensyduino's teensy3/mk66fx1m0.ld
// copies into RAM with .data, as its own FASTRUN does): no flash wait states,
// no cache misses after the main loop ran. Empty on the host. The cost is
// RAM (docs/cycle-model.md gives the size); define FF_NO_FASTRUN to keep
// everything in flash.
#if defined(__arm__) && !defined(FF_NO_FASTRUN)
#define FF_FASTRUN __attribute__((section(".fastrun")))
#else
#define FF_FASTRUN
#endif
