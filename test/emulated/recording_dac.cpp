#include "frictionfield/emulated/recording_dac.hpp"

namespace ff::emulated {

std::vector<uint16_t> RecordingDac::codes() const {
  std::vector<uint16_t> c;
  c.reserve(writes_.size());
  for (const Write& w : writes_) c.push_back(w.code);
  return c;
}

BusStatus RecordingDac::do_write(uint16_t code) {
  if (fail_count_ > 0) {
    --fail_count_;
    return fail_status_;
  }
  writes_.push_back({clock_ ? clock_->now_us() : 0u, code});
  return BusStatus::Ok;
}

}  // namespace ff::emulated
