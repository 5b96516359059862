#pragma once
// How DAC0 drives the AD9834's full-scale adjust, decided at build time
// because it is soldered: the code that rests the plate must be known
// before any host has sent a calibration, from the first microsecond after
// a reset.
//
// Reference: DAC0 uses the K66's 1.2 V internal reference (DACREF_1, VREF_OUT,
// which Teensyduino's analog_init() always enables), not the 3.3 V supply
// that analogWrite() selects (analog.c analogWriteDAC0). FSADJUST sits at the
// AD9834's 1.2 V reference, so with 3.3 V codes above ~1,490 would drive past
// it; with 1.2 V the whole 12-bit range spans FSADJUST's range, 2.75x finer.
// The load-cell ADC stays on 3.3 V (analogReference() would move both).
//
// Direction: FF_DAC_DECREASING=1 (build flag) for the wiring of Analog
// Devices' circuit note (more DAC volts, less output current: code 4095
// rests the plate); default increasing (code 0 rests it).
#include "frictionfield/core/amplitude_map.hpp"

#ifndef FF_DAC_DECREASING
#define FF_DAC_DECREASING 0
#endif

namespace ff::firmware {

constexpr bool kDacDecreasing = FF_DAC_DECREASING != 0;
// The code that rests the plate before any calibration has arrived.
constexpr uint16_t kBootRestCode = kDacDecreasing ? 4095 : 0;

// The calibration the firmware starts with (a host's condition brings its own).
inline DacCalibration wiring_calibration() {
  return kDacDecreasing ? DacCalibration::inverted() : DacCalibration::linear();
}

}  // namespace ff::firmware
