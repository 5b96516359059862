#pragma once
// The fake device of ffctl's tests: the firmware itself (firmware/app) on
// emulated peripherals, stepped in simulated time. The board (USB, UDP) is
// the test's.
#include <memory>

#include "firmware/app/firmware_app.hpp"
#include "frictionfield/emulated/ad9834_model.hpp"
#include "frictionfield/emulated/i2c_bus.hpp"
#include "frictionfield/emulated/recording_dac.hpp"
#include "frictionfield/emulated/scripted_adc.hpp"
#include "frictionfield/emulated/zforce_model.hpp"

namespace ff::ffctl {

struct EmulatedFirmware {
  void start(firmware::Board& board) {
    const ZforceConfig config;
    i2c.attach(config.address, zforce);
    zforce.set_calibration(config.calibration);
    for (uint8_t ch = 0; ch < 4; ++ch) adc.set(ch, 100);
    app = std::make_unique<firmware::FirmwareApp>(firmware::Peripherals{dds, 0, i2c, zforce, dac, adc}, board,
                                                  *pipeline);
    app->begin(now);
  }
  void step() {  // 100 us of device time: loop every step, tick every 5th
    now += 100;
    zforce.advance_to(now);
    app->loop(now);
    if (now % 500 == 0) app->tick(now);
  }

  emulated::Ad9834Model dds;
  emulated::ZforceModel zforce;
  emulated::EmulatedI2cBus i2c;
  emulated::RecordingDac dac;
  emulated::ScriptedAdc adc;
  std::unique_ptr<HapticPipeline> pipeline = std::make_unique<HapticPipeline>();
  std::unique_ptr<firmware::FirmwareApp> app;
  uint32_t now = 0;
};

}  // namespace ff::ffctl
