#include "frictionfield/core/fault_counters.hpp"

namespace ff {

const char* to_string(Fault f) {
  switch (f) {
    case Fault::NonFiniteCoordinate: return "non_finite_coordinate";
    case Fault::OffScreen: return "off_screen";
    case Fault::NonIncreasingTime: return "non_increasing_time";
    case Fault::JumpRejected: return "jump_rejected";
    case Fault::JumpConfirmed: return "jump_confirmed";
    case Fault::StaleSample: return "stale_sample";
    case Fault::SensorTimeout: return "sensor_timeout";
    case Fault::LiftOff: return "lift_off";
    case Fault::TouchDown: return "touch_down";
    case Fault::MailboxOverflow: return "mailbox_overflow";
    case Fault::BadStrength: return "bad_strength";
    case Fault::BadCalibration: return "bad_calibration";
    case Fault::BadTickTime: return "bad_tick_time";
    case Fault::SampleTimeImplausible: return "sample_time_implausible";
    case Fault::TimeBaseReset: return "time_base_reset";
    case Fault::BadSensorProfile: return "bad_sensor_profile";
    case Fault::kCount: break;
  }
  return "?";
}

uint32_t FaultCounters::total() const {
  uint64_t sum = 0;
  for (int i = 0; i < static_cast<int>(Fault::kCount); ++i) sum += (*this)[static_cast<Fault>(i)];
  return sum > UINT32_MAX ? UINT32_MAX : static_cast<uint32_t>(sum);
}

}  // namespace ff
