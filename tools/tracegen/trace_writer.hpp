#pragma once
// Writes generated traces in the sensor-trace format of docs/spec.md#sensor-trace, with the ground
// truth as extra columns readers ignore, and the truth at every 500 us tick.
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <string>

#include "support/models/sensor_model.hpp"

namespace ff::tracegen {

// A number as the trace files write it: shortest of %.3f without trailing
// zeros; nan, inf, -inf spelled so that strtof reads them back.
std::string format_number(double v);

// `t_us,x,y,touch,x_true,y_true[,x_tremor,y_tremor][,event]`: x_true, y_true
// the voluntary motion, x_tremor, y_tremor (only with tremor) the tremor's
// displacement on top of it at t_us.
void write_trace(std::ostream& out, const GeneratedTrace& trace, bool with_events);

using Progress = std::function<void(double fraction)>;

// `t_us,x_true,y_true,vx_true,vy_true,touch` at t0 + k * 500 us from the first
// report to the tick at or after the last one (docs/spec.md#tick-timing).
// vx, vy in px/s; x_true, y_true nan while lifted; with tremor also
// x_tremor, y_tremor. Returns the rows written.
uint64_t write_truth_ticks(std::ostream& out, const GeneratedTrace& trace, const Progress& progress = {});

}  // namespace ff::tracegen
