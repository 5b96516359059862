#include "frictionfield/protocol/hid_channel.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace ff::protocol {
namespace {

TEST(HidChannel, SplitsAndReassemblesALongFrame) {
  Message m;
  m.type = MessageType::Status;
  std::vector<uint8_t> frame(kMaxFrame);
  frame.resize(encode(m, frame.data(), frame.size()));
  uint8_t reports[kMaxHidReports][kHidReportBytes];
  const size_t n = split_into_reports(frame.data(), frame.size(), reports, kMaxHidReports);
  ASSERT_EQ(n, (frame.size() + 62) / 63);
  EXPECT_EQ(reports[0][0], 0x00);
  EXPECT_EQ(reports[n - 1][0], 0x80 | (n - 1));
  HidReassembler r;
  for (size_t i = 0; i + 1 < n; ++i) EXPECT_FALSE(r.push(reports[i]));
  ASSERT_TRUE(r.push(reports[n - 1]));
  ASSERT_EQ(r.size(), frame.size());
  Message out;
  EXPECT_EQ(decode(r.frame(), r.size(), out), DecodeStatus::Ok);
}

TEST(HidChannel, LostReportIsCountedAndTheNextFrameStillArrives) {
  Message m;
  m.type = MessageType::Status;
  std::vector<uint8_t> frame(kMaxFrame);
  frame.resize(encode(m, frame.data(), frame.size()));
  uint8_t reports[kMaxHidReports][kHidReportBytes];
  const size_t n = split_into_reports(frame.data(), frame.size(), reports, kMaxHidReports);
  ASSERT_GE(n, 2u);
  HidReassembler r;
  EXPECT_FALSE(r.push(reports[1]));  // the first one was lost
  EXPECT_EQ(r.errors(), 1u);
  for (size_t i = 0; i + 1 < n; ++i) r.push(reports[i]);
  EXPECT_TRUE(r.push(reports[n - 1]));
}

}  // namespace
}  // namespace ff::protocol
