#include "frictionfield/protocol/hid_channel.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <utility>
#include <vector>

namespace ff::protocol {
namespace {

std::vector<uint8_t> status_frame() {
  Message m;
  m.type = MessageType::Status;
  std::vector<uint8_t> frame(kMaxFrame);
  frame.resize(encode(m, frame.data(), frame.size()));
  return frame;
}


TEST(HidChannel, SplitsAndReassemblesALongFrame) {
  const std::vector<uint8_t> frame = status_frame();
  uint8_t reports[kMaxHidReports][kHidReportBytes];
  const size_t n = split_into_reports(frame.data(), frame.size(), reports, kMaxHidReports);
  ASSERT_EQ(n, (frame.size() + 62) / 63);
  ASSERT_GE(n, 2u);
  EXPECT_EQ(reports[0][0], 0x00);
  EXPECT_EQ(reports[n - 1][0], 0x80 | (n - 1));
  EXPECT_TRUE(std::equal(frame.begin(), frame.begin() + 63, &reports[0][1]));
  HidReassembler r;
  for (size_t i = 0; i + 1 < n; ++i) EXPECT_FALSE(r.push(reports[i]));
  ASSERT_TRUE(r.push(reports[n - 1]));
  ASSERT_EQ(r.size(), frame.size());
  EXPECT_TRUE(std::equal(frame.begin(), frame.end(), r.frame()));
  EXPECT_EQ(r.errors(), 0u);
}

TEST(HidChannel, LostReportIsCountedAndTheNextFrameStillArrives) {
  const std::vector<uint8_t> frame = status_frame();
  uint8_t reports[kMaxHidReports][kHidReportBytes];
  const size_t n = split_into_reports(frame.data(), frame.size(), reports, kMaxHidReports);
  ASSERT_GE(n, 2u);
  HidReassembler r;
  EXPECT_FALSE(r.push(reports[1]));  // the first one was lost
  EXPECT_EQ(r.errors(), 1u);
  for (size_t i = 0; i + 1 < n; ++i) r.push(reports[i]);
  EXPECT_TRUE(r.push(reports[n - 1]));
  EXPECT_EQ(r.size(), frame.size());
}

TEST(HidChannel, SplitRefusesWhatDoesNotFit) {
  const std::vector<uint8_t> frame = status_frame();
  uint8_t reports[1][kHidReportBytes];
  EXPECT_EQ(split_into_reports(frame.data(), frame.size(), reports, 1), 0u);
  EXPECT_EQ(split_into_reports(frame.data(), 0, reports, 1), 0u);
}

TEST(HidChannel, BinaryFramesWithEveryByteValueSurvive) {
  std::vector<uint8_t> frame(kMaxFrame);
  for (size_t i = 0; i < frame.size(); ++i) frame[i] = static_cast<uint8_t>(i * 7);  // all 256 values
  frame[5] = static_cast<uint8_t>((kMaxFrame - kHeaderBytes - kCrcBytes) & 0xFF);   // the header's length
  frame[6] = static_cast<uint8_t>((kMaxFrame - kHeaderBytes - kCrcBytes) >> 8);
  uint8_t reports[kMaxHidReports][kHidReportBytes];
  const size_t n = split_into_reports(frame.data(), frame.size(), reports, kMaxHidReports);
  ASSERT_EQ(n, kMaxHidReports);
  HidReassembler r;
  for (size_t i = 0; i + 1 < n; ++i) ASSERT_FALSE(r.push(reports[i]));
  ASSERT_TRUE(r.push(reports[n - 1]));
  EXPECT_EQ(std::vector<uint8_t>(r.frame(), r.frame() + r.size()), frame);
}

TEST(HidChannel, ReportsBeyondTheLongestFrameAreCounted) {
  uint8_t report[kHidReportBytes] = {};
  HidReassembler r;
  for (size_t i = 0; i < kMaxHidReports; ++i) {
    report[0] = static_cast<uint8_t>(i);  // never the last
    EXPECT_FALSE(r.push(report));
  }
  EXPECT_EQ(r.errors(), 0u);
  report[0] = static_cast<uint8_t>(kMaxHidReports);
  EXPECT_FALSE(r.push(report));  // one more than any frame needs
  EXPECT_EQ(r.errors(), 1u);
}

// A frame and its reports.
struct Split {
  std::vector<uint8_t> frame;
  uint8_t reports[kMaxHidReports][kHidReportBytes];
  size_t n = 0;
  explicit Split(std::vector<uint8_t> f, uint8_t fill = 0) : frame(std::move(f)) {
    std::memset(reports, fill, sizeof reports);
    n = split_into_reports(frame.data(), frame.size(), reports, kMaxHidReports);
  }
};

// Pushes `n` reports in order; how many of them completed a frame.
int push_all(HidReassembler& r, const uint8_t (*reports)[kHidReportBytes], size_t n) {
  int complete = 0;
  for (size_t i = 0; i < n; ++i) complete += r.push(reports[i]) ? 1 : 0;
  return complete;
}

TEST(HidChannel, TheLastReportIsPaddedWithZeroes) {
  const Split s(status_frame(), 0xAA);
  const size_t used = s.frame.size() - (s.n - 1) * kHidChunkBytes;  // bytes of the frame in the last report
  ASSERT_LT(used, kHidChunkBytes);
  for (size_t i = 1 + used; i < kHidReportBytes; ++i) EXPECT_EQ(s.reports[s.n - 1][i], 0) << i;
}

TEST(HidChannel, FramesBackToBackArriveWithoutErrors) {
  const Split s(status_frame());
  HidReassembler r;
  for (int k = 0; k < 3; ++k) EXPECT_EQ(push_all(r, s.reports, s.n), 1) << k;
  EXPECT_EQ(r.errors(), 0u);
}

TEST(HidChannel, AFrameWithoutItsFirstReportIsDroppedReportByReport) {
  const Split s(status_frame());
  ASSERT_GE(s.n, 3u);
  HidReassembler r;
  EXPECT_EQ(push_all(r, s.reports + 1, s.n - 1), 0);  // none starts a frame
  EXPECT_EQ(r.errors(), s.n - 1);
  EXPECT_EQ(push_all(r, s.reports, s.n), 1);  // the next whole frame arrives
  EXPECT_EQ(r.errors(), s.n - 1);
}

TEST(HidChannel, AFrameCutShortThenAWholeOneGivesTheWholeOne) {
  const Split cut(status_frame());
  Message m;
  m.type = MessageType::Status;
  m.status.ticks = 123456;  // different bytes from the first frame
  std::vector<uint8_t> bytes(kMaxFrame);
  bytes.resize(encode(m, bytes.data(), bytes.size()));
  const Split whole(bytes);
  HidReassembler r;
  EXPECT_EQ(push_all(r, cut.reports, cut.n - 1), 0);  // its last report lost
  EXPECT_EQ(push_all(r, whole.reports, whole.n), 1);
  EXPECT_EQ(r.errors(), 1u);  // the first report of the whole one, out of turn
  EXPECT_EQ(std::vector<uint8_t>(r.frame(), r.frame() + r.size()), whole.frame);
}

TEST(HidChannel, ReportsOutOfOrderLoseTheFrameAndCountEach) {
  const Split s(status_frame());
  ASSERT_GE(s.n, 4u);
  HidReassembler r;
  int complete = r.push(s.reports[0]) ? 1 : 0;
  complete += r.push(s.reports[2]) ? 1 : 0;  // 1 overtaken: the frame is lost from here
  complete += r.push(s.reports[1]) ? 1 : 0;
  complete += push_all(r, s.reports + 3, s.n - 3);
  EXPECT_EQ(complete, 0);
  EXPECT_EQ(r.errors(), s.n - 1);  // every report after the first
}

TEST(HidChannel, AfterTooManyReportsTheNextFrameArrivesWhole) {
  uint8_t report[kHidReportBytes] = {};
  HidReassembler r;
  for (size_t i = 0; i <= kMaxHidReports; ++i) {  // one more than any frame needs: dropped, counted
    report[0] = static_cast<uint8_t>(i);
    EXPECT_FALSE(r.push(report));
  }
  EXPECT_EQ(r.errors(), 1u);
  const Split s(status_frame());
  EXPECT_EQ(push_all(r, s.reports, s.n), 1);
  EXPECT_EQ(r.errors(), 1u);
  EXPECT_EQ(std::vector<uint8_t>(r.frame(), r.frame() + r.size()), s.frame);
}

TEST(HidChannel, ALastReportShorterThanTheHeaderSaysIsCounted) {
  const std::vector<uint8_t> frame = status_frame();
  uint8_t reports[kMaxHidReports][kHidReportBytes];
  const size_t n = split_into_reports(frame.data(), frame.size(), reports, kMaxHidReports);
  ASSERT_GE(n, 2u);
  HidReassembler r;
  reports[0][0] = 0x80;  // the first report claims to be the last
  EXPECT_FALSE(r.push(reports[0]));
  EXPECT_EQ(r.errors(), 1u);
  reports[0][0] = 0x00;
  for (size_t i = 0; i + 1 < n; ++i) r.push(reports[i]);
  EXPECT_TRUE(r.push(reports[n - 1]));  // and the next frame is whole again
}

}  // namespace
}  // namespace ff::protocol
