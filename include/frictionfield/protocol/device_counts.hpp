#pragma once
// What the firmware counts beside the pipeline's faults, and the touch
// sensor's state, as the Status message carries them (docs/protocol.md).
// Wire order is enum order: append only.
#include <cstdint>

namespace ff::protocol {

enum class DeviceCount : uint8_t {
  ConditionsSet,
  ConditionsRefused,      // a scene that does not fit or fails its checks
  SensorProfilesSet,
  SensorProfilesRefused,  // outside SensorProfileLimits
  TickStalls,             // the tick interrupt stopped: the loop rested the plate
  HidFramesDropped,       // replies or telemetry the USB host channel had no room for
  SensorRestarts,         // zForce configuration started again after it failed
  MouseMovesSkipped,      // the USB host did not poll the mouse
  UdpSendFailures,        // the reply address did not answer ARP
  ForceReadErrors,        // load-cell reads that failed: that reading skipped
  ForceRezeros,           // the zero re-taken while no finger was on the plate
  ForceRezerosRefused,    // over the limit from the tare: something rests on the plate, left visible
  ForcePeriodsMissed,     // readings later than their period (the main loop was busy)
  UdpUnavailable,         // 1: no network chip answered at start-up, so no UDP until reset
  kCount
};

const char* to_string(DeviceCount c);

struct DeviceCounts {
  uint32_t count[static_cast<int>(DeviceCount::kCount)] = {};
  uint32_t& operator[](DeviceCount c) { return count[static_cast<int>(c)]; }
  uint32_t operator[](DeviceCount c) const { return count[static_cast<int>(c)]; }
};

// The zForce driver's state (ZforceState, same order); Unknown: not said (a
// firmware before 1.1, or a device without the sensor).
enum class SensorState : uint8_t { Booting, Configuring, Running, Failed, Unknown };
const char* to_string(SensorState s);

// The zForce driver's counts travel as its ZforceCount order, uninterpreted
// here: up to this many.
constexpr int kMaxSensorCounts = 32;

}  // namespace ff::protocol
