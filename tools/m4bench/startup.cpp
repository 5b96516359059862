// Reset and exception handling for qemu mps2-an386 (Cortex-M4F): vector
// table, .data/.bss set-up, FPU on, static constructors, main(), exit
// through semihosting. Our own code; no vendor start-up files.
#include <cstdint>

#include "semihosting.hpp"
#include "systick_counter.hpp"

extern "C" {
extern uint32_t __stack_top;
extern uint32_t __data_start, __data_end, __data_load, __bss_start, __bss_end;
using InitFunction = void (*)();
extern InitFunction __preinit_array_start[], __preinit_array_end[];
extern InitFunction __init_array_start[], __init_array_end[];

int main();
[[noreturn]] void m4bench_reset();
}

namespace {

[[noreturn]] void fault_handler() {
  ff::m4::write_text("M4BENCH FAULT: hard fault or unexpected exception\n");
  ff::m4::exit_failure();
}

void systick_handler() { ff::m4::SystickCounter::on_wrap(); }

void enable_fpu() {
  // CPACR: full access to coprocessors 10 and 11 (the FPU), then make sure
  // the next instruction sees it.
  volatile uint32_t& cpacr = *reinterpret_cast<volatile uint32_t*>(0xE000ED88u);
  cpacr = cpacr | (0xFu << 20);
  asm volatile("dsb\n isb" ::: "memory");
}

using Vector = void (*)();
constexpr int kSystemVectors = 16;
constexpr int kDeviceVectors = 32;  // AN386: 32 external interrupts

}  // namespace

extern "C" [[noreturn]] void m4bench_reset() {
  for (uint32_t *src = &__data_load, *dst = &__data_start; dst < &__data_end;) *dst++ = *src++;
  for (uint32_t* dst = &__bss_start; dst < &__bss_end;) *dst++ = 0;
  enable_fpu();
  for (InitFunction* f = __preinit_array_start; f < __preinit_array_end; ++f) (*f)();
  for (InitFunction* f = __init_array_start; f < __init_array_end; ++f) (*f)();
  if (main() == 0) ff::m4::exit_success();
  ff::m4::exit_failure();
}

// Initial stack pointer, then handlers; everything but reset and SysTick is a fault here.
__attribute__((section(".vectors"), used)) const Vector g_vectors[kSystemVectors + kDeviceVectors] = {
    reinterpret_cast<Vector>(&__stack_top),
    m4bench_reset,
    fault_handler,  // NMI
    fault_handler,  // HardFault
    fault_handler,  // MemManage
    fault_handler,  // BusFault
    fault_handler,  // UsageFault
    nullptr, nullptr, nullptr, nullptr,
    fault_handler,  // SVCall
    fault_handler,  // DebugMonitor
    nullptr,
    fault_handler,  // PendSV
    systick_handler,
    // Device interrupts: none enabled.
    fault_handler, fault_handler, fault_handler, fault_handler, fault_handler, fault_handler,
    fault_handler, fault_handler, fault_handler, fault_handler, fault_handler, fault_handler,
    fault_handler, fault_handler, fault_handler, fault_handler, fault_handler, fault_handler,
    fault_handler, fault_handler, fault_handler, fault_handler, fault_handler, fault_handler,
    fault_handler, fault_handler, fault_handler, fault_handler, fault_handler, fault_handler,
    fault_handler, fault_handler,
};
