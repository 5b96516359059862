#include "frictionfield/host/trace_csv.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

namespace ff::host {
namespace {

bool parse(const std::string& text, std::vector<TraceRow>& rows, TraceError& err) {
  std::istringstream in(text);
  return read_sensor_trace(in, rows, err);
}

TEST(TraceCsv, ReadsAnyColumnOrderAndIgnoresExtraColumns) {
  std::vector<TraceRow> rows;
  TraceError err;
  ASSERT_TRUE(parse("x,touch,t_us,y,x_true,y_true\n10.5,1,5000000000,20,10,20\n,0,5000005000,,0,0\n", rows, err))
      << err.message;
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].t_us, 5000000000ull);  // beyond 2^32
  EXPECT_FLOAT_EQ(rows[0].x, 10.5f);
  EXPECT_FLOAT_EQ(rows[0].y, 20.0f);
  EXPECT_TRUE(rows[0].touch);
  EXPECT_FALSE(rows[1].touch);  // no finger: empty x, y allowed
}

TEST(TraceCsv, AnEmptyLastFieldIsAField) {
  // "5,0,," ends in an empty y: four fields, not three.
  std::vector<TraceRow> rows;
  TraceError err;
  ASSERT_TRUE(parse("t_us,touch,x,y\n5,0,,\n10,1,3,4\n", rows, err)) << err.message;
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_FALSE(rows[0].touch);
  EXPECT_EQ(rows[1].y, 4.0f);
}

TEST(TraceCsv, TakesSpacesAroundFieldsAndWindowsLineEnds) {
  std::vector<TraceRow> rows;
  TraceError err;
  ASSERT_TRUE(parse(" t_us , x,y ,touch\r\n 5 , 1.5,2 , 1\r\n", rows, err)) << err.message;
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].t_us, 5u);
  EXPECT_EQ(rows[0].x, 1.5f);
  EXPECT_EQ(rows[0].y, 2.0f);
  EXPECT_TRUE(rows[0].touch);
}

TEST(TraceCsv, AMissingFileSaysWhy) {
  std::vector<TraceRow> rows;
  TraceError err;
  EXPECT_FALSE(read_sensor_trace_file(::testing::TempDir() + "/ff_no_such_trace.csv", rows, err));
  EXPECT_EQ(err.message, "cannot open: No such file or directory");
  EXPECT_EQ(err.line, 0u);  // the file, not a line of it
  // A folder opens on Linux and reads as nothing: it was called an empty file with no header.
  EXPECT_FALSE(read_sensor_trace_file(::testing::TempDir(), rows, err));
  EXPECT_EQ(err.message, "is a folder, not a file");
}

TEST(TraceCsv, TakesStampsUpTo2To53) {
  std::vector<TraceRow> rows;
  TraceError err;
  ASSERT_TRUE(parse("t_us,x,y,touch\n9007199254740992,1,2,1\n", rows, err)) << err.message;
  EXPECT_EQ(rows[0].t_us, kMaxTraceTimeUs);
  EXPECT_EQ(kMaxTraceTimeUs, 9007199254740992ull);  // 2^53
}

TEST(TraceCsv, KeepsNonFiniteCoordinatesForTheTrackerToJudge) {
  std::vector<TraceRow> rows;
  TraceError err;
  ASSERT_TRUE(parse("t_us,x,y,touch\n0,nan,5,1\n5,inf,-inf,1\n", rows, err));
  EXPECT_TRUE(std::isnan(rows[0].x));
  EXPECT_TRUE(std::isinf(rows[1].y));
}

