#pragma once
// The finger the experiment program (or a person's mouse) sends to ff-sim as
// datagrams, turned into what the zForce would report: a touch notification
// every 5 ms (the sensor's 200 Hz) at the latest position while the finger
// is down, one "up" after it lifts, and the force on the load cells.
#include <cstdint>
#include <string>

#include "frictionfield/emulated/zforce_model.hpp"

namespace ff::sim {

struct FingerState {
  bool down = false;
  float x = 0.0f, y = 0.0f;  // screen pixels, 800 x 480, y down
  float force_N = 0.0f;
};

// "x y force_N" (finger down) or "up". False with a message for anything else.
bool parse_finger_datagram(const std::string& text, FingerState& out, std::string& error);

class LiveFinger {
 public:
  static constexpr uint32_t kReportPeriodUs = 5000;
  void set(const FingerState& f) { finger_ = f; }
  const FingerState& state() const { return finger_; }
  // Schedules the reports due up to now_us.
  void step(uint64_t now_us, emulated::ZforceModel& zforce);

 private:
  FingerState finger_;
  bool reported_down_ = false;
  uint64_t next_report_us_ = 0;
  uint32_t last_x_ = 0, last_y_ = 0;
};

}  // namespace ff::sim
