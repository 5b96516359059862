// Trace files as ff-tracegen writes them: docs/spec.md#trace-files, read back by the
// project's own reader, truth at every tick, and the bundled traces.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "frictionfield/host/trace_csv.hpp"
#include "support/file_contents.hpp"
#include "support/models/sensor_model.hpp"
#include "trace_writer.hpp"

namespace ff::tracegen {
namespace {

TEST(FormatNumber, ShortestFixedThreeDecimals) {
  EXPECT_EQ(format_number(1.5), "1.5");
  EXPECT_EQ(format_number(2.0), "2");
  EXPECT_EQ(format_number(123.4567), "123.457");
  EXPECT_EQ(format_number(-0.0001), "0");
  EXPECT_EQ(format_number(-3.25), "-3.25");
  EXPECT_EQ(format_number(65535.0), "65535");
  EXPECT_EQ(format_number(std::nan("")), "nan");
  EXPECT_EQ(format_number(HUGE_VAL), "inf");
  EXPECT_EQ(format_number(-HUGE_VAL), "-inf");
  // A NaN with its sign bit set (0 * inf on x86) is still "nan", not printf's "-nan".
  EXPECT_EQ(format_number(-std::nan("")), "nan");
}

TEST(WriteTruthTicks, AnEmptyTraceIsItsHeaderAlone) {
  const GeneratedTrace empty;
  std::stringstream csv;
  EXPECT_EQ(write_truth_ticks(csv, empty), 0u);
  EXPECT_EQ(csv.str(), "t_us,x_true,y_true,vx_true,vy_true,touch\n");
}

TraceOptions faulty() {
  TraceOptions o;
  o.seed = 19;
  o.motion.duration_s = 8.0;
  o.motion.lifts = 1;
  o.motion.rests = 1;
  o.faults.duplicates = 3;
  o.faults.non_finite = 5;
  o.faults.off_screen = 2;
  o.faults.wrap = true;
  return o;
}

TEST(WriteTrace, ReadsBackWithTheProjectsReader) {
  const GeneratedTrace t = generate_trace(faulty());
  std::stringstream csv;
  write_trace(csv, t, true);
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header, "t_us,x,y,touch,x_true,y_true,event");
  csv.seekg(0);
  std::vector<host::TraceRow> rows;
  host::TraceError error;
  ASSERT_TRUE(host::read_sensor_trace(csv, rows, error)) << error.to_string("generated");
  ASSERT_EQ(rows.size(), t.samples.size());
  for (size_t i = 0; i < rows.size(); ++i) {
    const TraceSample& s = t.samples[i];
    EXPECT_EQ(rows[i].t_us, s.t_us);  // 64-bit: past 2^32 intact
    EXPECT_EQ(rows[i].touch, s.touch);
    if (!s.touch) continue;
    for (auto [read, written] : {std::pair<float, double>{rows[i].x, s.x}, {rows[i].y, s.y}}) {
      if (std::isnan(written)) {
        EXPECT_TRUE(std::isnan(read));
      } else if (std::isinf(written)) {
        EXPECT_EQ(static_cast<double>(read), written);
      } else {
        EXPECT_NEAR(static_cast<double>(read), written, 0.0005 + 1e-4 * std::fabs(written));
      }
    }
  }
}

TEST(WriteTruthTicks, EveryTickFromTheFirstReportToTheLast) {
  TraceOptions o;
  o.seed = 23;
  o.motion.duration_s = 3.0;
  o.motion.lifts = 1;
  const GeneratedTrace t = generate_trace(o);
  std::stringstream csv;
  int progress_calls = 0;
  double last_fraction = 0.0;
  const uint64_t rows = write_truth_ticks(csv, t, [&](double f) {
    ++progress_calls;
    EXPECT_GE(f, last_fraction);
    last_fraction = f;
  });
  EXPECT_EQ(last_fraction, 1.0);
  EXPECT_GT(progress_calls, 10);
  const uint64_t t0 = t.samples.front().t_us;
  EXPECT_EQ(rows, (t.end_us() - t0 + 499) / 500 + 1);
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "t_us,x_true,y_true,vx_true,vy_true,touch");
  uint64_t k = 0, lifted = 0;
  while (std::getline(csv, line)) {
    std::istringstream f(line);
    std::string cell[6];
    for (auto& c : cell) std::getline(f, c, ',');
    const uint64_t t_us = std::stoull(cell[0]);
    ASSERT_EQ(t_us, t0 + 500 * k);
    const TrueState s = t.truth_at(t_us);
    EXPECT_EQ(cell[5], s.touching ? "1" : "0");
    if (s.touching) {
      EXPECT_NEAR(std::stod(cell[1]), s.position.x, 0.0005);
      EXPECT_NEAR(std::stod(cell[4]), s.velocity.y, 0.0005 + 1e-6 * std::fabs(s.velocity.y));
    } else {
      EXPECT_EQ(cell[1], "nan");
      ++lifted;
    }
    ++k;
  }
  EXPECT_EQ(k, rows);
  EXPECT_GT(lifted, 150000u / 500u - 12u);  // one lift of at least 0.15 s
}

