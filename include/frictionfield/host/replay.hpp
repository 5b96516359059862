#pragma once
// Replays a sensor trace through the 2 kHz pipeline exactly as docs/spec.md#tick-timing times
// it: ticks at t0 + k * 500 us (t0 = first sample), every sample at or before
// a tick delivered before that tick. The firmware's tick, tick for tick.
// Rows arrive in file order: a row stamped more than 20 ms after the next row
// is delivered with it, so one bad stamp cannot hold the trace back.
#include <cstdint>
#include <functional>
#include <vector>

#include "frictionfield/core/haptic_pipeline.hpp"
#include "frictionfield/host/trace_csv.hpp"

namespace ff::host {

struct ReplaySummary {
  uint64_t ticks = 0;
  uint64_t samples = 0;
  uint64_t ticks_with_finger = 0;
  float amplitude_min = 0.0f;
  float amplitude_mean = 0.0f;
  float amplitude_max = 0.0f;
  FaultCounters faults;
};

using TickSink = std::function<void(uint64_t t_us, const TickOutput& out)>;

// Runs to the tick at or after the last sample; `extra_ticks` more let
// time-outs (lift-off, stale sensor) play out.
ReplaySummary replay(const std::vector<TraceRow>& rows, HapticPipeline& pipeline,
                     const TickSink& sink, uint64_t extra_ticks = 0);

}  // namespace ff::host
