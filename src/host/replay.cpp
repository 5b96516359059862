#include "frictionfield/host/replay.hpp"

#include <algorithm>
#include <deque>

namespace ff::host {

uint64_t ReplaySummary::rejected_samples() const {
  const uint64_t rejected = uint64_t{faults[Fault::NonFiniteCoordinate]} + faults[Fault::OffScreen] +
                            faults[Fault::NonIncreasingTime] + faults[Fault::JumpRejected] +
                            faults[Fault::MailboxOverflow] + faults[Fault::SampleTimeImplausible];
  return std::min(rejected, samples);
}

namespace {

// Rows with their arrival time: the tick due to take them. A row of a device
// recording that says which tick took it (taken_us) arrives for the tick
// nearest that time, whatever its stamp: the replay then feeds the tracker as
// the device did. Any other row arrives at its stamp, except a row stamped far
// ahead of the rows behind it (a clock glitch, more than kMaxHoldUs), which
// arrives with the next one instead of holding the whole trace back; smaller
// inversions keep docs/spec.md's rule (the tracker then judges the earlier
// stamp). More than kMaxGlitchRun such rows in a row are not glitches but a
// clock that stepped back (a log restarted, two logs joined): they arrive at
// their stamps, and replay() ends where the clock steps back. Monotonic
// traces: the spec exactly.
// Arrivals are worked out backwards over a window of rows; the window looks
// kLookahead rows past the rows it hands out, and a run of glitches carries
// its length over from the rows handed out, so a streamed trace arrives as
// the whole file would.
class ArrivalQueue {
 public:
  explicit ArrivalQueue(const RowSource& source) : source_(source) {}

  // The next row in file order without taking it; false at the end.
  bool peek(TraceRow& row, uint64_t& arrival) {
    if (ready_ == 0 && !refill()) return false;
    row = rows_.front().row;
    arrival = rows_.front().arrival;
    return true;
  }
  // The arrival of the row after the next one; false if there is none. (Past
  // the window's final rows it may still be lowered by a glitch after it.)
  bool peek_second(uint64_t& arrival) const {
    if (rows_.size() < 2) return false;
    arrival = rows_[1].arrival;
    return true;
  }
  void pop() {
    glitch_run_ = rows_.front().glitch ? glitch_run_ + 1 : 0;
    rows_.pop_front();
    --ready_;
  }
  // Drops what is left and counts it (reading the rest of the source).
  uint64_t discard_rest() {
    uint64_t n = rows_.size();
    rows_.clear();
    ready_ = 0;
    TraceRow r;
    while (!ended_ && source_(r)) ++n;
    ended_ = true;
    return n;
  }

 private:
  struct Pending {
    TraceRow row;
    uint64_t arrival;
    bool glitch;  // stamped far ahead of the next row's arrival
  };
  static constexpr size_t kBlock = 4096;
  static constexpr size_t kLookahead = 64;
  static constexpr size_t kMaxGlitchRun = 8;
  static_assert(kMaxGlitchRun < kLookahead, "a run's length must be known before its rows are handed out");

  bool refill() {
    TraceRow r;
    while (!ended_ && rows_.size() < kBlock + kLookahead) {
      if (source_(r)) rows_.push_back({r, r.t_us, false});
      else ended_ = true;
    }
    if (rows_.empty()) return false;
    uint64_t next_arrival = UINT64_MAX;
    for (size_t i = rows_.size(); i-- > 0;) {
      Pending& p = rows_[i];
      p.glitch = p.row.taken_us < 0 && next_arrival != UINT64_MAX && p.row.t_us > next_arrival + kMaxHoldUs;
      if (p.row.taken_us >= 0) p.arrival = nearest_tick_takes(static_cast<uint64_t>(p.row.taken_us));
      else p.arrival = p.glitch ? next_arrival : p.row.t_us;
      next_arrival = p.arrival;
    }
    // A run too long for glitches: the clock stepped back after it.
    for (size_t begin = 0; begin < rows_.size();) {
      size_t end = begin;
      while (end < rows_.size() && rows_[end].glitch) ++end;
      const size_t run = end - begin + (begin == 0 ? glitch_run_ : 0);
      if (run > kMaxGlitchRun)
        for (size_t i = begin; i < end; ++i) rows_[i].arrival = rows_[i].row.t_us;
      begin = end == begin ? end + 1 : end;
    }
    ready_ = ended_ ? rows_.size() : rows_.size() - kLookahead;
    return true;
  }

  // On the device a tick's time is micros() in its interrupt, a microsecond or
  // so off the replay's 500 us grid: the tick within half a period takes it.
  static uint64_t nearest_tick_takes(uint64_t taken_us) {
    return taken_us > kTickPeriodUs / 2 ? taken_us - kTickPeriodUs / 2 + 1 : 0;
  }

