#pragma once
// Every kind of bad or unusual input the tick path has seen, counted. Each
// counter saturates instead of wrapping. One context writes a set (the tick
// the tracker's, the main loop its own) while the other may read it: every
// access to a live set is a relaxed atomic word access (a plain LDR/STR on
// the M4, so no cost), and a reader takes a snapshot().
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

  void add(Fault f) {  // the set's one writer
    uint32_t* c = &count[static_cast<int>(f)];
    const uint32_t n = __atomic_load_n(c, __ATOMIC_RELAXED);
    if (n != UINT32_MAX) __atomic_store_n(c, n + 1, __ATOMIC_RELAXED);
  }
  uint32_t operator[](Fault f) const { return __atomic_load_n(&count[static_cast<int>(f)], __ATOMIC_RELAXED); }
  // A copy that is safe to take while the writer runs (each counter whole).
  FaultCounters snapshot() const {
    FaultCounters s;
    for (int i = 0; i < static_cast<int>(Fault::kCount); ++i) s.count[i] = __atomic_load_n(&count[i], __ATOMIC_RELAXED);
    return s;
  }
  uint32_t total() const;
};

}  // namespace ff
