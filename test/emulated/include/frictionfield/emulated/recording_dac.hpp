#pragma once
// A DAC that remembers every code written (and when, if given a clock).
// Failures are injected as in every test double here: fail_next(count, status).
#include <cstdint>
#include <vector>

#include "frictionfield/bus/clock.hpp"
#include "frictionfield/bus/dac.hpp"

namespace ff::emulated {

class RecordingDac final : public Dac12 {
 public:
  explicit RecordingDac(const MonotonicClock* clock = nullptr) : clock_(clock) {}

  struct Write {
    uint32_t t_us;
    uint16_t code;
  };
  const std::vector<Write>& writes() const { return writes_; }
  std::vector<uint16_t> codes() const;
  uint16_t last() const { return writes_.empty() ? 0 : writes_.back().code; }
  // The next `count` writes fail with `status` (nothing recorded).
  void fail_next(uint32_t count, BusStatus status = BusStatus::BusError) {
    fail_count_ = count;
    fail_status_ = status;
  }
  void clear() { writes_.clear(); }

 private:
  BusStatus do_write(uint16_t code) override;

  const MonotonicClock* clock_;
  std::vector<Write> writes_;
  uint32_t fail_count_ = 0;
  BusStatus fail_status_ = BusStatus::Ok;
};

}  // namespace ff::emulated
