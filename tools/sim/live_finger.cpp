#include "live_finger.hpp"

#include <cmath>
#include <cstdio>

namespace ff::sim {

bool parse_finger_datagram(const std::string& text, FingerState& out, std::string& error) {
  std::string t = text;
  while (!t.empty() && (t.back() == '\n' || t.back() == '\r' || t.back() == ' ')) t.pop_back();
  if (t == "up") {
    out = FingerState{};
    return true;
  }
  float x = 0, y = 0, f = 0;
  char extra = 0;
  if (std::sscanf(t.c_str(), "%f %f %f %c", &x, &y, &f, &extra) != 3 || !std::isfinite(x) || !std::isfinite(y) ||
      !std::isfinite(f) || f < 0.0f) {
    error = "finger datagram '" + t.substr(0, 40) + "': expected 'x y force_N' or 'up'";
    return false;
  }
  out = {true, x, y, f};
  return true;
}

void LiveFinger::step(uint64_t now_us, emulated::ZforceModel& zforce) {
  if (next_report_us_ == 0) next_report_us_ = now_us;
  while (next_report_us_ <= now_us) {
    const uint32_t t = static_cast<uint32_t>(next_report_us_);
    next_report_us_ += kReportPeriodUs;
    uint8_t id = 0, event = 0;
    if (finger_.down) {
      zforce.to_sensor(finger_.x, finger_.y, last_x_, last_y_);
      event = reported_down_ ? 1 : 0;  // move after the down
      reported_down_ = true;
    } else if (reported_down_) {
      event = 2;  // up, at the last position
      reported_down_ = false;
    } else {
      continue;  // no finger: the sensor is quiet
    }
    zforce.schedule_raw(t, zforce.touch_frame(&id, &event, &last_x_, &last_y_, 1, t));
  }
}

}  // namespace ff::sim
