#pragma once
// Named kinds of generated traces: today's white-noise model and the
// realistic fingers and sensors of issue 14, one effect at a time and all
// together, so that the tracking benchmark can report per class and
// ff-tracegen can write any of them (--class).
#include <string>
#include <vector>

#include "frictionfield/core/sensor_profile.hpp"
#include "support/models/sensor_model.hpp"

namespace ff::tracegen {

struct TraceClass {
  const char* name;
  const char* description;
  // Sets the motion effects, the tremor and the sensor; leaves the seed, the
  // strategy, the paths, the duration, rests, lifts and faults alone.
  void (*apply)(TraceOptions& options);
};

const std::vector<TraceClass>& trace_classes();
// nullptr for an unknown name.
const TraceClass* find_trace_class(const std::string& name);

// The profile a perfect calibration would measure on traces with these
// options: the white noise with the quantisation's (q^2/12), the wander, the
// tremor, the rate, the interval's jitter (stamp jitter counts twice, period
// jitter once) and the mean latency. The drift (tau of seconds) is left out.
SensorProfile nominal_profile(const TraceOptions& options);
// The same with the tremor's frequency, drawn per trace, as a calibration of
// that finger measures it (within 0.1 Hz of a generated tremor,
// sensor_calibration_test): what a lab that calibrates each participant has.
SensorProfile nominal_profile(const TraceOptions& options, const GeneratedTrace& trace);
// The nominal profile of a named class's traces (default options otherwise;
// an unknown name aborts); the tests' profile for a sensor with every effect
// is "realistic-200hz"'s.
SensorProfile class_profile(const std::string& class_name);

}  // namespace ff::tracegen
