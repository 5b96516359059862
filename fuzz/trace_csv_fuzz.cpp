// libFuzzer target: the sensor trace reader (host/trace_csv) and, for every
// trace it accepts, the 2 kHz pipeline replaying it (host/replay, streamed
// with ff-replay's clock-fault rules): whatever the bytes, no crash, a
// located error for a rejected file, every tick finite, inside [0, 1] and
// [0, 4095], idle without a finger, and every row delivered or counted as
// left out after a clock fault.
//
// Build: clang++ -fsanitize=fuzzer,address,undefined with ff_host + ff_core.
// Defining FF_FUZZ_NO_ENTRY leaves out LLVMFuzzerTestOneInput, so the
// regression test (test/stress/fuzz_regression_test.cpp) can replay saved
// inputs through the same checks with any compiler.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "frictionfield/core/haptic_pipeline.hpp"
#include "frictionfield/core/scenes.hpp"
#include "frictionfield/host/replay.hpp"
#include "frictionfield/host/trace_csv.hpp"

namespace ff::fuzz {

namespace {

void check(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "trace_csv_fuzz: %s\n", what);
    std::abort();
  }
}

// Replays stay short so the fuzzer stays fast: at most 2000 rows over 2 s.
constexpr size_t kMaxRows = 2000;
constexpr uint64_t kMaxSpanUs = 2000000;

}  // namespace

int trace_csv_one_input(const uint8_t* data, size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  std::vector<host::TraceRow> rows;
  host::TraceError error;
  if (!host::read_sensor_trace(in, rows, error)) {
    check(!error.message.empty(), "a rejected trace has no message");
    check(error.line >= 1, "a rejected trace has no line number");
    return 0;
  }
  if (rows.empty() || rows.size() > kMaxRows) return 0;
  uint64_t lo = rows.front().t_us, hi = lo;
  for (const host::TraceRow& r : rows) {
    lo = r.t_us < lo ? r.t_us : lo;
    hi = r.t_us > hi ? r.t_us : hi;
  }
  if (hi - lo > kMaxSpanUs) return 0;

  // The scene and tracker follow from the input, so the fuzzer reaches all.
  const uint8_t pick = static_cast<uint8_t>(size);
  auto pipeline = std::make_unique<HapticPipeline>(pick & 1u ? TrackerConfig::thesis() : TrackerConfig::recommended());
  Condition condition;
  switch ((pick >> 1) % 4u) {
    case 0: condition.scene = scenes::heightmap(Target::Top); break;
    case 1: condition.scene = scenes::frictionmap(Target::Bottom); break;
    case 2: condition.scene = scenes::vortex(); break;
    default: condition.scene = scenes::neutral(); break;
  }
  condition.amplitude.strength = 0.66f;
  check(pipeline->set_condition(condition) == PrepareStatus::Ok, "a built-in scene was refused");
  // Streamed with ff-replay's clock-fault rules: every row is delivered or counted as left out.
  size_t next = 0;
  const host::RowSource source = [&](host::TraceRow& r) { return next < rows.size() ? (r = rows[next++], true) : false; };
  host::ReplayOptions options;
  options.extra_ticks = 600;
  options.max_gap_us = 600'000'000;
  options.max_step_back_us = host::kClockStepBackUs;
  const host::ReplaySummary summary = host::replay(source, *pipeline, [](uint64_t, const TickOutput& t) {
    check(std::isfinite(t.amplitude), "amplitude not finite");
    check(t.dac <= kDacMax, "DAC code above 4095");
    check(is_finite(t.direction), "direction not finite");
    if (t.present) {
      check(t.amplitude >= 0.5f - 0.33f - 1e-6f && t.amplitude <= 0.5f + 0.33f + 1e-6f, "amplitude outside the strength range");
      check(is_finite(t.position), "position not finite");
    } else {
      check(t.amplitude == 0.0f && t.dac == 0, "no finger but the plate is driven");
    }
  }, options);
  check(summary.samples + summary.rows_after_time_jump == rows.size(), "a row neither delivered nor left out");
  check(summary.time_jump || summary.rows_after_time_jump == 0, "rows left out without a clock fault");
  return 0;
}

}  // namespace ff::fuzz

#ifndef FF_FUZZ_NO_ENTRY
extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return ff::fuzz::trace_csv_one_input(data, size);
}
#endif
