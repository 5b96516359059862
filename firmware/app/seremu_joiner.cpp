#include "firmware/app/seremu_joiner.hpp"

#include <cstring>

namespace ff::firmware {

bool SeremuJoiner::push(const uint8_t* data, size_t len, uint32_t now_us, uint8_t* report64) {
  if (have_first_ && now_us - first_us_ > kHalfTimeoutUs) {
    have_first_ = false;
    ++dropped_;
  }
  if (len != kPacketBytes) {  // not half of a report: start over
    dropped_ += have_first_ ? 2u : 1u;
    have_first_ = false;
    return false;
  }
  if (!have_first_) {
    std::memcpy(first_, data, kPacketBytes);
    have_first_ = true;
    first_us_ = now_us;
    return false;
  }
  std::memcpy(report64, first_, kPacketBytes);
  std::memcpy(report64 + kPacketBytes, data, kPacketBytes);
  have_first_ = false;
  return true;
}

}  // namespace ff::firmware
