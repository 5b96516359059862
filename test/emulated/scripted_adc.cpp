#include "frictionfield/emulated/scripted_adc.hpp"

namespace ff::emulated {

BusStatus ScriptedAdc::do_read(uint8_t channel, uint16_t& value) {
  ++reads_;
  if (fail_count_ > 0) {
    --fail_count_;
    return fail_status_;
  }
  const std::vector<uint16_t>& s = scripts_[channel];
  if (s.empty()) {
    value = 0;
    return BusStatus::Ok;
  }
  size_t& next = next_[channel];
  value = s[next < s.size() ? next : s.size() - 1];
  if (next < s.size()) ++next;
  const uint32_t full_scale = (1u << bits_) - 1u;
  if (value > full_scale) value = static_cast<uint16_t>(full_scale);
  return BusStatus::Ok;
}

}  // namespace ff::emulated
