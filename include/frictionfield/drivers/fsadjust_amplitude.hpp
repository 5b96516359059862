#pragma once
// The carrier's amplitude: the DAC drives the AD9834's FSADJUST pin, which
// sets the full-scale output current. The calibration from normalised
// amplitude to DAC code is the core's DacCalibration, increasing (default) or
// decreasing (DacCalibration::inverted(): more volts on FSADJUST, less
// current, as in Analog Devices' circuit note).
#include <cstdint>

#include "frictionfield/bus/dac.hpp"
#include "frictionfield/core/amplitude_map.hpp"

namespace ff {

class FsAdjustAmplitude {
 public:
  // An invalid calibration is replaced by DacCalibration::linear() and
  // reported by calibration_repaired().
  FsAdjustAmplitude(Dac12& dac, const DacCalibration& calibration);

  BusStatus set_amplitude(float amplitude);  // [0, 1]; NaN -> 0
  BusStatus write_code(uint16_t code);       // a code already mapped (the pipeline's TickOutput::dac)
  BusStatus silence() { return set_amplitude(0.0f); }

  uint16_t code_for(float amplitude) const { return calibration_.code_for(amplitude); }
  uint16_t last_code() const { return last_code_; }
  bool calibration_repaired() const { return repaired_; }
  uint32_t bus_errors() const { return bus_errors_; }

 private:
  Dac12& dac_;
  DacCalibration calibration_;
  uint16_t last_code_ = 0;
  uint32_t bus_errors_ = 0;
  bool repaired_ = false;
};

}  // namespace ff
