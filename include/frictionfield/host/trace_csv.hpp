#pragma once
// Trace files (docs/spec.md#trace-files): sensor traces in, replay output out.
// Host only: std::string and streams are fine here.
//
// Every reader in the project accepts the same shape: an optional UTF-8 BOM,
// lines starting with '#' anywhere (metadata, skipped), a header row naming the
// columns, then one row per line.
#include <cstdint>
#include <iosfwd>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "frictionfield/core/haptic_pipeline.hpp"

namespace ff::host {

// The largest stamp a trace may carry: 2^53 us (285 years), exact in a double
// (numpy, the plots), and far enough below 2^64 that a replay's tick times
// never wrap.
constexpr uint64_t kMaxTraceTimeUs = uint64_t{1} << 53;

struct TraceRow {
  uint64_t t_us = 0;  // may exceed 2^32; the device sees the low 32 bits; at most kMaxTraceTimeUs
  float x = 0.0f;
  float y = 0.0f;
  bool touch = false;
  // The device tick that took the report, from an ffctl recording's taken_us
  // column: -1 where the file has no such column or the firmware did not say.
  int64_t taken_us = -1;
  size_t line = 0;  // the file line it was read from (1-based); 0 when it came from no file
};

struct TraceError {
  size_t line = 0;    // 1-based; 0 when the file could not be read at all
  size_t column = 0;  // 1-based field number
  std::string message;
  std::string to_string(const std::string& file) const;  // "file:line:column: message"
};

// The true finger of a row, when the file carries it (ff-tracegen's x_true,
// y_true, or a motion-capture reference): NaN while lifted or unknown.
struct TruthPoint {
  double x = std::numeric_limits<double>::quiet_NaN();
  double y = std::numeric_limits<double>::quiet_NaN();
};

// Reads `t_us,x,y,touch` row by row (any column order, extra columns ignored),
// so a trace of any length needs constant memory. Coordinates may be nan/inf
// (the tracker must cope); t_us and touch must be integers, and so must
// taken_us where the header names it (-1: not known).
class SensorTraceReader {
 public:
  explicit SensorTraceReader(std::istream& in) : in_(in) {}
  // The header row (after the BOM and '#' lines); false with `error` set.
  bool read_header(TraceError& error);
  // true with the next row; false at the end (error.message empty) or on an error.
  // With `truth`, also the row's x_true, y_true (NaN where absent or not a number).
  // An error in a last line without its end says so: a recording cut short.
  bool next(TraceRow& row, TraceError& error, TruthPoint* truth = nullptr);
  bool has_truth() const { return col_x_true_ >= 0 && col_y_true_ >= 0; }
  // The value of a metadata line before the header, "# key value" (ffctl) or
  // "# key: value" (the other tools); "" where there is none.
  std::string metadata(const std::string& key) const;
  size_t line() const { return line_no_; }
  // A column's index in the header (-1: absent).
  int column(const std::string& name) const;

 private:
  bool next_data_line(std::string& line);
  bool parse_row(const std::string& line, TraceRow& row, TraceError& error, TruthPoint* truth);
  std::istream& in_;
  std::vector<std::string> names_;  // the header's, trimmed
  std::vector<std::string> leading_comments_;  // '#' lines before the header, trimmed (the first 64)
  size_t line_no_ = 0;
  int col_t_ = -1, col_x_ = -1, col_y_ = -1, col_touch_ = -1, col_x_true_ = -1, col_y_true_ = -1, col_taken_ = -1;
  size_t needed_ = 0;
};

// The whole trace at once (small traces, tests).
bool read_sensor_trace(std::istream& in, std::vector<TraceRow>& rows, TraceError& error);
bool read_sensor_trace_file(const std::string& path, std::vector<TraceRow>& rows, TraceError& error);

// Replay output: `t_us,x,y,vx,vy,amplitude,dac,present` (present: a finger was
// tracked at the tick; amplitude alone cannot tell idle from A = 0 with a finger).
void write_replay_header(std::ostream& out);
void write_replay_row(std::ostream& out, uint64_t t_us, const TickOutput& tick);

// Metadata as '#' comment lines, one `# key: value` per pair (newlines in a
// value become spaces so each stays one line).
using Metadata = std::vector<std::pair<std::string, std::string>>;
void write_metadata(std::ostream& out, const Metadata& metadata);

}  // namespace ff::host
