// Joining the host's two 32-byte SEREMU packets into one 64-byte report:
// halves in order, a stale first half dropped, a packet of another size
// dropped with the half it would have joined.
#include "firmware/app/seremu_joiner.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>

namespace ff::firmware {
namespace {

using Packet = std::array<uint8_t, SeremuJoiner::kPacketBytes>;

Packet packet(uint8_t fill) {
  Packet p;
  p.fill(fill);
  return p;
}

TEST(SeremuJoiner, TwoHalvesMakeOneReportInOrder) {
  SeremuJoiner j;
  uint8_t report[SeremuJoiner::kReportBytes] = {};
  EXPECT_FALSE(j.push(packet(1).data(), 32, 1000, report));
  EXPECT_TRUE(j.push(packet(2).data(), 32, 1100, report));
  for (size_t i = 0; i < 32; ++i) ASSERT_EQ(report[i], 1) << i;
  for (size_t i = 32; i < 64; ++i) ASSERT_EQ(report[i], 2) << i;
  EXPECT_FALSE(j.push(packet(3).data(), 32, 1200, report));  // the next report's first half
  EXPECT_EQ(j.packets_dropped(), 0u);
}

TEST(SeremuJoiner, AFirstHalfLeftAloneOver20msIsDropped) {
  SeremuJoiner j;
  uint8_t report[SeremuJoiner::kReportBytes] = {};
  EXPECT_FALSE(j.push(packet(1).data(), 32, 0, report));
  EXPECT_FALSE(j.push(packet(3).data(), 32, 20001, report));  // its partner lost: this one starts anew
  EXPECT_EQ(j.packets_dropped(), 1u);
  EXPECT_TRUE(j.push(packet(4).data(), 32, 20100, report));
  EXPECT_EQ(report[0], 3);
  EXPECT_EQ(report[63], 4);
  EXPECT_FALSE(j.push(packet(5).data(), 32, 40000, report));  // exactly 20 ms is still in time
  EXPECT_TRUE(j.push(packet(6).data(), 32, 60000, report));
  EXPECT_EQ(j.packets_dropped(), 1u);
}

TEST(SeremuJoiner, APacketOfAnotherSizeIsDroppedWithTheHalfItWouldJoin) {
  SeremuJoiner j;
  uint8_t report[SeremuJoiner::kReportBytes] = {};
  const Packet p = packet(7);
  EXPECT_FALSE(j.push(p.data(), 31, 0, report));  // alone: one dropped
  EXPECT_EQ(j.packets_dropped(), 1u);
  EXPECT_FALSE(j.push(p.data(), 32, 100, report));
  EXPECT_FALSE(j.push(p.data(), 16, 200, report));  // with a first half: both dropped
  EXPECT_EQ(j.packets_dropped(), 3u);
  EXPECT_FALSE(j.push(packet(8).data(), 32, 300, report));  // a fresh pair after it
  EXPECT_TRUE(j.push(packet(9).data(), 32, 400, report));
  EXPECT_EQ(report[0], 8);
  EXPECT_EQ(report[63], 9);
}

}  // namespace
}  // namespace ff::firmware
