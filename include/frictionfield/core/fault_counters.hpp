#pragma once
// Every kind of bad or unusual input the tick path has seen, counted. Each
// counter saturates instead of wrapping.
#include <cstdint>

namespace ff {

enum class Fault : uint8_t {
  NonFiniteCoordinate,   // NaN or infinite x, y: sample dropped
  OffScreen,             // beyond the screen margin: sample dropped
  NonIncreasingTime,     // duplicate or earlier timestamp: sample dropped
  JumpRejected,          // impossible speed, not confirmed by the next sample
  JumpConfirmed,         // the next sample agreed: tracking restarted there
  StaleSample,           // no sample within the extrapolation horizon: position held
  SensorTimeout,         // no sample for the stale timeout: treated as lift-off
  LiftOff,               // finger gone (touch = 0 then timeout)
  TouchDown,             // finger arrived: tracking restarted without history
  MailboxOverflow,       // samples arrived faster than ticks could take them
  BadStrength,           // strength NaN or outside (0, 1]: repaired
  BadCalibration,        // non-monotonic or out-of-range calibration: linear used
  BadTickTime,           // tick time stood still, ran back or leapt: state repeated until it settles
  SampleTimeImplausible, // report stamped in the future or long past by the tick clock: dropped
  TimeBaseReset,         // the tick clock moved (confirmed leap or step back): finger found again
  BadSensorProfile,      // a sensor profile outside SensorProfileLimits: refused, the tracker unchanged
  kCount
};

const char* to_string(Fault f);

struct FaultCounters {
  uint32_t count[static_cast<int>(Fault::kCount)] = {};

  void add(Fault f) {
    uint32_t& c = count[static_cast<int>(f)];
    if (c != UINT32_MAX) ++c;
  }
  uint32_t operator[](Fault f) const { return count[static_cast<int>(f)]; }
  uint32_t total() const;
};

}  // namespace ff
