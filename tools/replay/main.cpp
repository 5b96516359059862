// ff-replay: a logged or generated finger trace through the full 2 kHz
// pipeline, tick by tick, exactly as the firmware renders it.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>

#include "frictionfield/core/haptic_pipeline.hpp"
#include "frictionfield/host/replay.hpp"
#include "frictionfield/host/scene_spec.hpp"
#include "frictionfield/host/trace_csv.hpp"

namespace {

uint32_t host_micros() {
  using namespace std::chrono;
  return static_cast<uint32_t>(duration_cast<microseconds>(steady_clock::now().time_since_epoch()).count());
}

constexpr uint64_t kMaxReplayTicks = 2000ull * 3600 * 24;  // one day of ticks

bool make_tracker(const std::string& name, const std::string& derivative, ff::TrackerConfig& out,
                  std::string& error) {
  if (name == "thesis") out = ff::TrackerConfig::thesis();
  else if (name == "recommended") out = ff::TrackerConfig::recommended();
  else if (name == "kalman") { out = ff::TrackerConfig::recommended(); out.estimator = ff::Estimator::Kalman; }
  else if (name == "split-kalman") { out = ff::TrackerConfig::recommended(); out.estimator = ff::Estimator::SplitKalman; }
  else if (name == "timed") { out = ff::TrackerConfig::recommended(); out.estimator = ff::Estimator::TimedExtrapolation; }
  else if (name == "thesis-ticks") { out = ff::TrackerConfig::recommended(); out.estimator = ff::Estimator::ThesisTicks; }
  else return error = "unknown tracker '" + name + "': recommended, thesis, split-kalman, kalman, timed, thesis-ticks", false;
  if (derivative == "filtered") out.one_euro.derivative_from = ff::DerivativeFrom::PreviousFiltered;
  else if (derivative == "raw") out.one_euro.derivative_from = ff::DerivativeFrom::PreviousRaw;
  else return error = "--derivative is filtered or raw", false;
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "ff-replay: replay a finger trace through the frictionfield pipeline (extrapolation, filter,\n"
      "scene, amplitude, DAC code) at 2 kHz, exactly as the Teensy renders it.\n\n"
      "Input: CSV with header t_us,x,y,touch (extra columns ignored), screen pixels 800x480.\n"
      "Output: one row per 500 us tick: t_us,x,y,vx,vy,amplitude,dac.\n\n"
      "Example:\n"
      "  ff-replay --scene heightmap --target top --strength 0.66 trace.csv -o rendered.csv\n"};
  ff::host::SceneSpec spec;
  std::string input, output = "-", tracker = "recommended", derivative = "filtered";
  double extra_ms = 100.0;
  bool quiet = false;
  app.add_option("trace", input, "sensor trace CSV (t_us,x,y,touch)")->required();
  app.add_option("-o,--output", output, "replay output CSV ('-' for stdout)")->capture_default_str();
  ff::host::add_scene_options(app, spec);
  app.add_option("--tracker", tracker, "finger tracker: recommended (split Kalman), thesis (ticks + 1-euro, exactly as the thesis),\n"
                 "split-kalman, kalman, timed (extrapolate to the tick's time + 1-euro), thesis-ticks")
      ->capture_default_str();
  app.add_option("--derivative", derivative, "1-euro derivative from the previous filtered or raw value")
      ->capture_default_str();
  app.add_option("--extra-ms", extra_ms, "keep ticking this long after the last sample (time-outs play out)")
      ->capture_default_str();
  app.add_flag("-q,--quiet", quiet, "no summary on stderr");
  CLI11_PARSE(app, argc, argv);

  std::string error;
  ff::Condition condition;
  ff::TrackerConfig tracker_config;
  if (!ff::host::make_condition(spec, condition, error) || !make_tracker(tracker, derivative, tracker_config, error)) {
    std::cerr << "ff-replay: " << error << "\n";
    return 2;
  }