TEST(TraceCsv, ErrorsNameLineAndColumn) {
  struct Case { const char* text; size_t line, column; const char* says; };
  const Case cases[] = {
      {"", 1, 0, "empty file"},
      {"t,x,y\n", 1, 0, "header"},
      {"t_us,x,y,touch\n0,1,2,1\n5,1\n", 3, 3, "fields"},
      {"t_us,x,y,touch\n-5,1,2,1\n", 2, 1, "t_us must be a non-negative integer"},
      {"t_us,x,y,touch\n0,1,2,+1\n", 2, 4, "touch must be 0 or 1"},
      {"t_us,x,y,touch\n0,1,2,-0\n", 2, 4, "touch must be 0 or 1"},
      {"t_us,x,y,touch\n1.5,1,2,1\n", 2, 1, "t_us"},
      {"t_us,x,y,touch\n0,1,2,2\n", 2, 4, "touch"},
      {"t_us,x,y,touch\n0,abc,2,1\n", 2, 2, "x is not a number"},
      {"t_us,x,y,touch\n0,1,,1\n", 2, 3, "y is not a number"},
      // A stamp near 2^64 hung the replay (its tick times wrapped): found by fuzz/trace_csv.
      {"t_us,x,y,touch\n18446744073709551610,100,0,0\n", 2, 1, "at most 2^53"},
      {"t_us,x,y,touch\n9007199254740993,100,0,0\n", 2, 1, "at most 2^53"},
      // A file merged or shifted by hand: a column named twice, a row wider than the header.
      {"t_us,x,y,touch,t_us\n1000,400,240,1,5\n", 1, 5, "column 't_us' is named twice"},
      {"t_us,x,y,touch\n1000,400,240,1\n1500,401,240,1,junk,more\n", 3, 5, "more fields than the header names (4)"},
  };
  for (const Case& c : cases) {
    std::vector<TraceRow> rows;
    TraceError err;
    EXPECT_FALSE(parse(c.text, rows, err)) << c.text;
    EXPECT_EQ(err.line, c.line) << c.text;
    EXPECT_EQ(err.column, c.column) << c.text;
    EXPECT_NE(err.message.find(c.says), std::string::npos) << err.message;
  }
  TraceError e{3, 2, "bad"};
  EXPECT_EQ(e.to_string("a.csv"), "a.csv:3:2: bad");
}

TEST(TraceCsv, AnErrorInALastLineWithoutItsEndSaysTheRecordingWasCutShort) {
  const std::string hint = "(the last line, without its end: a recording cut short? delete it to read the rest)";
  std::vector<TraceRow> rows;
  TraceError err;
  EXPECT_FALSE(parse("t_us,x,y,touch\n0,1,2,1\n5,1", rows, err));
  EXPECT_EQ(err.message, "expected at least 4 fields, got 2 " + hint);
  EXPECT_EQ(err.line, 3u);
  rows.clear();
  EXPECT_FALSE(parse("t_us,x,y,touch\n0,1,2,1\n5,1\n", rows, err));  // ended: a bad row, not a cut
  EXPECT_EQ(err.message, "expected at least 4 fields, got 2");
  rows.clear();
  EXPECT_FALSE(parse("t_us,x,y,touch\n5,1\n0,1,2,1", rows, err));  // not the last line
  EXPECT_EQ(err.message, "expected at least 4 fields, got 2");
  rows.clear();
  EXPECT_TRUE(parse("t_us,x,y,touch\n0,1,2,1\n5,1,2,0", rows, err)) << err.message;  // whole without its end
  EXPECT_EQ(rows.size(), 2u);
}

TEST(TraceCsv, WritesTheReplayFormat) {
  std::ostringstream out;
  write_replay_header(out);
  TickOutput t;
  t.position = {1.5f, 2.25f};
  t.direction = {0.6f, -0.8f};
  t.amplitude = 0.25f;
  t.dac = 1024;
  write_replay_row(out, 5000000000ull, t);
  t.present = true;
  write_replay_row(out, 7, TickOutput{});
  EXPECT_EQ(out.str(),
            "t_us,x,y,vx,vy,amplitude,dac,present\n5000000000,1.500,2.250,0.60000,-0.80000,0.250000,1024,0\n"
            "7,0.000,0.000,0.00000,0.00000,0.000000,0,0\n");
  std::ostringstream present;
  write_replay_row(present, 1, t);
  EXPECT_EQ(present.str().back(), '\n');
  EXPECT_EQ(present.str().substr(present.str().size() - 3), ",1\n");
}

TEST(TraceCsv, SkipsMetadataLinesAndAByteOrderMark) {
  std::vector<TraceRow> rows;
  TraceError err;
  ASSERT_TRUE(parse("\xEF\xBB\xBF# tool: ff-replay 0.1.0\n#scene: x\nt_us,x,y,touch\n# in between\n5,1,2,1\n"
                    "# summary: ticks=1\n",
                    rows, err))
      << err.message;
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].t_us, 5u);
  EXPECT_EQ(rows[0].line, 5u);  // each row knows its own line, comments counted
  // Errors still name the file's own line numbers.
  EXPECT_FALSE(parse("# a\nt_us,x,y,touch\n# b\n5,z,2,1\n", rows, err));
  EXPECT_EQ(err.line, 4u);
}

