#pragma once
// ARM semihosting, the few calls the harness needs (bkpt 0xAB, operation in
// r0, argument in r1): qemu's -semihosting-config enable=on serves them.
#include <cstddef>
#include <cstdint>

namespace ff::m4 {

void write_text(const char* text);           // SYS_WRITE0 (NUL-terminated)
// The command line the harness was started with (SYS_GET_CMDLINE); empty if none.
bool command_line(char* buffer, size_t capacity);
[[noreturn]] void exit_success();            // SYS_EXIT, ADP_Stopped_ApplicationExit: qemu exits 0
[[noreturn]] void exit_failure();            // SYS_EXIT, run-time error: qemu exits 1

// Small line builder: text and integers only (no printf, no double).
class Line {
 public:
  Line& text(const char* s);
  Line& number(int64_t v);
  Line& field(const char* s) { return comma().text(s); }
  Line& field(int64_t v) { return comma().number(v); }
  void print();  // appends '\n', writes, clears

 private:
  Line& comma();
  char buffer_[256] = {};
  size_t used_ = 0;
  bool first_ = true;
};

}  // namespace ff::m4