  std::vector<ff::host::TraceRow> rows;
  ff::host::TraceError trace_error;
  if (!ff::host::read_sensor_trace_file(input, rows, trace_error)) {
    std::cerr << "ff-replay: " << trace_error.to_string(input) << "\n";
    return 2;
  }
  if (rows.empty()) {
    std::cerr << "ff-replay: " << input << ": no samples after the header\n";
    return 2;
  }
  uint64_t t_first = rows.front().t_us, t_last = t_first;
  for (const auto& r : rows) t_last = std::max(t_last, r.t_us);
  const uint64_t span_ticks = (t_last - t_first) / ff::kTickPeriodUs;
  if (span_ticks > kMaxReplayTicks) {
    std::cerr << "ff-replay: " << input << ": the trace spans " << (t_last - t_first) / 1000000
              << " s; more than a day of ticks is refused (check the t_us column)\n";
    return 2;
  }

  auto pipeline = std::make_unique<ff::HapticPipeline>(tracker_config);
  pipeline->set_clock(host_micros);
  const ff::PrepareStatus status = pipeline->set_condition(condition);
  if (status != ff::PrepareStatus::Ok) {
    std::cerr << "ff-replay: cannot prepare the scene: " << ff::to_string(status) << "\n";
    return 2;
  }

  std::ofstream file;
  std::ostream* out = &std::cout;
  if (output != "-") {
    file.open(output);
    if (!file) {
      std::cerr << "ff-replay: cannot write " << output << "\n";
      return 2;
    }
    out = &file;
  }
  ff::host::write_replay_header(*out);
  const uint64_t extra_ticks = static_cast<uint64_t>(std::max(0.0, extra_ms) * 1000.0 / ff::kTickPeriodUs);
  const uint64_t total = span_ticks + extra_ticks + 1;
  const bool progress = !quiet && total > 2'000'000;
  uint64_t done = 0;
  const ff::host::ReplaySummary summary = ff::host::replay(
      rows, *pipeline,
      [&](uint64_t t, const ff::TickOutput& tick) {
        ff::host::write_replay_row(*out, t, tick);
        if (progress && (++done % 200000) == 0) {
          std::fprintf(stderr, "\rff-replay: %5.1f %%", 100.0 * static_cast<double>(done) / static_cast<double>(total));
        }
      },
      extra_ticks);
  if (progress) std::fprintf(stderr, "\r");

  if (!quiet) {
    const ff::FaultCounters& f = summary.faults;
    const uint64_t rejected = f[ff::Fault::NonFiniteCoordinate] + f[ff::Fault::OffScreen] +
                              f[ff::Fault::NonIncreasingTime] + f[ff::Fault::JumpRejected] +
                              f[ff::Fault::MailboxOverflow];
    const ff::PlanStats& ps = pipeline->plan().stats();
    std::fprintf(stderr, "ff-replay: %s, scene %s target %s strength %.2f, tracker %s\n", input.c_str(),
                 spec.scene.c_str(), spec.target.c_str(), static_cast<double>(spec.strength), tracker.c_str());
    std::fprintf(stderr, "  ticks %llu (%.2f s), with finger %llu\n", static_cast<unsigned long long>(summary.ticks),
                 static_cast<double>(summary.ticks) * ff::kTickPeriodUs * 1e-6,
                 static_cast<unsigned long long>(summary.ticks_with_finger));
    std::fprintf(stderr, "  samples %llu: used %llu, rejected %llu\n", static_cast<unsigned long long>(summary.samples),
                 static_cast<unsigned long long>(summary.samples - std::min<uint64_t>(rejected, summary.samples)),
                 static_cast<unsigned long long>(rejected));
    std::fprintf(stderr, "  amplitude min %.4f  mean %.4f  max %.4f\n", static_cast<double>(summary.amplitude_min),
                 static_cast<double>(summary.amplitude_mean), static_cast<double>(summary.amplitude_max));
    std::fprintf(stderr, "  scene plan: max|G| %.4f, table %u bytes, plan %u bytes, prepared in %u us (host)\n",
                 static_cast<double>(ps.max_gradient), ps.table_bytes, ps.plan_bytes, pipeline->last_prepare_us());
    std::fprintf(stderr, "  events/faults:");
    bool any = false;
    for (int i = 0; i < static_cast<int>(ff::Fault::kCount); ++i) {
      if (f.count[i] == 0) continue;
      std::fprintf(stderr, " %s=%u", ff::to_string(static_cast<ff::Fault>(i)), f.count[i]);
      any = true;
    }
    std::fprintf(stderr, "%s\n", any ? "" : " none");
  }
  return 0;
}
