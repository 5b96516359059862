#pragma once
// Replays a sensor trace through the 2 kHz pipeline exactly as docs/spec.md#tick-timing times
// it: ticks at t0 + k * 500 us (t0 = first sample), every sample at or before
// a tick delivered before that tick. The firmware's tick, tick for tick.
// Rows arrive in file order: a row stamped more than 20 ms after the next row
// is delivered with it, so one bad stamp cannot hold the trace back.
//
// The trace streams through: memory stays bounded whatever its length. A gap
// between reports longer than `max_gap_us` cannot come from a session (a
// clock fault, a corrupt stamp): the replay ends at the last plausible report
// instead of ticking through the gap, and says how many rows it left out.
// So does a clock that steps back (two rows in a row stamped more than
// `max_step_back_us` before the latest report delivered: a log restarted or
// two logs joined), which would otherwise flood the mailbox with every row
// behind the tick clock at once.
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
  // Implausible time jump, forwards or back: the stamp that ended the replay
  // and the rows after it.
  bool time_jump = false;
  uint64_t time_jump_from_us = 0;
  uint64_t time_jump_to_us = 0;
  uint64_t rows_after_time_jump = 0;
  // The file lines of the last report delivered and of the row that ended the
  // replay (TraceRow::line: 0 when the rows came from no file).
  size_t time_jump_from_line = 0;
  size_t time_jump_to_line = 0;

  // Samples the tracker dropped (non-finite, off-screen, time, jumps, overflow).
  uint64_t rejected_samples() const;
};

using TickSink = std::function<void(uint64_t t_us, const TickOutput& out)>;
// Fills the next row; false at the end of the trace.
using RowSource = std::function<bool(TraceRow& row)>;

// ff-replay's step back: more than the 20 ms by which a late-read stamp
// may fall behind the one before (docs/spec.md#tick-timing).
inline constexpr uint64_t kClockStepBackUs = 20000;

struct ReplayOptions {
  uint64_t extra_ticks = 0;             // after the last sample: time-outs play out
  uint64_t max_gap_us = UINT64_MAX;     // a longer gap ends the replay (see above)
  uint64_t max_step_back_us = UINT64_MAX;  // so does a longer step back, twice in a row
};

// Runs to the tick at or after the last sample, plus `extra_ticks`.
ReplaySummary replay(const RowSource& source, HapticPipeline& pipeline, const TickSink& sink,
                     const ReplayOptions& options);
ReplaySummary replay(const std::vector<TraceRow>& rows, HapticPipeline& pipeline,
                     const TickSink& sink, uint64_t extra_ticks = 0);

}  // namespace ff::host
