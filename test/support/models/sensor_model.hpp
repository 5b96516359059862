#pragma once
// The zForce as the Teensy sees it: ~200 Hz reports with timing jitter,
// noise and quantisation, plus every fault the tracker must survive,
// inserted on request at random (seeded) places. On request also what a real
// sensor adds (stamp latency, period jitter, correlated noise, drift) and
// what a real finger adds on top of its voluntary motion (tremor).
#include <cstdint>
#include <string>
#include <vector>

#include "support/models/motion.hpp"
#include "support/models/search_strategy.hpp"
#include "support/models/tremor.hpp"

namespace ff::tracegen {

// What a row is; written as the optional `event` column.
enum class SampleEvent : uint8_t {
  Normal,
  TouchDown,   // first report after the finger lands
  LiftReport,  // touch = 0: the finger left
  AfterGap,    // first report after missing ones
  Late,        // stamped late: position measured up to 12 ms before t_us
  Jump,        // a second finger or a glitch far from the finger
  Duplicate,   // exact copy of the previous row
  SameTime,    // a fresh report with the previous row's timestamp
  Earlier,     // stamped before the previous row (out of order)
  NaN,         // x and/or y not a number
  Infinite,    // x or y infinite
  OffScreen,   // far outside the screen (sensor garbage)
  kCount
};
const char* to_string(SampleEvent e);

struct TraceSample {
  uint64_t t_us = 0;      // file time (may pass 2^32)
  double x = 0.0;         // reported (noisy, quantised, maybe faulty)
  double y = 0.0;
  bool touch = false;
  double x_true = 0.0;    // the finger's voluntary motion at t_us (NaN while lifted; no tremor)
  double y_true = 0.0;
  double latency_us = 0.0;  // how long before t_us the sensor scanned what x, y report
  SampleEvent event = SampleEvent::Normal;
};

// Noise presets: 1 sigma per axis. "~1 mm accuracy" (docs/spec.md#sensor) is 5 px; high
// noise puts 95 % of reports within ~1.2 mm, low within ~0.5 mm.
constexpr double kNoiseLowPx = 1.0;
constexpr double kNoiseHighPx = 2.5;
// zForce coordinates arrive in 0.1 mm units = 0.5 px.
constexpr double kZForceQuantumPx = 0.5;

// Stamp and period jitter are clipped to this share of the period either
// way, so that reports never change order.
constexpr double kJitterClipOfPeriod = 0.3;

struct SensorOptions {
  double rate_hz = 200.0;
  double jitter_us = 150.0;   // 1 sigma, clipped to +-30 % of the period
  double noise_px = kNoiseLowPx;
  double quantum_px = 0.0;    // 0: no quantisation
  double latency_us = 0.0;    // reports describe the finger this long before t_us

  // What a real sensor adds (issue 14), each off by default and drawn from
  // its own random stream, so that the default trace stays exactly as it was.
  double latency_spread_us = 0.0;  // each report's latency: latency_us + uniform(0, spread)
  // The scan interval itself varies (1 sigma, clipped to +-30 % of the
  // period): unlike jitter_us, which scatters stamps around a fixed grid, the
  // errors accumulate and the clock wanders.
  double period_jitter_us = 0.0;
  // Temporally correlated noise: a Gauss-Markov process per axis
  // (gauss_markov.hpp), added to the white noise_px.
  double correlated_noise_px = 0.0;
  double correlated_noise_tau_s = 0.03;
  // Slow drift of the whole coordinate frame: the same process, slower.
  double drift_px = 0.0;
  double drift_tau_s = 10.0;
};

struct FaultOptions {
  int missing = 0;      // gaps of 1-6 reports
  int late = 0;         // reports stamped 1-12 ms late
  int jumps = 0;        // 1-3 reports far away
  int duplicates = 0;   // cycles: exact duplicate, same timestamp, earlier timestamp
  int non_finite = 0;   // NaN / infinite coordinates
  int off_screen = 0;
  bool wrap = false;    // start so that the 32-bit clock wraps in mid-stroke near the middle
  uint64_t start_us = 10'000'000;  // time of the first report unless wrap
};

struct TraceOptions {
  MotionOptions motion;
  TremorOptions tremor;  // part of what the sensor sees, not of the truth
  SensorOptions sensor;
  FaultOptions faults;
  uint64_t seed = 1;
};

struct GeneratedTrace {
  Motion motion;  // the voluntary motion: the truth
  Tremor tremor;  // the involuntary tremor on top of it
  uint64_t start_us = 0;  // file time of motion time 0 (= the first report)
  std::vector<TraceSample> samples;
  int events[static_cast<int>(SampleEvent::kCount)] = {};  // rows of each kind
  // The faults asked for that found a site (each needs ordinary reports
  // around it): fewer than asked when the trace is too short or too busy.
  FaultOptions faults_placed;

  // The true finger at a file time.
  TrueState truth_at(uint64_t t_us) const;
  // The tremor's displacement at a file time (zero without tremor).
  Point tremor_at(uint64_t t_us) const;
  uint64_t end_us() const { return samples.empty() ? start_us : samples.back().t_us; }
};

GeneratedTrace generate_trace(const TraceOptions& options);

}  // namespace ff::tracegen
