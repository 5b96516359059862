// The USB host channel's outbox: whole frames in, their reports out in order
// as the board's transmit queue has room (firmware/app/hid_outbox.hpp).
#include "firmware/app/hid_outbox.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

namespace ff::firmware {
namespace {

// A board whose SEREMU queue takes `room` reports until the host reads them.
class QueueBoard final : public Board {
 public:
  bool mouse_move_to(int, int) override { return true; }
  bool udp_receive(uint8_t*, size_t, size_t&, UdpEndpoint&) override { return false; }
  bool udp_send(const UdpEndpoint&, const uint8_t*, size_t) override { return true; }
  bool hid_receive(uint8_t*) override { return false; }
  void hid_send(const uint8_t* report) override {
    ASSERT_GT(room, 0u) << "sent beyond the room the board reported";
    --room;
    reports.emplace_back(report, report + protocol::kHidReportBytes);
  }
  size_t hid_tx_room() override { return room; }
  uint32_t cycles() override { return 0; }
  void reboot_to_bootloader() override {}

  size_t room = 0;
  std::vector<std::vector<uint8_t>> reports;
};

// A frame of `size` bytes whose header says so (the host reads its length there); the rest a pattern.
std::vector<uint8_t> frame_of(size_t size, uint8_t seed) {
  std::vector<uint8_t> f(size);
  for (size_t i = 0; i < size; ++i) f[i] = static_cast<uint8_t>(seed + i * 7);
  const size_t payload = size - protocol::kHeaderBytes - protocol::kCrcBytes;
  f[5] = static_cast<uint8_t>(payload & 0xFF);
  f[6] = static_cast<uint8_t>(payload >> 8);
  return f;
}

// The frames the host reassembles from the reports, in order.
std::vector<std::vector<uint8_t>> frames_from(const std::vector<std::vector<uint8_t>>& reports) {
  std::vector<std::vector<uint8_t>> frames;
  protocol::HidReassembler host;
  for (const std::vector<uint8_t>& r : reports) {
    if (host.push(r.data())) frames.emplace_back(host.frame(), host.frame() + host.size());
  }
  EXPECT_EQ(host.errors(), 0u);
  return frames;
}

TEST(HidOutbox, AFrameLongerThanTheQueueGoesOutOverSeveralPassesWhole) {
  QueueBoard board;
  HidOutbox out;
  const std::vector<uint8_t> big = frame_of(22 * 63, 1);  // 22 reports, as a Condition with a full scene
  ASSERT_TRUE(out.push(big.data(), big.size()));
  for (int pass = 0; pass < 4; ++pass) {
    board.room = 6;  // the host read what was queued
    out.drain(board);
    EXPECT_EQ(board.reports.size(), std::min<size_t>(6u * (pass + 1), 22u)) << pass;
  }
  EXPECT_TRUE(out.empty());
  const std::vector<std::vector<uint8_t>> frames = frames_from(board.reports);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0], big);
}

TEST(HidOutbox, FramesKeepTheirOrderAndNoReportIsSentWithoutRoom) {
  QueueBoard board;
  HidOutbox out;
  std::vector<std::vector<uint8_t>> sent;
  for (uint8_t i = 0; i < 5; ++i) {
    sent.push_back(frame_of(40 + 90u * i, i));  // 1, 3, 4, 5 and 7 reports
    ASSERT_TRUE(out.push(sent.back().data(), sent.back().size()));
  }
  out.drain(board);  // no room: nothing (QueueBoard fails the test otherwise)
  EXPECT_TRUE(board.reports.empty());
  while (!out.empty()) {
    board.room = 1;
    out.drain(board);
  }
  EXPECT_EQ(board.reports.size(), 1u + 3 + 4 + 5 + 7);
  EXPECT_EQ(frames_from(board.reports), sent);
}

TEST(HidOutbox, AFrameThatDoesNotFitIsRefusedWholeAndTheOthersStayIntact) {
  QueueBoard board;
  HidOutbox out;
  const std::vector<uint8_t> first = frame_of(700, 3), second = frame_of(700, 9), third = frame_of(200, 5);
  ASSERT_TRUE(out.push(first.data(), first.size()));
  ASSERT_TRUE(out.push(second.data(), second.size()));
  // 2 x (2 + 700) of 1,472 bytes taken: 68 left, so 200 bytes do not fit.
  EXPECT_FALSE(out.push(third.data(), third.size()));
  board.room = 12;  // the first frame's 12 reports: its room is free again, but at the front
  out.drain(board);
  ASSERT_EQ(board.reports.size(), 12u);
  EXPECT_TRUE(out.push(third.data(), third.size()));  // the waiting frame moves to the front
  board.room = 100;
  out.drain(board);
  EXPECT_EQ(frames_from(board.reports), (std::vector<std::vector<uint8_t>>{first, second, third}));
}

TEST(HidOutbox, TheLargestFrameFitsAloneAndNothingElseBeside) {
  QueueBoard board;
  HidOutbox out;
  const std::vector<uint8_t> largest = frame_of(protocol::kMaxFrame, 2);
  EXPECT_FALSE(out.push(largest.data(), largest.size() + 1));  // over any frame
  EXPECT_FALSE(out.push(largest.data(), 0));
  ASSERT_TRUE(out.push(largest.data(), largest.size()));
  const std::vector<uint8_t> small = frame_of(64, 4);
  EXPECT_FALSE(out.push(small.data(), small.size()));  // 1,472 - 1,411 = 61 bytes left
  board.room = protocol::kMaxHidReports;
  out.drain(board);
  EXPECT_EQ(board.reports.size(), protocol::kMaxHidReports);
  EXPECT_TRUE(out.empty());
  EXPECT_EQ(frames_from(board.reports), std::vector<std::vector<uint8_t>>{largest});
}

}  // namespace
}  // namespace ff::firmware
