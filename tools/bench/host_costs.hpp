#pragma once
// Host cost of each case, tracker configuration and whole tick, measured with
// Google Benchmark: nanoseconds per evaluation, per preparation, per tick.
#include <map>
#include <string>
#include <vector>

#include "bench_cases.hpp"

namespace ff::bench {

struct HostCostOptions {
  double min_time_s = 0.05;  // per benchmark
  bool smoke = false;        // a few iterations each: keeps the code running, times meaningless
};

struct HostCosts {
  std::map<std::string, double> eval_ns;     // per plan.amplitude() call, by case id
  std::map<std::string, double> prepare_us;  // per ScenePlan::prepare(), by case id
  std::map<std::string, double> tick_ns;     // per HapticPipeline::tick() with a finger moving, by case id
  std::map<std::string, double> tracker_ns;  // per tracker update (on_sample + on_tick), by config name
};

struct HostCase {
  BenchCase bench_case;
  bool fits_slot = true;  // the pipeline accepts it: its table fits the slot, its preparation the budget
};

// Registers and runs every benchmark for `cases`; prints Google Benchmark's
// console table while it runs.
HostCosts measure_host_costs(const std::vector<HostCase>& cases, const HostCostOptions& options);

}  // namespace ff::bench
