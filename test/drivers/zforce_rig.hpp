#pragma once
// The zForce driver wired to the emulated sensor on an emulated I2C bus, with
// helpers to configure it and to run the main loop over a time span.
#include <cstdint>
#include <vector>

#include "frictionfield/drivers/zforce_sensor.hpp"
#include "frictionfield/emulated/i2c_bus.hpp"
#include "frictionfield/emulated/zforce_model.hpp"

namespace ff::test {

struct ZforceRig {
  emulated::ZforceModel model;
  emulated::EmulatedI2cBus bus;
  ZforceSensor sensor;

  explicit ZforceRig(const ZforceConfig& config = ZforceConfig(),
                     const emulated::ZforceModel::Options& options = emulated::ZforceModel::Options(),
                     const ScreenCalibration* model_calibration = nullptr)
      : model(options), sensor(bus, model, config) {
    bus.attach(config.address, model);
    model.set_calibration(model_calibration ? *model_calibration : config.calibration);
  }

  // Boot and configuration, polling every millisecond from `from_us`.
  // Returns the time it reached Running or Failed (or gave up after `limit_us`).
  uint32_t configure(uint32_t from_us = 0, uint32_t limit_us = 2000000) {
    sensor.begin(from_us);
    for (uint32_t t = from_us; t - from_us < limit_us; t += 1000) {
      model.advance_to(t);
      SensorSample s;
      while (sensor.poll(t, s)) {
      }
      if (sensor.state() == ZforceState::Running || sensor.state() == ZforceState::Failed) return t;
    }
    return from_us + limit_us;
  }

  // The main loop from `from_us` to `to_us` every `step_us`: all samples.
  std::vector<SensorSample> run(uint32_t from_us, uint32_t to_us, uint32_t step_us = 500) {
    std::vector<SensorSample> out;
    for (uint32_t t = from_us; static_cast<int32_t>(to_us - t) >= 0; t += step_us) {
      model.advance_to(t);
      SensorSample s;
      while (sensor.poll(t, s)) out.push_back(s);
    }
    return out;
  }
};

}  // namespace ff::test
