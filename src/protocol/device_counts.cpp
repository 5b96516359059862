#include "frictionfield/protocol/device_counts.hpp"

namespace ff::protocol {

const char* to_string(DeviceCount c) {
  switch (c) {
    case DeviceCount::ConditionsSet: return "conditions_set";
    case DeviceCount::ConditionsRefused: return "conditions_refused";
    case DeviceCount::SensorProfilesSet: return "sensor_profiles_set";
    case DeviceCount::SensorProfilesRefused: return "sensor_profiles_refused";
    case DeviceCount::TickStalls: return "tick_stalls";
    case DeviceCount::HidFramesDropped: return "hid_frames_dropped";
    case DeviceCount::SensorRestarts: return "sensor_restarts";
    case DeviceCount::MouseMovesSkipped: return "mouse_moves_skipped";
    case DeviceCount::UdpSendFailures: return "udp_send_failures";
    case DeviceCount::ForceReadErrors: return "force_read_errors";
    case DeviceCount::ForceRezeros: return "force_rezeros";
    case DeviceCount::ForceRezerosRefused: return "force_rezeros_refused";
    case DeviceCount::ForcePeriodsMissed: return "force_periods_missed";
    case DeviceCount::UdpUnavailable: return "udp_unavailable";
    case DeviceCount::kCount: break;
  }
  return "?";
}

const char* to_string(SensorState s) {
  switch (s) {
    case SensorState::Booting: return "booting";
    case SensorState::Configuring: return "configuring";
    case SensorState::Running: return "running";
    case SensorState::Failed: return "failed";
    case SensorState::Unknown: break;
  }
  return "unknown";
}

}  // namespace ff::protocol
