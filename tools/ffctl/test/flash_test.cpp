// Flashing without a board: Intel HEX parsing and the HalfKay blocks ffctl
// writes, against teensy_loader_cli's rule and the cross toolchain's objcopy.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "halfkay.hpp"
#include "hex_record.hpp"
#include "intel_hex.hpp"
#include "support/file_contents.hpp"

namespace ff::ffctl {
namespace {

TEST(IntelHex, ParsesWithExtendedAddressesAndRejectsBadRecords) {
  FlashImage image;
  std::string error;
  // Two bytes at 0x0000, one at 0x10000 (extended linear address 0x0001), end.
  ASSERT_TRUE(parse_intel_hex(":020000000102FB\n:020000040001F9\n:0100000055AA\n:00000001FF\n", image, error)) << error;
  EXPECT_EQ(image.bytes[0], 0x01);
  EXPECT_EQ(image.bytes[1], 0x02);
  EXPECT_EQ(image.bytes[0x10000], 0x55);
  EXPECT_EQ(image.highest, 0x10001u);
  FlashImage bad;
  EXPECT_FALSE(parse_intel_hex(":020000000102FC\n:00000001FF\n", bad, error));
  EXPECT_NE(error.find("line 1: checksum"), std::string::npos) << error;
  EXPECT_FALSE(parse_intel_hex(":00000007F9\n", bad, error));
  EXPECT_NE(error.find("unknown record type 7"), std::string::npos) << error;
  EXPECT_FALSE(parse_intel_hex(":020000000102FB\n", bad, error));
  EXPECT_EQ(error, "no end-of-file record after line 1 (a truncated file?)");
  FlashImage empty;
  EXPECT_FALSE(parse_intel_hex("\r\n\n", empty, error));
  EXPECT_EQ(error, "no Intel HEX records (an empty file?)");
  EXPECT_FALSE(parse_intel_hex(":00000001FF\n", empty, error));
  EXPECT_EQ(error, "an end-of-file record but no data");
}

TEST(IntelHex, LowerCaseDigitsBlankLinesAndCrLfAreRead) {
  FlashImage image;
  std::string error;
  ASSERT_TRUE(parse_intel_hex("\r\n:02000000abcd86\r\n\n  \n:00000001ff\r\n\n", image, error)) << error;
  EXPECT_EQ(image.bytes[0], 0xAB);
  EXPECT_EQ(image.bytes[1], 0xCD);
  EXPECT_EQ(image.highest, 2u);
}

TEST(IntelHex, EachMalformedRecordIsRefusedWithItsLineAndReason) {
  const std::string data = hex_record(0, 0x00, {0x01, 0x02});
  const std::string end = hex_record(0, 0x01, {});
  const struct {
    std::string text;
    const char* error;
  } cases[] = {
      {data + end + data, "line 3: data after the end-of-file record"},
      {data + "020000000102FB\n" + end, "line 2: not an Intel HEX record"},           // no colon
      {":0000000\n" + end, "line 1: not an Intel HEX record"},                         // shorter than a record
      {":020000000102FB0\n" + end, "line 1: not an Intel HEX record"},                 // an odd digit count
      {":020000000102FG\n" + end, "line 1: not a hex digit"},
      {":030000000102FA\n" + end, "line 1: byte count does not match the record length"},  // 3 said, 2 there
      {hex_record(0, 0x02, {0x10}) + end, "line 1: extended segment address needs 2 bytes"},
      {hex_record(0, 0x04, {0x00, 0x00, 0x00}) + end, "line 1: extended linear address needs 2 bytes"},
      {hex_record(0, 0x04, {0x00, 0x01}) + end, "an end-of-file record but no data"},
      // Two records for one byte that disagree: which one the flash holds would depend on their order.
      {hex_record(0x20, 0x00, {1, 2, 3, 4}) + hex_record(0x22, 0x00, {3, 9}) + end,
       "line 2: overlaps line 1 at 0x000023 with different data"},
  };
  for (const auto& c : cases) {
    FlashImage image;
    std::string error;
    EXPECT_FALSE(parse_intel_hex(c.text, image, error)) << c.text;
    EXPECT_EQ(error, c.error) << c.text;
  }
}

TEST(IntelHex, RecordsThatRepeatTheSameBytesAreRead) {
  // Some linkers write a section twice with the same bytes: nothing to choose between.
  FlashImage image;
  std::string error;
  ASSERT_TRUE(parse_intel_hex(hex_record(0x20, 0x00, {1, 2, 3, 4}) + hex_record(0x22, 0x00, {3, 4, 5}) +
                                  hex_record(0, 0x01, {}),
                              image, error))
      << error;
  EXPECT_EQ(image.bytes[0x24], 5);
  EXPECT_EQ(image.highest, 0x25u);
}

TEST(IntelHex, DataIsRefusedPastTheFlashEvenWhereItsAddressWrapsAt4GiB) {
  std::string error;
  // The last two bytes of the flash: accepted.
  FlashImage edge;
  ASSERT_TRUE(parse_intel_hex(hex_record(0, 0x04, {0x00, 0x0F}) + hex_record(0xFFFE, 0x00, {0xAA, 0xBB}) +
                                  hex_record(0, 0x01, {}),
                              edge, error))
      << error;
  EXPECT_EQ(edge.bytes[kMk66FlashBytes - 1], 0xBB);
  EXPECT_EQ(edge.highest, kMk66FlashBytes);
  // One byte further: refused.
  FlashImage past;
  EXPECT_FALSE(parse_intel_hex(hex_record(0, 0x04, {0x00, 0x0F}) + hex_record(0xFFFF, 0x00, {0xAA, 0xBB}) +
                                   hex_record(0, 0x01, {}),
                               past, error));
  EXPECT_NE(error.find("line 2: data beyond the 1 MiB flash"), std::string::npos) << error;
  // 0xFFFF0000 + 0xFFFF + 2 would be 1 in 32-bit arithmetic: still beyond the flash.
  FlashImage wrapped;
  EXPECT_FALSE(parse_intel_hex(hex_record(0, 0x04, {0xFF, 0xFF}) + hex_record(0xFFFF, 0x00, {0xAA, 0xBB}) +
                                   hex_record(0, 0x01, {}),
                               wrapped, error));
  EXPECT_NE(error.find("line 2: data beyond the 1 MiB flash"), std::string::npos) << error;
  EXPECT_EQ(wrapped.highest, 0u);
}

TEST(HalfKay, BlocksHaveTheMk66LayoutSkipBlanksButTheFirstAndEndWithBoot) {
  FlashImage image;
  image.bytes[5] = 0xAB;         // block 0
  image.bytes[3 * 1024 + 7] = 1;  // block 3; blocks 1 and 2 stay blank
  image.highest = 3 * 1024 + 8;
  const auto writes = halfkay_writes(image);
  ASSERT_EQ(writes.size(), 3u);  // block 0, block 3, boot
  EXPECT_EQ(writes[0].report.size(), 64u + 1024u);
  EXPECT_EQ(writes[0].report[0], 0);
  EXPECT_EQ(writes[0].report[64 + 5], 0xAB);
  EXPECT_EQ(writes[1].address, 3u * 1024u);
  EXPECT_EQ(writes[1].report[0], 0x00);
  EXPECT_EQ(writes[1].report[1], 0x0C);  // 3072 = 0x000C00, little-endian
  EXPECT_EQ(writes[1].report[2], 0x00);
  EXPECT_EQ(writes[1].report[64 + 7], 1);
  EXPECT_EQ(writes[2].report[0], 0xFF);
  EXPECT_EQ(writes[2].report[1], 0xFF);
  EXPECT_EQ(writes[2].report[2], 0xFF);
  EXPECT_EQ(writes[2].address, 0xFFFFFFu);  // what an error about it would name
  FlashImage blank;
  blank.highest = 2048;
  EXPECT_EQ(halfkay_writes(blank).size(), 2u);  // the first block is always written: it erases the chip
}

// teensy_loader_cli's rule, modelled from the HEX records themselves (which
// addresses a record wrote, and with what): write block 0 always, any other
// block only if a record wrote into it and not only 0xFF.
std::vector<uint32_t> loader_cli_blocks(const std::vector<std::pair<uint32_t, std::vector<uint8_t>>>& records,
                                        uint32_t code_size) {
  std::vector<uint32_t> blocks;
  for (uint32_t addr = 0; addr < code_size; addr += 1024) {
    bool within = false, blank = true;
    for (const auto& rec : records) {
      for (size_t i = 0; i < rec.second.size(); ++i) {
        const uint32_t a = rec.first + static_cast<uint32_t>(i);
        if (a < addr || a >= addr + 1024) continue;
        within = true;
        blank = blank && rec.second[i] == 0xFF;
      }
    }
    if (addr == 0 || (within && !blank)) blocks.push_back(addr);
  }
  return blocks;
}


TEST(HalfKay, SameBlocksAsTeensyLoaderCliWouldWrite) {
  // Records: data in block 0; only 0xFF in block 2; data and 0xFF in block 5;
  // one byte at the very end of the flash (extended linear address 0x000F).
  const std::vector<std::pair<uint32_t, std::vector<uint8_t>>> records = {
      {0x0000, {0x00, 0x80, 0x00, 0x20}},
      {0x0800, {0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF}},
      {0x1400, {0xFF, 0x12, 0xFF}},
      {0xFFFFF, {0x5A}},
  };
  std::string text;
  for (const auto& rec : records) {
    if (rec.first > 0xFFFF) text += hex_record(0, 0x04, {0x00, static_cast<uint8_t>(rec.first >> 16)});
    text += hex_record(static_cast<uint16_t>(rec.first), 0x00, rec.second);
  }
  text += hex_record(0, 0x01, {});
  FlashImage image;
  std::string error;
  ASSERT_TRUE(parse_intel_hex(text, image, error)) << error;
  EXPECT_EQ(image.highest, kMk66FlashBytes);
  const auto writes = halfkay_writes(image);
  std::vector<uint32_t> ours;
  for (size_t i = 0; i + 1 < writes.size(); ++i) ours.push_back(writes[i].address);
  const std::vector<uint32_t> expected = loader_cli_blocks(records, static_cast<uint32_t>(kMk66FlashBytes));
  EXPECT_EQ(ours, expected);
  EXPECT_EQ(expected, (std::vector<uint32_t>{0x0000, 0x1400, 0xFFC00}));
  for (const auto& w : writes) {
    ASSERT_EQ(w.report.size(), 1088u);  // teensy_loader_cli's write_size for 1024-byte blocks
    EXPECT_TRUE(std::all_of(w.report.begin() + 3, w.report.begin() + 64, [](uint8_t b) { return b == 0; }));
  }
  EXPECT_EQ(writes[2].report[0], 0x00);  // 0x0FFC00 little-endian
  EXPECT_EQ(writes[2].report[1], 0xFC);
  EXPECT_EQ(writes[2].report[2], 0x0F);
  EXPECT_EQ(writes[2].report[64 + 1023], 0x5A);
  EXPECT_EQ(writes[1].report[64 + 1], 0x12);
  EXPECT_EQ(writes[1].report[64 + 3], 0xFF);  // unwritten flash reads erased
  const auto& boot = writes.back().report;  // FF FF FF, then zeros
  EXPECT_TRUE(boot[0] == 0xFF && boot[1] == 0xFF && boot[2] == 0xFF);
  EXPECT_TRUE(std::all_of(boot.begin() + 3, boot.end(), [](uint8_t b) { return b == 0; }));
}

#ifdef FF_TOOLCHAIN_HEX
TEST(HalfKay, ImageFromTheCrossToolchainsObjcopy) {
  // objcopy put intel_hex.cpp's bytes at 0x10000 (extended linear address records).
  const std::string data = support::file_contents(FF_TOOLCHAIN_HEX_SOURCE);
  FlashImage image;
  std::string error;
  ASSERT_TRUE(parse_intel_hex(support::file_contents(FF_TOOLCHAIN_HEX), image, error)) << error;
  ASSERT_EQ(image.highest, 0x10000u + data.size());
  EXPECT_TRUE(std::equal(data.begin(), data.end(), image.bytes.begin() + 0x10000));
  const auto writes = halfkay_writes(image);
  // Block 0 (blank, but written: it erases), every block under the data, the boot command.
  const size_t data_blocks = (data.size() + kHalfKayBlock - 1) / kHalfKayBlock;
  ASSERT_EQ(writes.size(), 1 + data_blocks + 1);
  EXPECT_EQ(writes[0].address, 0u);
  EXPECT_EQ(writes[1].address, 0x10000u);
  EXPECT_EQ(writes[1].report[2], 0x01);  // 0x010000 little-endian: byte 2
  EXPECT_EQ(writes[1].report[kHalfKayHeader], static_cast<uint8_t>(data[0]));
}
#endif

}  // namespace
}  // namespace ff::ffctl