TEST(TraceCsv, MetadataIsOneCommentLinePerKey) {
  std::ostringstream out;
  write_metadata(out, {{"tool", "ff-replay"}, {"scene", "two\nlines"}});
  EXPECT_EQ(out.str(), "# tool: ff-replay\n# scene: two lines\n");
}

TEST(TraceCsv, TheReaderStreamsRowByRow) {
  std::istringstream in("t_us,x,y,touch\n1,1,1,1\n2,2,2,1\nbad\n");
  SensorTraceReader reader(in);
  TraceError err;
  ASSERT_TRUE(reader.read_header(err));
  TraceRow row;
  ASSERT_TRUE(reader.next(row, err));
  EXPECT_EQ(row.t_us, 1u);
  ASSERT_TRUE(reader.next(row, err));
  EXPECT_EQ(row.t_us, 2u);
  EXPECT_FALSE(reader.next(row, err));
  EXPECT_EQ(err.line, 4u);  // an error, not the end
}

TEST(TraceCsv, EachRowAndEachCallStartsClean) {
  // One row and one error object reused, as a streaming caller does: a row
  // without a finger or coordinates does not keep the last row's, and the
  // end of the file is the end (no error), whatever the last call said.
  std::istringstream in("t_us,x,y,touch\n1,7,8,1\n2,,,0\n");
  SensorTraceReader reader(in);
  TraceError err{9, 9, "from an earlier file"};
  ASSERT_TRUE(reader.read_header(err));
  TraceRow row;
  ASSERT_TRUE(reader.next(row, err));
  EXPECT_TRUE(err.message.empty()) << err.message;
  ASSERT_TRUE(reader.next(row, err));
  EXPECT_FALSE(row.touch);
  EXPECT_EQ(row.x, 0.0f);
  EXPECT_EQ(row.y, 0.0f);
  err = {9, 9, "from an earlier call"};
  EXPECT_FALSE(reader.next(row, err));
  EXPECT_TRUE(err.message.empty()) << err.message;
  EXPECT_EQ(err.line, 0u);
}

TEST(TraceCsv, ARecordingsTakenTimesAreReadWithTheirRows) {
  std::istringstream in("t_us, x ,y,touch , taken_us \r\n1,1,1,1, 500 \r\n# a comment\n\n2,2,2,1,-1\n3,3,3,1,x\n");
  SensorTraceReader reader(in);
  TraceError err;
  ASSERT_TRUE(reader.read_header(err));
  EXPECT_EQ(reader.column("taken_us"), 4);  // names trimmed
  EXPECT_EQ(reader.column("note"), -1);
  TraceRow row;
  ASSERT_TRUE(reader.next(row, err));
  EXPECT_EQ(row.taken_us, 500);
  ASSERT_TRUE(reader.next(row, err));
  EXPECT_EQ(row.t_us, 2u);
  EXPECT_EQ(row.taken_us, -1);  // the firmware did not say
  EXPECT_FALSE(reader.next(row, err));
  EXPECT_EQ(err.to_string("r.csv"), "r.csv:6:5: taken_us must be a time in us or -1 (got 'x')");
}

TEST(TraceCsv, ATraceWithoutTakenTimesLeavesThemUnknown) {
  std::istringstream in("t_us,x,y,touch,note\n1,1,1,1,500\n");
  std::vector<TraceRow> rows;
  TraceError err;
  ASSERT_TRUE(read_sensor_trace(in, rows, err)) << err.message;
  EXPECT_EQ(rows.at(0).taken_us, -1);
}

TEST(TraceCsv, MetadataBeforeTheHeaderIsFoundByItsKeyInEitherForm) {
  std::istringstream in(
      "# ffctl 0.1.0 record -o r.csv\n#  sensor-profile --white-noise-px 2 \n# scene_hash: ab12\n"
      "# sensor-profiles other\nt_us,x,y,touch\n# sensor-profile late\n1,1,1,1\n");
  SensorTraceReader reader(in);
  TraceError err;
  ASSERT_TRUE(reader.read_header(err));
  TraceRow row;
  ASSERT_TRUE(reader.next(row, err));
  EXPECT_EQ(reader.metadata("sensor-profile"), "--white-noise-px 2");  // ffctl's "key value", trimmed
  EXPECT_EQ(reader.metadata("scene_hash"), "ab12");                    // the other tools' "key: value"
  EXPECT_EQ(reader.metadata("ffctl"), "0.1.0 record -o r.csv");
  EXPECT_EQ(reader.metadata("date"), "");  // none; and a line after the header is a row's note, not metadata
}

}  // namespace
}  // namespace ff::host
