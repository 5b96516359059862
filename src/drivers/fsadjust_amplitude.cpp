#include "frictionfield/drivers/fsadjust_amplitude.hpp"

#include "frictionfield/core/fastrun.hpp"

namespace ff {

FsAdjustAmplitude::FsAdjustAmplitude(Dac12& dac, const DacCalibration& calibration)
    : dac_(dac), calibration_(calibration) {
  if (!calibration_.valid()) {
    calibration_ = DacCalibration::linear();
    repaired_ = true;
  }
}

BusStatus FsAdjustAmplitude::set_amplitude(float amplitude) { return write_code(calibration_.code_for(amplitude)); }

FF_FASTRUN BusStatus FsAdjustAmplitude::write_code(uint16_t code) {
  const BusStatus s = dac_.write(code);
  if (s == BusStatus::Ok) {
    last_code_ = code;
  } else if (bus_errors_ != UINT32_MAX) {
    ++bus_errors_;
  }
  return s;
}

}  // namespace ff
