// The per-class report (class_report.hpp): its cases, its share of slow
// ticks against a count by hand, and its tables and CSV well formed (every
// row as many cells as its header), so that docs/tracking.md and the plots
// read what the benchmark measured.
#include "class_report.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include "support/text_lines.hpp"

namespace ff::bench {
namespace {

size_t count_of(const std::string& line, char c) { return static_cast<size_t>(std::count(line.begin(), line.end(), c)); }

// A Markdown table at the top of `text`: a header, a separator of as many
// cells (only '-' and ':' in them), then `rows` rows of as many cells.
void expect_markdown_table(const std::string& text, size_t rows) {
  const std::vector<std::string> lines = support::lines_of(text);
  ASSERT_GE(lines.size(), rows + 2) << text;
  const size_t pipes = count_of(lines[0], '|');
  EXPECT_GT(pipes, 3u) << lines[0];
  EXPECT_EQ(lines[1].find_first_not_of("|-:"), std::string::npos) << lines[1];
  for (size_t i = 1; i < rows + 2; ++i) EXPECT_EQ(count_of(lines[i], '|'), pipes) << lines[i];
  if (lines.size() > rows + 2) {
    EXPECT_EQ(lines[rows + 2], "") << "the table ends with its rows";
  }
}

std::vector<ClassRow> two_classes() {
  std::vector<ClassRow> rows;
  for (const char* trace_class : {"white-200hz", "tremor"}) {
    for (const char* tracker : {"thesis", "recommended()"}) {
      ClassRow r{trace_class, tracker, {}, 0.1};
      r.metrics.heightmap_rms = 0.2;
      r.metrics.frictionmap_rms = 0.05;
      r.metrics.heightmap_rest_rms = 0.3;
      r.metrics.stops = 4;
      rows.push_back(r);
    }
  }
  return rows;
}

TEST(ClassReport, ClassCasesAreTheStandardSetNamedByTheirClass) {
  const tracegen::TraceClass* tremor = tracegen::find_trace_class("tremor");
  ASSERT_NE(tremor, nullptr);
  const std::vector<TrackCase> cases = class_cases(*tremor, 4.0);
  const std::vector<TrackCase> standard = standard_cases(tracegen::kNoiseLowPx, 4.0);
  ASSERT_EQ(cases.size(), standard.size());
  for (size_t i = 0; i < cases.size(); ++i) {
    EXPECT_EQ(cases[i].name, "tremor " + standard[i].name);
    EXPECT_EQ(cases[i].options.seed, standard[i].options.seed);
  }
}

TEST(ClassReport, SlowShareIsTheMovingTicksAt20To70PxPerSecond) {
  PreparedCase c;
  for (double speed : {5.0, 19.0, 20.0, 45.0, 70.0, 71.0, 300.0}) {
    TickTruth t;
    t.state.touching = true;
    t.state.velocity = {0.6 * speed, 0.8 * speed};
    c.ticks.push_back(t);
  }
  TickTruth resting;
  resting.state.touching = true;
  resting.state.resting = true;
  resting.state.velocity = {40.0, 0.0};  // at rest by the truth: not a moving tick
  c.ticks.push_back(resting);
  std::vector<PreparedCase> cases;
  cases.push_back(std::move(c));
  // Moving (>= 10 px/s): 19, 20, 45, 70, 71, 300; of those 20, 45 and 70 are slow.
  EXPECT_DOUBLE_EQ(slow_share(cases, 10.0), 3.0 / 6.0);
  EXPECT_DOUBLE_EQ(slow_share(cases, 50.0), 1.0 / 3.0);  // 70, 71, 300
  EXPECT_DOUBLE_EQ(slow_share(cases, 1000.0), 0.0);      // nothing moves that fast
}

TEST(ClassReport, TablesAreWellFormed) {
  const std::vector<ClassRow> rows = two_classes();
  std::ostringstream classes, rests;
  write_class_report(classes, rows, 30.0, kClassMovingSpeedPxS);
  expect_markdown_table(classes.str(), rows.size());
  write_rest_report(rests, rows);
  expect_markdown_table(rests.str(), rows.size());
  std::vector<StartFloorRow> floors(2);
  floors[0].trace_class = "white-200hz";
  floors[1].trace_class = "tremor";
  std::ostringstream floor_table;
  write_start_floor(floor_table, floors);
  expect_markdown_table(floor_table.str(), floors.size());
}

TEST(ClassReport, EveryCsvRowHasItsHeadersFields) {
  const std::vector<ClassRow> rows = two_classes();
  std::vector<StartFloorRow> floors(1);
  floors[0].trace_class = "tremor";
  std::vector<LookaheadRow> lookahead(1);
  lookahead[0].trace_class = "white-200hz";
  std::ostringstream csv;
  write_class_csv(csv, rows, floors, lookahead);
  const std::vector<std::string> lines = support::lines_of(csv.str());
  ASSERT_EQ(lines.size(), rows.size() + 1) << csv.str();
  const size_t fields = count_of(lines[0], ',');
  EXPECT_GT(fields, 30u);
  for (size_t i = 1; i < lines.size(); ++i) EXPECT_EQ(count_of(lines[i], ','), fields) << lines[i];
}

}  // namespace
}  // namespace ff::bench