  static constexpr uint64_t kMaxHoldUs = 20000;
  const RowSource& source_;
  std::deque<Pending> rows_;
  size_t ready_ = 0;       // rows at the front whose arrival is final
  size_t glitch_run_ = 0;  // glitches in a row just before the front
  bool ended_ = false;
};

}  // namespace

ReplaySummary replay(const RowSource& source, HapticPipeline& pipeline, const TickSink& sink,
                     const ReplayOptions& options) {
  ReplaySummary summary;
  ArrivalQueue queue(source);
  TraceRow row;
  uint64_t arrival = 0;
  if (!queue.peek(row, arrival)) return summary;
  // The first tick takes the first row: on a recording, the device's tick that
  // took it (so the ticks fall where the device's fell); else at its arrival,
  // so a first row stamped far ahead cannot skip the rows behind it.
  const uint64_t t0 = row.taken_us >= 0 ? static_cast<uint64_t>(row.taken_us) : arrival;
  uint64_t last_due = t0;  // the latest arrival delivered so far
  size_t last_due_line = row.line;  // its row's file line
  // The device ticks from power-on, so its tracker judges even the first
  // report's stamp by the tick clock: one silent tick before t0 gives the
  // replay's tracker that clock too (a first stamp 100 s ahead is then a
  // glitch, not the time every later report must follow).
  if (t0 >= kTickPeriodUs) pipeline.tick(static_cast<uint32_t>(t0 - kTickPeriodUs));
  // A row, and the one after it, stamped far behind the latest report: the clock stepped back.
  const auto far_behind = [&](uint64_t t) { return t < last_due && last_due - t > options.max_step_back_us; };
  const auto steps_back = [&](uint64_t next_arrival) {
    uint64_t second = 0;
    return far_behind(next_arrival) && queue.peek_second(second) && far_behind(second);
  };
  // A clock fault: the replay ends at the last plausible report.
  bool more = true;
  const auto end_at = [&](uint64_t next_arrival, size_t next_line) {
    summary.time_jump = true;
    summary.time_jump_from_us = last_due;
    summary.time_jump_to_us = next_arrival;
    summary.time_jump_from_line = last_due_line;
    summary.time_jump_to_line = next_line;
    summary.rows_after_time_jump = queue.discard_rest();
    more = false;
  };
  double amplitude_sum = 0.0;
  summary.amplitude_min = 1.0f;
  uint64_t extra_left = options.extra_ticks;
  for (uint64_t k = 0;; ++k) {
    const uint64_t now = t0 + k * kTickPeriodUs;
    if (now < t0) break;  // stamps near 2^64 (the reader refuses them): the tick time wrapped
    // Samples due at or before this tick, in file order; the tracker judges their stamps.
    while (more && (more = queue.peek(row, arrival)) && arrival <= now) {
      if (steps_back(arrival)) {
        end_at(arrival, row.line);
        break;
      }
      pipeline.post_sample({static_cast<uint32_t>(row.t_us), row.x, row.y, row.touch});
      ++summary.samples;
      if (arrival >= last_due) {
        last_due = arrival;
        last_due_line = row.line;
      }
      queue.pop();
    }
    if (more && arrival > last_due && arrival - last_due > options.max_gap_us) end_at(arrival, row.line);
    const TickOutput out = pipeline.tick(static_cast<uint32_t>(now));
    ++summary.ticks;
    summary.ticks_with_finger += out.present ? 1 : 0;
    summary.amplitude_min = std::min(summary.amplitude_min, out.amplitude);
    summary.amplitude_max = std::max(summary.amplitude_max, out.amplitude);
    amplitude_sum += static_cast<double>(out.amplitude);
    if (sink) sink(now, out);
    // The tick at or after the last sample and every report taken (a tick
    // takes one at most), then the extra ticks.
    if (!more && now >= last_due && pipeline.samples_taken() == pipeline.samples_posted()) {
      if (extra_left == 0) break;
      --extra_left;
    }
  }
  summary.amplitude_mean = static_cast<float>(amplitude_sum / static_cast<double>(summary.ticks));
  summary.faults = pipeline.faults();
  return summary;
}

ReplaySummary replay(const std::vector<TraceRow>& rows, HapticPipeline& pipeline, const TickSink& sink,
                     uint64_t extra_ticks) {
  size_t next = 0;
  const RowSource source = [&](TraceRow& r) {
    if (next == rows.size()) return false;
    r = rows[next++];
    return true;
  };
  ReplayOptions options;
  options.extra_ticks = extra_ticks;
  return replay(source, pipeline, sink, options);
}

}  // namespace ff::host
