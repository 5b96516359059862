// The binding built for the decreasing DAC wiring (FF_DAC_DECREASING=1: Analog
// Devices' circuit note, more DAC volts = less current): code 4095 rests the
// plate, from the first millisecond after reset and through a reboot.
#include <gtest/gtest.h>

#include "binding_rig.hpp"
#include "firmware/app/dac_wiring.hpp"

namespace teensy_model {
namespace {

using ff::protocol::Message;
using ff::protocol::MessageType;

TEST(BindingDecreasing, TheFirstDacStateAfterResetIsCode4095) {
  static_assert(ff::firmware::kBootRestCode == 4095, "built with FF_DAC_DECREASING=1");
  BindingRig rig;
  rig.boot();
  const std::vector<DacState>& dac = dac_history();
  ASSERT_GE(dac.size(), 2u);
  EXPECT_FALSE(dac[0].enabled);
  EXPECT_TRUE(dac[1].enabled);
  EXPECT_LT(dac[1].t_us, 1000u);
  EXPECT_EQ(dac[1].code, 4095);
  rig.run_until(1200000);
  for (const DacState& d : dac_history()) {
    if (d.enabled) {
      EXPECT_EQ(d.code, 4095) << "t " << d.t_us;
    }
  }
}

TEST(BindingDecreasing, IdleWithAFingerDownAndAfterLiftOffIsTheRestCode) {
  BindingRig rig;
  rig.devices.zforce.load_trace(back_and_forth(900000, 1600000));
  rig.boot();
  rig.run_until(1000000);
  Message m;
  m.type = MessageType::SetCondition;
  m.condition.kind = ff::protocol::ConditionKind::Heightmap;
  m.condition.calibration = ff::DacCalibration::inverted();
  rig.udp_send(m);
  rig.run_until(1800000);  // the finger lifted at 1.6 s
  EXPECT_EQ(dac_history().back().code, 4095);
  EXPECT_NE(dac_code_at(1400000), 4095) << "a finger on the heightmap: the plate renders";
}

}  // namespace
}  // namespace teensy_model
