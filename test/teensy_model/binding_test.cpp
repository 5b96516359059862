// firmware/src/main.cpp, unchanged, against the Teensyduino model: setup()
// and loop() run with the 2 kHz IntervalTimer firing in simulated time, the
// emulated zForce, AD9834 and load cells on their pins, a USB host and a
// network host. Each test is its own process (gtest_discover_tests), since
// the binding's globals live once per program, as on the Teensy.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "binding_rig.hpp"
#include "firmware/app/dac_wiring.hpp"
#include "firmware/app/host_link_limits.hpp"
#include "firmware/app/pins.hpp"

namespace teensy_model {
namespace {

using ff::protocol::Message;
using ff::protocol::MessageType;

TEST(Binding, TheFirstDacStateAfterResetIsTheRestCodeOnTheInternalReference) {
  BindingRig rig;
  rig.boot();
  const std::vector<DacState>& dac = dac_history();
  ASSERT_GE(dac.size(), 2u);
  EXPECT_FALSE(dac[0].enabled);  // off from reset until the hook
  EXPECT_TRUE(dac[1].enabled);
  EXPECT_LT(dac[1].t_us, 1000u) << "the plate must rest from startup_middle_hook, not from setup() 300 ms later";
  EXPECT_EQ(dac[1].code, 0);
  for (const DacState& d : dac) {
    if (d.enabled) {
      EXPECT_TRUE(d.internal_ref) << "DAC0 must stay on the 1.2 V reference (t " << d.t_us << ")";
    }
  }
  rig.run_until(600000);
  for (const DacState& d : dac_history()) {
    if (d.enabled) {
      EXPECT_EQ(d.code, 0) << "no finger, no scene: the plate rests (t " << d.t_us << ")";
    }
  }
}

TEST(Binding, HostReportsFullOfZeroBytesArriveWhole) {
  BindingRig rig;
  rig.boot();
  rig.run_until(400000);
  // A general scene: a long frame, mostly zero bytes (floats of 0, padding).
  Message m;
  m.type = MessageType::SetCondition;
  m.sequence = 7;
  m.condition.kind = ff::protocol::ConditionKind::General;
  m.condition.scene = ff::scenes::neutral();
  m.condition.strength = 0.5f;
  rig.usb_send(m);
  Message q;
  q.type = MessageType::QueryStatus;
  q.sequence = 8;
  rig.usb_send(q);
  rig.run_until(now_us() + 400000);
  const std::vector<Message> in = rig.usb_received();
  ASSERT_EQ(in.size(), 2u);
  EXPECT_EQ(in[0].type, MessageType::Ack);
  EXPECT_EQ(in[0].sequence, 7);
  EXPECT_EQ(in[0].ack.status, ff::protocol::AckStatus::Ok);
  EXPECT_EQ(in[1].type, MessageType::Status);
  EXPECT_EQ(in[1].status.kind, ff::protocol::ConditionKind::General);
  EXPECT_EQ(in[1].status.protocol_errors, 0u);
  EXPECT_EQ(serial_available_calls(), 0u) << "Serial.available() parks or drops binary packets (usb_seremu.c)";
}

TEST(Binding, AThousandBackToBackHostReportsWhileTheMouseKeepsMoving) {
  BindingRig rig;
  rig.devices.zforce.load_trace(back_and_forth(900000, 6000000));
  rig.boot();
  rig.run_until(1000000);
  for (int i = 0; i < 1000; ++i) {
    Message m;
    m.type = MessageType::SetCarrier;
    m.sequence = static_cast<uint8_t>(i);
    m.carrier.frequency_hz = 34900.0f;
    rig.usb_send(m);  // 2 OUT packets each, sent every 2 ms as the host may: 4 s
  }
  std::vector<Message> replies;
  std::vector<MouseReport> mouse;
  while (now_us() < 5900000) {
    rig.run_until(now_us() + 100000);
    for (const Message& m : rig.usb_received()) replies.push_back(m);
    for (const MouseReport& r : host_take_mouse()) mouse.push_back(r);
  }
  EXPECT_EQ(host_out_backlog(), 0u);
  ASSERT_EQ(replies.size(), 1000u);
  for (size_t i = 0; i < replies.size(); ++i) {
    ASSERT_EQ(replies[i].type, MessageType::Ack) << i;
    ASSERT_EQ(replies[i].sequence, static_cast<uint8_t>(i)) << i;
  }
  // The cursor follows the finger every 3 ms throughout.
  ASSERT_GT(mouse.size(), 1000u);
  for (size_t i = 1; i < mouse.size(); ++i) {
    if (mouse[i].t_us > 5900000) break;
    ASSERT_LE(mouse[i].t_us - mouse[i - 1].t_us, 4000u) << "the mouse stalled at " << mouse[i - 1].t_us << " us";
  }
  EXPECT_GE(usb_buffers_free(), 15u);
}

TEST(Binding, AHostThatStopsPollingCostsNoLoopTime) {
  BindingRig rig;
  rig.devices.zforce.load_trace(back_and_forth(900000, 3500000));
  rig.boot();
  rig.run_until(1000000);
  Message start;
  start.type = MessageType::StartStream;
  start.stream.tick_decimation = 1;
  rig.usb_send(start);
  rig.run_until(1200000);
  set_host_polls(false);  // the host application hangs: IN endpoints are no longer read
  rig.run_until(3000000);
  EXPECT_LT(longest_loop_pass_us(), 2000u) << "a write waited for a host that does not poll (usb_seremu.c, usb_mouse.c)";
  const Message st = rig.udp_status();
  EXPECT_EQ(st.status.watchdog_trips, 0u);
}

TEST(Binding, AReplyAddressThatNeverAnswersKeepsTheLoopUnderTheWatchdog) {
  BindingRig rig;
  rig.devices.zforce.load_trace(back_and_forth(900000, 3500000));
  rig.boot();
  rig.run_until(1000000);
  rig.network.answers_arp = false;
  Message q;
  q.type = MessageType::QueryStatus;
  rig.udp_send(q);  // the reply, and force every 30 ms, go to an address without ARP
  rig.run_until(3000000);
  EXPECT_EQ(retransmission_timeout_ms(), ff::firmware::kW5200RetransmissionMs);
  EXPECT_EQ(retransmission_count(), ff::firmware::kW5200Retries);
  EXPECT_LT(longest_loop_pass_us(), 20000u);
  EXPECT_LE(rig.network.unanswered, 2u) << "quiet towards an address that did not answer until it speaks again";
  rig.network.answers_arp = true;
  const Message st = rig.udp_status();
  EXPECT_EQ(st.status.watchdog_trips, 0u);
}

TEST(Binding, WithoutAW5200TheSocketIsLeftAloneAndUsbStillAnswers) {
  Options no_chip;
  no_chip.w5200_present = false;
  BindingRig rig(no_chip);
  rig.devices.zforce.load_trace(back_and_forth(900000, 2500000));
  rig.boot();
  rig.run_until(1000000);
  Message q;
  q.type = MessageType::QueryStatus;
  rig.udp_send(q);  // nobody can hear it
  rig.usb_send(q);
  rig.run_until(1300000);
  EXPECT_EQ(udp_calls_without_socket(), 0u) << "EthernetUDP called on no socket: socket.cpp indexes past its state";
  std::vector<Message> status;
  for (const Message& m : rig.usb_received()) {
    if (m.type == MessageType::Status) status.push_back(m);
  }
  ASSERT_EQ(status.size(), 1u);
  EXPECT_EQ(status[0].status.device[ff::protocol::DeviceCount::UdpUnavailable], 1u);
  EXPECT_TRUE(rig.udp_received().empty());
}

TEST(Binding, WithAW5200UdpIsAvailable) {
  BindingRig rig;
  rig.boot();
  rig.run_until(1000000);
  const Message st = rig.udp_status();
  ASSERT_EQ(st.type, MessageType::Status);
  EXPECT_EQ(st.status.device[ff::protocol::DeviceCount::UdpUnavailable], 0u);
}

TEST(Binding, ADatagramTooLongForAnyMessageIsDroppedWithoutReadingItByteByByte) {
  BindingRig rig;
  rig.boot();
  rig.run_until(1000000);
  rig.network.host_send(std::vector<uint8_t>(2000, 0x46));  // a W5200 socket buffer's worth
  rig.run_until(1100000);
  EXPECT_LT(longest_loop_pass_us(), 2000u) << "one SPI transaction per byte: ~5 us each";
  const std::vector<Message> replies = rig.udp_received();
  ASSERT_FALSE(replies.empty());
  EXPECT_EQ(replies[0].type, MessageType::Error);  // an empty frame: malformed
  EXPECT_EQ(rig.udp_status().type, MessageType::Status);  // and the next datagram is read whole
}

TEST(Binding, TheLoadCellsReadTheirOwnPins) {
  BindingRig rig;
  rig.devices.use_pin_counts = true;
  for (uint8_t p : ff::firmware::pins::kLoadCells) rig.devices.counts_on_pin[p] = 100;
  rig.boot();
  rig.run_until(1200000);  // setup() returned at ~0.86 s; tared 5 x 30 ms later
  Message q;
  q.type = MessageType::QueryStatus;
  rig.udp_send(q);
  for (uint8_t p : ff::firmware::pins::kLoadCells) rig.devices.counts_on_pin[p] = 140;  // +40 counts each
  rig.run_until(1500000);
  std::vector<Message> force;
  for (const Message& m : rig.udp_received()) {
    if (m.type == MessageType::Force) force.push_back(m);
  }
  ASSERT_GT(force.size(), 5u);
  // The cells' sum: 4 x 40 counts x 1.0712 g x 9.81 = 1681.36 mN (drivers/load_cells), once all five
  // readings see it. A chip select on a load cell's pin (15 = A1) reads its own level: 1260 mN.
  EXPECT_NEAR(force.back().force.force_mN, 1681.36f, 0.5f);
  EXPECT_NE(ethernet_chip_select(), ff::firmware::pins::kLoadCells[1]);
}

TEST(Binding, TheTickIsTheTimerAboveUsbAndTheDacFollowsTheScene) {
  BindingRig rig;
  rig.devices.zforce.load_trace(back_and_forth(900000, 2500000));
  rig.boot();
  EXPECT_EQ(timer_priority(), 64);
  const uint64_t t0 = now_us();  // setup() returned: the timer runs from here (Ethernet's start-up took 560 ms)
  rig.run_until(1000000);
  Message m;
  m.type = MessageType::SetCondition;
  m.condition.kind = ff::protocol::ConditionKind::Heightmap;
  rig.udp_send(m);
  const uint32_t before = interrupt_count();
  rig.run_until(2000000);
  // Ticks every 500 us, plus the DR edges of a report every 5 ms.
  EXPECT_NEAR(static_cast<double>(interrupt_count() - before), 1000000 / 500 + 1000000 / 5000, 10.0);
  EXPECT_GT(t0, 800000u);
  EXPECT_NE(dac_code_at(1900000), 0) << "a finger on the heightmap: the plate renders";
  rig.run_until(2700000);
  EXPECT_EQ(dac_code_at(2600000), 0) << "lifted at 2.5 s: the plate rests";
  EXPECT_EQ(rig.devices.dds.total_faults(), 0u) << rig.devices.dds.first_fault();
  EXPECT_TRUE(rig.devices.dds.output_on());
  const Message st = rig.udp_status();
  EXPECT_GT(st.status.isr_cycles_mean, 0u);
  EXPECT_GE(st.status.isr_cycles_max, st.status.isr_cycles_mean);
  EXPECT_GT(st.status.zforce_layout_beside, 0u);
}

// Teensyduino's own way in (usb_dev.c): a 4-byte SEREMU feature report of the
// magic restarts the chip 5 ms later, from the USB interrupt, whatever the loop
// does; any other 4 bytes only mark the serial emulation online.
TEST(Binding, SeremuFeatureReportRestartsFiveFramesLater) {
  BindingRig rig;
  rig.boot();
  rig.run_until(1000000);
  const uint8_t other[4] = {0xA9, 0x45, 0xC2, 0x6C};
  host_set_seremu_feature_report(other, 4);
  const uint8_t magic[4] = {0xA9, 0x45, 0xC2, 0x6B};
  host_set_seremu_feature_report(magic, 3);  // a wrong length is not the request
  rig.run_until(1100000);
  EXPECT_FALSE(rebooted());
  EXPECT_TRUE(usb_seremu_online());
  const uint64_t at = now_us();
  host_set_seremu_feature_report(magic, 4);
  rig.run_until(at + 3900);
  EXPECT_FALSE(rebooted()) << "five frames, not fewer";
  rig.run_until(at + 6500);
  EXPECT_TRUE(rebooted());
  EXPECT_LE(now_us(), at + 6500);
}

// A reboot the firmware decides rests the plate, and the tick keeps it resting
// until the jump: whenever it lands relative to the tick.
class RebootAt : public ::testing::TestWithParam<int> {};

TEST_P(RebootAt, LeavesThePlateAtRest) {
  BindingRig rig;
  rig.devices.zforce.load_trace(back_and_forth(900000, 3000000));
  rig.boot();
  rig.run_until(1000000);
  Message m;
  m.type = MessageType::SetCondition;
  m.condition.kind = ff::protocol::ConditionKind::Heightmap;
  rig.udp_send(m);
  rig.run_until(1500000 + static_cast<uint64_t>(GetParam()) * 37);
  ASSERT_NE(dac_history().back().code, ff::firmware::kBootRestCode) << "the finger moves: the plate renders";
  Message reboot;
  reboot.type = MessageType::RebootToBootloader;
  rig.udp_send(reboot);
  rig.run_until(1800000);
  ASSERT_TRUE(rebooted());
  EXPECT_EQ(dac_history().back().code, ff::firmware::kBootRestCode);
  EXPECT_TRUE(dac_history().back().enabled);
}
INSTANTIATE_TEST_SUITE_P(Binding, RebootAt, ::testing::Range(0, 12));

}  // namespace
}  // namespace teensy_model
