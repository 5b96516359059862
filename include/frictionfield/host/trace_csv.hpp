#pragma once
// Trace files (docs/spec.md#trace-files): sensor traces in, replay output out.
// Host only: std::string and streams are fine here.
#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

#include "frictionfield/core/haptic_pipeline.hpp"

namespace ff::host {

struct TraceRow {
  uint64_t t_us = 0;  // may exceed 2^32; the device sees the low 32 bits
  float x = 0.0f;
  float y = 0.0f;
  bool touch = false;
};

struct TraceError {
  size_t line = 0;    // 1-based; 0 when the file could not be read at all
  size_t column = 0;  // 1-based field number
  std::string message;
  std::string to_string(const std::string& file) const;  // "file:line:column: message"
};

// Reads `t_us,x,y,touch` (any column order, extra columns ignored). Coordinates
// may be nan/inf (the tracker must cope); t_us and touch must be integers.
bool read_sensor_trace(std::istream& in, std::vector<TraceRow>& rows, TraceError& error);
bool read_sensor_trace_file(const std::string& path, std::vector<TraceRow>& rows, TraceError& error);

// Replay output: `t_us,x,y,vx,vy,amplitude,dac`.
void write_replay_header(std::ostream& out);
void write_replay_row(std::ostream& out, uint64_t t_us, const TickOutput& tick);

}  // namespace ff::host
