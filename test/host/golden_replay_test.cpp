// Golden traces: every bundled trace replayed through the whole pipeline and
// compared with its stored output. The stored outputs were written by the
// code they test (FF_UPDATE_GOLDEN=1): they are change detectors, not proofs.
// Beside them, GoldenOutputsObeyTheSpec checks every stored row against an
// independent double-precision form of the spec's rendering. Tolerances: position 1e-3 px, direction
// 1e-4, amplitude 1e-5 (well under one DAC LSB = 2.4e-4), DAC code +-1 (a
// half-code rounding may flip between compilers).
// FF_UPDATE_GOLDEN=1 rewrites the files after an intended change (or
// test/traces/generate.sh with the build folder). They are change detectors;
// replay_test.cpp checks the timing and the end of a replay independently.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <sstream>

#include "support/reference/reference_scene.hpp"
#include "support/reference/spec_scenes.hpp"
#include "frictionfield/host/replay.hpp"
#include "frictionfield/host/scene_spec.hpp"

namespace ff::host {
namespace {

struct GoldenCase {
  std::string trace, scene, target, tracker;
  float strength = 1.0f;
  int stride = 1;
  std::string golden_name() const {
    return trace.substr(0, trace.size() - 4) + "." + scene + "-" + tracker + ".golden.csv";
  }
};

std::vector<GoldenCase> load_manifest() {
  std::vector<GoldenCase> cases;
  std::ifstream in(std::string(FF_TRACE_DIR) + "/golden.txt");
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream s(line);
    GoldenCase c;
    s >> c.trace >> c.scene >> c.target >> c.strength >> c.tracker >> c.stride;
    if (s) cases.push_back(c);
  }
  return cases;
}

std::vector<std::string> render(const GoldenCase& c) {
  SceneSpec spec;
  spec.scene = c.scene;
  spec.target = c.target;
  spec.strength = c.strength;
  Condition cond;
  std::string err;
  EXPECT_TRUE(make_condition(spec, cond, err)) << err;
  auto p = std::make_unique<HapticPipeline>(c.tracker == "thesis" ? TrackerConfig::thesis()
                                                                   : TrackerConfig::recommended());
  EXPECT_EQ(p->set_condition(cond), PrepareStatus::Ok);
  std::vector<TraceRow> rows;
  TraceError terr;
  EXPECT_TRUE(read_sensor_trace_file(std::string(FF_TRACE_DIR) + "/" + c.trace, rows, terr)) << terr.message;
  std::vector<std::string> lines;
  uint64_t k = 0;
  replay(rows, *p, [&](uint64_t t, const TickOutput& o) {
    if (k++ % static_cast<uint64_t>(c.stride) != 0) return;
    std::ostringstream row;
    write_replay_row(row, t, o);
    std::string r = row.str();
    r.pop_back();
    lines.push_back(r);
  }, 200);  // 100 ms after the last sample: lift-off and time-outs play out
  return lines;
}

std::vector<double> fields(const std::string& line) {
  std::vector<double> v;
  std::istringstream s(line);
  std::string f;
  while (std::getline(s, f, ',')) v.push_back(std::strtod(f.c_str(), nullptr));
  return v;
}

class GoldenReplay : public ::testing::TestWithParam<GoldenCase> {};

TEST_P(GoldenReplay, MatchesStoredOutput) {
  const GoldenCase& c = GetParam();
  const std::vector<std::string> got = render(c);
  const std::string path = std::string(FF_TRACE_DIR) + "/" + c.golden_name();
  if (std::getenv("FF_UPDATE_GOLDEN") != nullptr) {
    std::ofstream out(path);
    write_metadata(out, {{"golden", c.trace + " --scene " + c.scene + " --target " + c.target + " --strength " +
                                        std::to_string(c.strength) + " --tracker " + c.tracker + ", every " +
                                        std::to_string(c.stride) + " tick(s)"},
                         {"note", "a change detector: regenerate with test/traces/generate.sh after an intended change"}});
    write_replay_header(out);
    for (const std::string& l : got) out << l << "\n";
    GTEST_SKIP() << "rewrote " << path;
  }
  std::ifstream in(path);
  ASSERT_TRUE(in) << path << " missing: run with FF_UPDATE_GOLDEN=1";
  std::string line;
  while (std::getline(in, line) && (line.empty() || line[0] == '#')) {
  }
  EXPECT_EQ(line, "t_us,x,y,vx,vy,amplitude,dac,present");
  size_t i = 0;
  const double tol[] = {0, 1e-3, 1e-3, 1e-4, 1e-4, 1e-5, 1, 0};  // DAC: rounding may flip at a half code
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    ASSERT_LT(i, got.size()) << "golden has more ticks";
    const std::vector<double> want = fields(line), have = fields(got[i]);
    ASSERT_EQ(want.size(), 8u);
    ASSERT_EQ(have.size(), 8u);
    for (int f = 0; f < 8; ++f) {
      ASSERT_NEAR(have[f], want[f], tol[f] + 1e-9) << c.golden_name() << " row " << i + 2 << " column " << f + 1;
    }
    ++i;
  }
  EXPECT_EQ(i, got.size()) << "replay has more ticks than the golden";
}

