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

TEST(BindingDecreasing, BeforeAnyConditionTheQueryAnswersTheBoardsWiring) {
  // A host that asks first, then sets a scene with the calibration it was told,
  // keeps the board's direction: code 4095 rests the plate.
  BindingRig rig;
  rig.boot();
  rig.run_until(1000000);
  Message q;
  q.type = MessageType::QueryCondition;
  rig.udp_send(q);
  rig.run_until(1050000);
  std::vector<Message> answers;
  for (const Message& m : rig.udp_received()) {
    if (m.type == MessageType::Condition) answers.push_back(m);
  }
  ASSERT_EQ(answers.size(), 1u);
  const ff::DacCalibration& c = answers[0].condition.calibration;
  ASSERT_EQ(c.count, 2);
  EXPECT_EQ(c.amplitude[0], 0.0f);
  EXPECT_EQ(c.code[0], 4095.0f);
  EXPECT_EQ(c.amplitude[1], 1.0f);
  EXPECT_EQ(c.code[1], 0.0f);
}

}  // namespace
}  // namespace teensy_model