// test/traces/generate.sh's invocations, as options. The files were written
// before the finger and sensor effects of issue 14 existed: with all of them
// off (the default) the generator must still reproduce them exactly.
TEST(BundledTraces, GeneratorStillReproducesEveryGeneratedOneBitForBit) {
  struct Bundled {
    const char* file;
    TraceOptions options;
    bool events;
  };
  auto base = [](Strategy s, double duration_s, uint64_t seed) {
    TraceOptions o;
    o.motion.strategy = s;
    o.motion.duration_s = duration_s;
    o.seed = seed;
    o.sensor.noise_px = kNoiseLowPx;
    return o;
  };
  std::vector<Bundled> bundled;
  bundled.push_back({"gen_along_low.csv", base(Strategy::Along, 10.0, 1), false});
  TraceOptions across = base(Strategy::Across, 10.0, 2);
  across.sensor.noise_px = kNoiseHighPx;
  across.sensor.quantum_px = 1.0;
  bundled.push_back({"gen_across_high_px.csv", across, false});
  TraceOptions rests = base(Strategy::Mixed, 8.0, 3);
  rests.sensor.quantum_px = kZForceQuantumPx;
  rests.motion.rests = 2;
  rests.motion.lifts = 1;
  bundled.push_back({"gen_mixed_zforce_rests.csv", rests, false});
  TraceOptions faults = base(Strategy::Mixed, 8.0, 4);  // --all-faults
  faults.faults.missing = 2;
  faults.faults.late = 2;
  faults.faults.jumps = 2;
  faults.faults.duplicates = 3;
  faults.faults.non_finite = 2;
  faults.faults.off_screen = 2;
  faults.motion.rests = 2;
  faults.motion.lifts = 2;
  bundled.push_back({"gen_all_faults.csv", faults, true});
  TraceOptions wrap = base(Strategy::Along, 5.0, 5);
  wrap.faults.wrap = true;
  bundled.push_back({"gen_clock_wrap.csv", wrap, true});
  for (const Bundled& b : bundled) {
    std::ostringstream csv;
    write_trace(csv, generate_trace(b.options), b.events);
    std::istringstream made(csv.str()), stored(support::file_contents(std::string(FF_TRACE_DIR) + "/" + b.file));
    std::string a, s;
    size_t line = 0;
    for (;;) {
      const bool more_a = static_cast<bool>(std::getline(made, a));
      bool more_s = static_cast<bool>(std::getline(stored, s));
      ++line;
      // ff-tracegen's metadata ('#' lines, first and last) is not write_trace's: the seed is the test's.
      while (more_s && s.rfind("#", 0) == 0) {
        if (s.rfind("# seed: ", 0) == 0) {
          EXPECT_EQ(s, "# seed: " + std::to_string(b.options.seed)) << b.file;
        }
        more_s = static_cast<bool>(std::getline(stored, s));
      }
      ASSERT_EQ(more_a, more_s) << b.file << ": lengths differ at line " << line << ": run test/traces/generate.sh";
      if (!more_a) break;
      ASSERT_EQ(a, s) << b.file << ": line " << line << " differs: run test/traces/generate.sh";
    }
    EXPECT_GT(line, 500u) << b.file;
  }
}

TEST(BundledTraces, EveryTraceIsReadableAndDescribedInTheReadme) {
  const std::string readme = support::file_contents(std::string(FF_TRACE_DIR) + "/README.md");
  const char* kTraces[] = {
      "gen_along_low.csv", "gen_across_high_px.csv", "gen_mixed_zforce_rests.csv", "gen_all_faults.csv",
      "gen_clock_wrap.csv", "edge_header_only.csv", "edge_single_sample.csv", "edge_no_finger.csv",
      "edge_columns_reordered.csv", "edge_duplicate_times.csv", "edge_nan_inf.csv", "edge_off_screen.csv",
      "edge_jump.csv", "edge_clock_wrap.csv", "edge_gaps.csv", "edge_lift_and_return.csv", "edge_rest.csv",
  };
  for (const char* name : kTraces) {
    EXPECT_NE(readme.find(std::string("`") + name + "`"), std::string::npos) << name << " missing from README.md";
    std::vector<host::TraceRow> rows;
    host::TraceError error;
    EXPECT_TRUE(host::read_sensor_trace_file(std::string(FF_TRACE_DIR) + "/" + name, rows, error))
        << error.to_string(name);
  }
}

}  // namespace
}  // namespace ff::tracegen