// The independent check: each stored row's amplitude follows from its own
// position and direction by docs/spec.md#rendering and #amplitude, computed in
// double from the spec (test/support/reference), not by the core:
//   heightmap:   A_s = 0.5 - s (vx, vy) . G / (2 max|G|)
//   frictionmap: A_s = 0.5 + s (S5((30 - |u|) / 20) - 0.5)
// and dac = round(4095 A_s) (the default calibration), or the idle output
// (0, code 0) without a finger.
TEST_P(GoldenReplay, GoldenOutputsObeyTheSpec) {
  const GoldenCase& c = GetParam();
  const double T = c.target == "top" ? -200.0 : (c.target == "bottom" ? 200.0 : 0.0);
  const double s = c.strength;
  const reference::ReferenceScene heightmap(reference::spec::heightmap(T), reference::kEveryPixel);
  const reference::ReferenceScene frictionmap(reference::spec::frictionmap(T));
  const double max_gradient = heightmap.max_gradient();
  std::ifstream in(std::string(FF_TRACE_DIR) + "/" + c.golden_name());
  ASSERT_TRUE(in);
  std::string line;
  bool header_seen = false;
  int checked = 0;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;  // metadata
    if (!header_seen) {
      header_seen = true;
      continue;
    }
    const std::vector<double> v = fields(line);
    ASSERT_EQ(v.size(), 8u);
    const double x = v[1], y = v[2], vx = v[3], vy = v[4], amplitude = v[5], dac = v[6], present = v[7];
    EXPECT_NEAR(dac, std::floor(amplitude * 4095.0 + 0.5), 1.0) << line;
    if (present == 0.0) {  // idle: the plate rests
      EXPECT_EQ(amplitude, 0.0) << line;
      EXPECT_EQ(dac, 0.0) << line;
      continue;
    }
    if (amplitude == 0.0 && dac == 0.0 && vx == 0.0 && vy == 0.0) continue;  // sticky output
    double expected = 0.5;
    if (c.scene == "heightmap") {
      const reference::DVec g = heightmap.field(x, y);
      expected = 0.5 - s * (vx * g.x + vy * g.y) / (2.0 * max_gradient);
    } else {
      expected = 0.5 + s * (frictionmap.profile(x, y) - 0.5);
    }
    // 1e-3: the stored position is rounded to 1e-3 px and direction to 1e-5,
    // and the core's max|G| is searched between pixel centres.
    EXPECT_NEAR(amplitude, expected, 1e-3) << c.golden_name() << ": " << line;
    ++checked;
  }
  if (c.trace != "edge_no_finger.csv") {
    EXPECT_GT(checked, 0) << c.golden_name();
  }
}

INSTANTIATE_TEST_SUITE_P(Traces, GoldenReplay, ::testing::ValuesIn(load_manifest()),
                         [](const ::testing::TestParamInfo<GoldenCase>& info) {
                           std::string n = info.param.golden_name();
                           n = n.substr(0, n.size() - 11);
                           for (char& ch : n) if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return n;
                         });

}  // namespace
}  // namespace ff::host
