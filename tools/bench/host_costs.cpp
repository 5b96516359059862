#include "host_costs.hpp"

#include <benchmark/benchmark.h>

#include <cstdint>
#include <memory>

#include "bench_workload.hpp"
#include "frictionfield/core/haptic_pipeline.hpp"

namespace ff::bench {

namespace {

constexpr size_t kTableBytes = 3u * 1024u * 1024u;  // the largest table: 1 px float gradient
// Every strategy is measured, those past the Teensy's preparation budget too.
constexpr uint32_t kUnlimitedPreparation = UINT32_MAX;

struct Buffer {
  Buffer() : bytes(new unsigned char[kTableBytes + 8]) {}
  void* aligned() {
    auto p = reinterpret_cast<uintptr_t>(bytes.get());
    return reinterpret_cast<void*>((p + 7u) & ~uintptr_t{7u});
  }
  std::unique_ptr<unsigned char[]> bytes;
};

std::string id_of(const BenchCase& c) {
  char id[96];
  case_id(c, id, sizeof(id));
  return id;
}

// Google Benchmark reports per iteration; each benchmark says how many items an iteration holds.
class RecordingReporter : public benchmark::ConsoleReporter {
 public:
  struct Target {
    std::map<std::string, double>* into;
    std::string key;
    double items_per_iteration;
    double scale;  // seconds -> reported unit
  };
  std::map<std::string, Target> targets;

  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs) {
      if (run.error_occurred || run.run_type != Run::RT_Iteration || run.iterations == 0) continue;
      auto it = targets.find(run.run_name.function_name);
      if (it == targets.end()) continue;
      const Target& t = it->second;
      (*t.into)[t.key] = run.real_accumulated_time / static_cast<double>(run.iterations) /
                         t.items_per_iteration * t.scale;
    }
    ConsoleReporter::ReportRuns(runs);
  }
};

// Strokes follow each other on one clock, as they do on the device.
uint32_t g_clock_us = 1000;

void run_lift(HapticPipeline& pipeline, const FingerStroke& stroke) {
  for (int k = FingerStroke::kMovingTicks; k < FingerStroke::kTotalTicks; ++k) {
    SensorSample s;
    if (stroke.report_before(k, s)) pipeline.post_sample(s);
    benchmark::DoNotOptimize(pipeline.tick(stroke.tick_time(k)));
  }
}

}  // namespace

HostCosts measure_host_costs(const std::vector<HostCase>& cases, const HostCostOptions& options) {
  HostCosts costs;
  RecordingReporter reporter;
  auto shared_buffer = std::make_shared<Buffer>();
  auto pipeline = std::make_shared<HapticPipeline>();
  auto points = std::make_shared<std::vector<EvalPoint>>(kEvalPoints);
  {
    EvalPoint tmp[kEvalPoints];
    make_eval_points(tmp);
    std::copy(tmp, tmp + kEvalPoints, points->begin());
  }
  auto limit = [&](benchmark::internal::Benchmark* b) {
    if (options.smoke) b->Iterations(2);
    else b->MinTime(options.min_time_s);
    b->Unit(benchmark::kNanosecond);
  };
  auto target = [&](const std::string& name, std::map<std::string, double>& into, const std::string& key,
                    double items, double scale) {
    reporter.targets[name] = {&into, key, items, scale};
  };

  for (const HostCase& hc : cases) {
    const BenchCase& c = hc.bench_case;
    const std::string id = id_of(c);
    const SceneDefinition def = case_definition(c);

    const std::string eval_name = "eval/" + id;
    limit(benchmark::RegisterBenchmark(eval_name.c_str(), [=](benchmark::State& state) {
      ScenePlan plan;
      if (plan.prepare(def, shared_buffer->aligned(), kTableBytes, kUnlimitedPreparation) != PrepareStatus::Ok) {
        state.SkipWithError("prepare failed");
        return;
      }
      for (auto _ : state) {
        float sum = 0.0f;
        for (const EvalPoint& p : *points) sum += plan.amplitude(p.position, p.direction);
        benchmark::DoNotOptimize(sum);
      }
      state.SetItemsProcessed(state.iterations() * kEvalPoints);
    }));
    target(eval_name, costs.eval_ns, id, kEvalPoints, 1e9);

    const std::string prepare_name = "prepare/" + id;
    limit(benchmark::RegisterBenchmark(prepare_name.c_str(), [=](benchmark::State& state) {
      ScenePlan plan;
      for (auto _ : state) {
        benchmark::DoNotOptimize(plan.prepare(def, shared_buffer->aligned(), kTableBytes, kUnlimitedPreparation));
      }
    }));
    target(prepare_name, costs.prepare_us, id, 1.0, 1e6);

    if (!hc.fits_slot) continue;  // the pipeline would refuse it: no whole tick
    const std::string tick_name = "tick/" + id;
    limit(benchmark::RegisterBenchmark(tick_name.c_str(), [=](benchmark::State& state) {
      Condition condition;
      condition.scene = def;
      if (pipeline->set_condition(condition) != PrepareStatus::Ok) {
        state.SkipWithError("the pipeline refuses it (table slot or preparation budget)");
        return;
      }
      for (auto _ : state) {
        const FingerStroke stroke(g_clock_us);
        for (int k = 0; k < FingerStroke::kMovingTicks; ++k) {
          SensorSample s;
          if (stroke.report_before(k, s)) pipeline->post_sample(s);
          benchmark::DoNotOptimize(pipeline->tick(stroke.tick_time(k)));
        }
        state.PauseTiming();
        run_lift(*pipeline, stroke);
        g_clock_us += FingerStroke::kDurationUs;
        state.ResumeTiming();
      }
    }));
    target(tick_name, costs.tick_ns, id, FingerStroke::kMovingTicks, 1e9);
  }

  for (int i = 0; i < kTrackerConfigCount; ++i) {
    const std::string name = std::string("tracker/") + tracker_config_name(i);
    const TrackerConfig config = tracker_config(i);
    limit(benchmark::RegisterBenchmark(name.c_str(), [=](benchmark::State& state) {
      Tracker tracker(config);
      for (auto _ : state) {
        const FingerStroke stroke(g_clock_us);
        for (int k = 0; k < FingerStroke::kMovingTicks; ++k) {
          SensorSample s;
          if (stroke.report_before(k, s)) tracker.on_sample(s);
          benchmark::DoNotOptimize(tracker.on_tick(stroke.tick_time(k), true));
        }
        state.PauseTiming();
        tracker.reset();
        g_clock_us += FingerStroke::kDurationUs;
        state.ResumeTiming();
      }
    }));
    target(name, costs.tracker_ns, tracker_config_name(i), FingerStroke::kMovingTicks, 1e9);
  }

  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::ClearRegisteredBenchmarks();
  return costs;
}

}  // namespace ff::bench
