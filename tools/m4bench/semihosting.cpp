#include "semihosting.hpp"

namespace ff::m4 {

namespace {

constexpr uint32_t kSysWrite0 = 0x04;
constexpr uint32_t kSysGetCmdline = 0x15;
constexpr uint32_t kSysExit = 0x18;
constexpr uint32_t kApplicationExit = 0x20026;  // ADP_Stopped_ApplicationExit
constexpr uint32_t kRunTimeError = 0x20023;     // ADP_Stopped_RunTimeErrorUnknown

uint32_t call(uint32_t operation, const void* argument) {
  register uint32_t r0 asm("r0") = operation;
  register const void* r1 asm("r1") = argument;
  asm volatile("bkpt 0xAB" : "+r"(r0) : "r"(r1) : "memory");
  return r0;
}

[[noreturn]] void stop(uint32_t reason) {
  // On 32-bit targets SYS_EXIT takes the reason itself in r1, not a pointer.
  call(kSysExit, reinterpret_cast<const void*>(reason));
  for (;;) {
  }
}

}  // namespace

void write_text(const char* text) { call(kSysWrite0, text); }

bool command_line(char* buffer, size_t capacity) {
  struct {
    char* data;
    uint32_t size;
  } block{buffer, static_cast<uint32_t>(capacity)};
  if (capacity == 0) return false;
  buffer[0] = '\0';
  return call(kSysGetCmdline, &block) == 0;
}

void exit_success() { stop(kApplicationExit); }
void exit_failure() { stop(kRunTimeError); }

Line& Line::text(const char* s) {
  while (*s != '\0' && used_ + 2 < sizeof(buffer_)) buffer_[used_++] = *s++;
  return *this;
}

Line& Line::number(int64_t v) {
  char digits[24];
  int n = 0;
  const bool negative = v < 0;
  uint64_t u = negative ? 0u - static_cast<uint64_t>(v) : static_cast<uint64_t>(v);
  do {
    digits[n++] = static_cast<char>('0' + u % 10u);
    u /= 10u;
  } while (u != 0u);
  if (negative) digits[n++] = '-';
  while (n > 0 && used_ + 2 < sizeof(buffer_)) buffer_[used_++] = digits[--n];
  return *this;
}

Line& Line::comma() {
  if (!first_) text(",");
  first_ = false;
  return *this;
}

void Line::print() {
  buffer_[used_++] = '\n';
  buffer_[used_] = '\0';
  write_text(buffer_);
  used_ = 0;
  first_ = true;
}

}  // namespace ff::m4
