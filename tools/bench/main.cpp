// ff-bench: every way the core can evaluate a scene, side by side: amplitude
// error against an independent double-precision reference, memory, and host
// cost (Google Benchmark). Cortex-M4F costs come from ff-m4bench under qemu;
// make_report.py merges both into docs/benchmarks.md.
#include <CLI/CLI.hpp>

#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "frictionfield/host/cli_conventions.hpp"
#include "frictionfield/host/output_file.hpp"
#include "frictionfield/host/trace_csv.hpp"
#include "accuracy.hpp"
#include "bench_cases.hpp"
#include "bench_workload.hpp"
#include "host_costs.hpp"

namespace {

using namespace ff;
using namespace ff::bench;

constexpr const char* kDescription =
    "ff-bench: evaluation strategies of every scene, error against cost.\n"
    "\n"
    "For each scene (the built-in ones and general sums of 1, 3 and 6 elements) and each strategy\n"
    "(closed form; tables at 1, 2, 4, 8, 16 px, float and int16, tabulated gradient or height +\n"
    "central differences, bilinear): the amplitude error against a double-precision reference written\n"
    "from docs/spec.md, over a grid between pixel centres and 16 directions of motion (max and RMS, in DAC\n"
    "LSB = 1/4095); table and plan bytes; host ns per evaluation, us per preparation, ns per whole\n"
    "tick with a finger moving; ns per tracker update for each tracker configuration.\n"
    "Writes host_cases.csv and host_trackers.csv into --out.";

constexpr size_t kTableBytes = 3u * 1024u * 1024u;

struct CaseResult {
  BenchCase bench_case;
  std::string id;
  std::string strategy;
  PrepareStatus status = PrepareStatus::Ok;
  // As the Teensy would prepare it (one table slot, the watchdog's budget):
  // TableTooLarge or TooCostlyToPrepare where it refuses the strategy.
  PrepareStatus device_status = PrepareStatus::Ok;
  PlanStats stats;
  Accuracy accuracy;
  double max_g_ref = 0.0;
  uint32_t checksum = 0;
};

const char* rendering_name(Rendering r) {
  return r == Rendering::Constant ? "constant" : (r == Rendering::PositionOnly ? "position" : "directional");
}

bool in_smoke_set(const BenchCase& c) {
  return c.strategy.evaluation == Evaluation::ClosedForm || c.strategy.table.spacing_px >= 8.0f;
}

void measure_scene_accuracy(const ReferenceGrid& grid, std::vector<CaseResult*>& results, int threads) {
  std::atomic<size_t> next{0};
  auto work = [&]() {
    auto memory = std::make_unique<unsigned char[]>(kTableBytes + 8);
    void* table = reinterpret_cast<void*>((reinterpret_cast<uintptr_t>(memory.get()) + 7u) & ~uintptr_t{7u});
    EvalPoint points[kEvalPoints];
    make_eval_points(points);
    for (size_t i = next++; i < results.size(); i = next++) {
      CaseResult& r = *results[i];
      ScenePlan plan;
      // Every strategy, those past the Teensy's table slot or preparation budget too.
      r.device_status = plan.prepare(case_definition(r.bench_case), table, kTableSlotBytes);
      r.status = plan.prepare(case_definition(r.bench_case), table, kTableBytes, UINT32_MAX);
      if (r.status != PrepareStatus::Ok) continue;
      r.stats = plan.stats();
      r.accuracy = grid.measure(plan);
      r.max_g_ref = grid.max_gradient();
      r.checksum = eval_checksum(plan, points, kEvalPoints);
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
}

std::string number(double v, const char* format = "%.6g") {
  if (!std::isfinite(v)) return "";
  char text[64];
  std::snprintf(text, sizeof(text), format, v);
  return text;
}

std::string lookup(const std::map<std::string, double>& m, const std::string& key, const char* format) {
  const auto it = m.find(key);
  return it == m.end() ? "" : number(it->second, format);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{kDescription, "ff-bench"};
  bool smoke = false;
  bool timing = true;
  double grid_step = 1.0;
  double min_time = 0.05;
  int threads = 2;
  std::string out_dir = ".";
  std::string filter;
  app.add_flag("--smoke", smoke, "tiny grid, closed forms and 8/16 px tables, 2 iterations per benchmark");
  app.add_option("--grid-step", grid_step, "spacing of the error grid in px (default 1; --smoke: 40)")
      ->check(CLI::Range(0.25, 200.0));
  app.add_option("--min-time", min_time, "Google Benchmark minimum time per benchmark, seconds")
      ->check(CLI::Range(0.001, 10.0));
  app.add_option("--threads", threads, "threads for the error grids")->check(CLI::Range(1, 64));
  app.add_option("--out", out_dir, "folder for host_cases.csv and host_trackers.csv");
  app.add_option("--filter", filter, "only cases whose id contains this text");
  app.add_flag("!--no-timing", timing, "errors and memory only (no Google Benchmark)");
  if (const int code = ff::host::parse_command_line(app, argc, argv); code >= 0) return code;
  if (smoke && app.count("--grid-step") == 0) grid_step = 40.0;

  std::vector<CaseResult> results;
  for (int i = 0; i < case_count(); ++i) {
    CaseResult r;
    r.bench_case = case_at(i);
    char text[96];
    case_id(r.bench_case, text, sizeof(text));
    r.id = text;
    strategy_label(r.bench_case.strategy, scene_definition(r.bench_case.scene).rendering, text, sizeof(text));
    r.strategy = text;
    if (!filter.empty() && r.id.find(filter) == std::string::npos) continue;
    if (smoke && !in_smoke_set(r.bench_case)) continue;
    results.push_back(r);
  }

  // Errors: one reference grid per scene, its strategies in parallel.
  for (int s = 0; s < kSceneCount; ++s) {
    std::vector<CaseResult*> of_scene;
    for (CaseResult& r : results) {
      if (static_cast<int>(r.bench_case.scene) == s) of_scene.push_back(&r);
    }
    if (of_scene.empty()) continue;
    const ReferenceGrid grid(reference_scene_for(static_cast<SceneId>(s)), grid_step);
    std::fprintf(stderr, "errors: %-22s %zu strategies, %zu points x %d directions, max|G| %.9g\n",
                 scene_name(static_cast<SceneId>(s)), of_scene.size(), grid.points(), kDirections,
                 grid.max_gradient());
    measure_scene_accuracy(grid, of_scene, threads);
  }

  int failures = 0;
  for (const CaseResult& r : results) {
    const bool bad = r.status != PrepareStatus::Ok || !std::isfinite(r.accuracy.max_lsb) ||
                     r.accuracy.max_lsb > 4095.0 || r.accuracy.samples == 0;
    if (bad) {
      ++failures;
      std::fprintf(stderr, "FAILED %s: %s\n", r.id.c_str(), to_string(r.status));
    }
  }

  HostCosts costs;
  if (timing) {
    std::vector<HostCase> host_cases;
    for (const CaseResult& r : results) {
      if (r.status == PrepareStatus::Ok) host_cases.push_back({r.bench_case, r.device_status == PrepareStatus::Ok});
    }
    HostCostOptions options;
    options.smoke = smoke;
    options.min_time_s = min_time;
    costs = measure_host_costs(host_cases, options);
  }

  const std::string cases_path = out_dir + "/host_cases.csv";
  // What made these numbers, first in each file (make_report.py skips '#' lines).
  char settings[160];
  std::snprintf(settings, sizeof settings, "%s, error grid every %g px, %s, %d threads%s%s", smoke ? "smoke" : "full",
                grid_step, timing ? "timed (Google Benchmark)" : "not timed", threads,
                filter.empty() ? "" : ", only ids containing ", filter.c_str());
  const ff::host::Metadata metadata = {{"tool", std::string("ff-bench ") + ff::host::project_version()},
                                       {"date", ff::host::utc_timestamp()},
                                       {"run", settings},
                                       {"host", "host-build costs in ns; not a Teensy (docs/benchmarks.md)"}};
  std::ostringstream cases;
  ff::host::write_metadata(cases, metadata);
  cases << "id,scene,strategy,builtin,default,rendering,status,table_bytes,plan_bytes,fits_teensy,"
           "gradient_evaluations,max_g_core,max_g_ref,max_lsb,rms_lsb,p99_lsb,max_interior_lsb,worst_x,worst_y,worst_direction_deg,"
           "error_samples,eval_checksum,host_eval_ns,host_prepare_us,host_tick_ns\n";
  for (const CaseResult& r : results) {
    const SceneId scene = r.bench_case.scene;
    cases << r.id << ',' << scene_name(scene) << ',' << r.strategy << ',' << (is_builtin(scene) ? 1 : 0) << ','
          << (is_default(r.bench_case) ? 1 : 0) << ',' << rendering_name(scene_definition(scene).rendering) << ','
          << (r.status == PrepareStatus::Ok ? "ok" : "failed") << ',' << r.stats.table_bytes << ','
          << r.stats.plan_bytes << ',' << (r.device_status == PrepareStatus::Ok ? 1 : 0) << ','
          << r.stats.gradient_evaluations << ',' << number(static_cast<double>(r.stats.max_gradient), "%.9g") << ','
          << number(r.max_g_ref, "%.12g") << ',' << number(r.accuracy.max_lsb) << ','
          << number(r.accuracy.rms_lsb) << ',' << number(r.accuracy.p99_lsb) << ','
          << number(r.accuracy.max_interior_lsb) << ',' << number(r.accuracy.worst_position.x) << ','
          << number(r.accuracy.worst_position.y) << ',' << number(r.accuracy.worst_direction_deg) << ','
          << r.accuracy.samples << ',' << r.checksum << ',' << lookup(costs.eval_ns, r.id, "%.2f") << ','
          << lookup(costs.prepare_us, r.id, "%.2f") << ',' << lookup(costs.tick_ns, r.id, "%.2f") << '\n';
  }
  const std::string trackers_path = out_dir + "/host_trackers.csv";
  std::ostringstream trackers;
  ff::host::write_metadata(trackers, metadata);
  trackers << "config,host_update_ns\n";
  for (int i = 0; i < kTrackerConfigCount; ++i) {
    trackers << tracker_config_name(i) << ',' << lookup(costs.tracker_ns, tracker_config_name(i), "%.2f") << '\n';
  }
  std::string error;
  if (!ff::host::write_file_atomically(cases_path, cases.str(), error) ||
      !ff::host::write_file_atomically(trackers_path, trackers.str(), error)) {
    std::fprintf(stderr, "ff-bench: %s\n", error.c_str());
    return ff::host::kExitBadUsage;
  }
  std::fprintf(stderr, "wrote %s (%zu cases) and %s; %d failed\n", cases_path.c_str(), results.size(),
               trackers_path.c_str(), failures);
  return failures == 0 ? 0 : 1;
}
