// ff-replay: a logged or generated finger trace through the full 2 kHz
// pipeline, tick by tick, exactly as the firmware renders it.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>

#include "frictionfield/core/haptic_pipeline.hpp"
#include "frictionfield/host/cli_conventions.hpp"
#include "frictionfield/host/input_file.hpp"
#include "frictionfield/host/output_file.hpp"
#include "frictionfield/host/replay.hpp"
#include "frictionfield/host/scene_hash.hpp"
#include "frictionfield/host/scene_spec.hpp"
#include "frictionfield/host/sensor_profile_options.hpp"
#include "frictionfield/host/trace_csv.hpp"

namespace {

using ff::host::kExitBadUsage;
using ff::host::kExitCheckFailed;
using ff::host::kExitOk;

uint32_t host_micros() {
  using namespace std::chrono;
  return static_cast<uint32_t>(duration_cast<microseconds>(steady_clock::now().time_since_epoch()).count());
}

// The device's trackers are told the sensor's profile; the thesis pipeline ignores it.
bool make_tracker(const std::string& name, const std::string& derivative, const ff::SensorProfile& sensor,
                  ff::TrackerConfig& out, std::string& error) {
  const ff::TrackerConfig told = ff::TrackerConfig::recommended(sensor);
  if (name == "thesis") out = ff::TrackerConfig::thesis();
  else if (name == "recommended") out = told;
  else if (name == "kalman") { out = told; out.estimator = ff::Estimator::Kalman; }
  else if (name == "split-kalman") { out = told; out.estimator = ff::Estimator::SplitKalman; }
  else if (name == "timed") { out = told; out.estimator = ff::Estimator::TimedExtrapolation; }
  else if (name == "thesis-ticks") { out = told; out.estimator = ff::Estimator::ThesisTicks; }
  else return error = "unknown tracker '" + name + "': recommended, thesis, split-kalman, kalman, timed, thesis-ticks", false;
  if (derivative == "filtered") out.one_euro.derivative_from = ff::DerivativeFrom::PreviousFiltered;
  else if (derivative == "raw") out.one_euro.derivative_from = ff::DerivativeFrom::PreviousRaw;
  else return error = "--derivative is filtered or raw", false;
  return true;
}

// "WxH" with positive integers.
bool parse_screen(const std::string& text, float& width, float& height) {
  unsigned w = 0, h = 0;
  char x = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%u%c%u%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X') || w == 0 ||
      h == 0) {
    return false;
  }
  width = static_cast<float>(w);
  height = static_cast<float>(h);
  return true;
}

std::string shortest(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "ff-replay: replay a finger trace through the frictionfield pipeline (extrapolation, filter,\n"
      "scene, amplitude, DAC code) at 2 kHz, exactly as the Teensy renders it.\n\n"
      "Input: CSV with header t_us,x,y,touch (extra columns, '#' lines and a UTF-8 BOM are fine),\n"
      "screen pixels 800x480 (--screen WxH scales a trace from another screen). Read as a stream:\n"
      "any length in constant memory.\n"
      "Output: '#' metadata lines (tool, version, date, scene words and hash, tracker, strength,\n"
      "calibration, input), then one row per 500 us tick: t_us,x,y,vx,vy,amplitude,dac,present\n"
      "(present = 1: a finger was tracked at that tick), then a '# summary' line.\n"
      "A gap between reports longer than --max-gap-s is a clock fault, and so is a clock stepping back\n"
      "(two rows in a row stamped over 20 ms before the latest report): the replay ends at the last\n"
      "plausible report and reports the rows it left out.\n"
      "An ffctl recording replays as the device rendered it: each report at the tick that took it\n"
      "(taken_us), with the sensor profile its '# sensor-profile' line names (unless flags are given).\n\n"
      "Exit codes: 0 ok; 1 a check failed (--strict: samples rejected or rows left out);\n"
      "2 bad usage or input (unreadable trace, bad scene words, output = input).\n\n"
      "Example:\n"
      "  ff-replay --scene heightmap --target top --strength 0.66 trace.csv -o rendered.csv\n"};
  ff::host::SceneSpec spec;
  std::string input, output = "-", tracker = "recommended", derivative = "filtered", screen = "800x480";
  double extra_ms = 100.0, max_gap_s = 600.0;
  bool quiet = false, strict = false;
  app.add_option("trace", input, "sensor trace CSV (t_us,x,y,touch)")->required();
  app.add_option("-o,--output", output, "replay output CSV ('-' for stdout); never the trace itself")
      ->capture_default_str();
  ff::host::add_scene_options(app, spec);
  app.add_option("--tracker", tracker, "finger tracker: recommended (split Kalman), thesis (ticks + 1-euro, exactly as the thesis),\n"
                 "split-kalman, kalman, timed (extrapolate to the tick's time + 1-euro), thesis-ticks")
      ->capture_default_str();
  app.add_option("--derivative", derivative, "1-euro derivative from the previous filtered or raw value")
      ->capture_default_str();
  app.add_option("--extra-ms", extra_ms, "keep ticking this long after the last sample (time-outs play out)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 60000.0));
  app.add_option("--screen", screen,
                 "the trace's screen size WxH in its own units; x and y are scaled to the 800x480 screen\n"
                 "(the sensor's calibration already maps to pixels: use this for traces from another display)")
      ->capture_default_str();
  app.add_option("--max-gap-s", max_gap_s, "longest plausible gap between reports (s); a longer one ends the replay")
      ->capture_default_str()
      ->check(CLI::Range(0.001, 86400.0));
  ff::SensorProfile sensor;  // the device's default until a lab sends its own
  ff::host::add_sensor_profile_options(app, sensor);
  app.add_flag("--strict", strict, "exit 1 if any sample is rejected or rows are left out after a time jump");
  app.add_flag("-q,--quiet", quiet, "only problems on stderr (the rejected count when not 0)");
  if (const int code = ff::host::parse_command_line(app, argc, argv); code >= 0) return code;

  std::string error;
  ff::Condition condition;
  ff::TrackerConfig tracker_config;
  float screen_w = 0.0f, screen_h = 0.0f;
  if (!parse_screen(screen, screen_w, screen_h)) {
    std::cerr << "ff-replay: --screen '" << screen << "': expected WxH, e.g. 4096x4096\n";
    return kExitBadUsage;
  }
  if (!ff::host::make_condition(spec, condition, error) || !make_tracker(tracker, derivative, sensor, tracker_config, error)) {
    std::cerr << "ff-replay: " << error << "\n";
    return kExitBadUsage;
  }
  const bool profile_given = ff::host::sensor_profile_given(app);
  if (output != "-" && ff::host::same_file(input, output)) {
    std::cerr << "ff-replay: the output " << output << " is the input trace itself: choose another -o\n";
    return kExitBadUsage;
  }
  std::ifstream in;
  std::string why;
  if (!ff::host::open_input_file(input, in, why)) {
    std::cerr << "ff-replay: " << input << ": " << why << "\n";
    return kExitBadUsage;
  }
  ff::host::SensorTraceReader reader(in);
  ff::host::TraceError trace_error;
  if (!reader.read_header(trace_error)) {
    std::cerr << "ff-replay: " << trace_error.to_string(input) << "\n";
    return kExitBadUsage;
  }
  // An ffctl recording names the profile the device's tracker used: replay with it unless told otherwise.
  std::string profile_source = profile_given ? "command line" : "default";
  if (const std::string recorded = reader.metadata("sensor-profile"); !profile_given && recorded.rfind("--", 0) == 0) {
    if (!ff::host::parse_sensor_profile_flags(recorded, sensor, error)) {
      std::cerr << "ff-replay: " << input << ": its sensor-profile line: " << error
                << " (give the profile's flags to override it)\n";
      return kExitBadUsage;
    }
    make_tracker(tracker, derivative, sensor, tracker_config, error);
    profile_source = "the recording's sensor-profile line";
  }

  auto pipeline = std::make_unique<ff::HapticPipeline>(tracker_config);
  pipeline->set_clock(host_micros);
  const ff::PrepareStatus status = pipeline->set_condition(condition);
  if (status != ff::PrepareStatus::Ok) {
    std::cerr << "ff-replay: cannot prepare the scene: " << ff::to_string(status) << "\n";
    return kExitBadUsage;
  }

  ff::host::ToolOutput output_file(output);
  if (!output_file.open()) {
    std::cerr << "ff-replay: " << output_file.error() << "\n";
    return kExitBadUsage;
  }
  std::ostream* out = &output_file.stream();
  std::error_code ec;
  const uint64_t input_bytes = std::filesystem::file_size(input, ec);
  ff::host::write_metadata(
      *out, {{"tool", std::string("ff-replay ") + ff::host::project_version()},
             {"date", ff::host::utc_timestamp()},
             {"input", std::filesystem::path(input).filename().string() + " (" +
                           std::to_string(ec ? 0 : input_bytes) + " bytes)"},
             {"input_path", input},
             {"scene", ff::host::scene_words(spec)},
             {"scene_hash", ff::host::hash_hex(ff::host::condition_hash(condition))},
             {"tracker", tracker + " (derivative " + derivative + ")"},
             {"sensor_profile", tracker == "thesis" ? "not used by the thesis pipeline"
                                                    : ff::host::sensor_profile_flags(sensor) + " (" +
                                                          profile_source + ")"},
             {"strength", std::to_string(spec.strength)},
             {"calibration", spec.inverted_dac ? "inverted (AD9834 FSADJUST)" : "linear"},
             {"timing", std::string(reader.column("taken_us") >= 0
                                        ? "each report at the tick that took it on the device (taken_us)"
                                        : "each report at the first tick at or after its stamp") +
                            ", --extra-ms " + shortest(extra_ms) + ", --max-gap-s " + shortest(max_gap_s)},
             {"screen", screen + (screen == "800x480" ? "" : " scaled to 800x480")},
             {"columns", "t_us,x,y (filtered px),vx,vy (direction used),amplitude,dac,present (finger tracked)"}});
  ff::host::write_replay_header(*out);

  const float sx = ff::kScreenWidthPx / screen_w, sy = ff::kScreenHeightPx / screen_h;
  const bool scaled = screen != "800x480";
  bool read_failed = false;
  const ff::host::RowSource source = [&](ff::host::TraceRow& row) {
    if (read_failed || !reader.next(row, trace_error)) {
      read_failed = read_failed || !trace_error.message.empty();
      return false;
    }
    if (scaled) {
      row.x *= sx;
      row.y *= sy;
    }
    return true;
  };
  ff::host::ReplayOptions options;
  options.extra_ticks = static_cast<uint64_t>(extra_ms * 1000.0 / ff::kTickPeriodUs);
  options.max_gap_us = static_cast<uint64_t>(max_gap_s * 1e6);
  options.max_step_back_us = ff::host::kClockStepBackUs;
  uint64_t done = 0;
  const ff::host::ReplaySummary summary = ff::host::replay(
      source, *pipeline,
      [&](uint64_t t, const ff::TickOutput& tick) {
        ff::host::write_replay_row(*out, t, tick);
        if (!quiet && (++done % 2'000'000) == 0) {
          std::fprintf(stderr, "\rff-replay: %llu s replayed", static_cast<unsigned long long>(done / 2000));
        }
      },
      options);
  if (!quiet && done >= 2'000'000) std::fprintf(stderr, "\n");
  if (read_failed) {
    std::cerr << "ff-replay: " << trace_error.to_string(input) << "\n";
    return kExitBadUsage;
  }
  if (summary.samples == 0) {
    std::cerr << "ff-replay: " << input << ": no samples after the header\n";
    return kExitBadUsage;
  }
  const uint64_t rejected = summary.rejected_samples();
  char line[256];
  std::snprintf(line, sizeof line, "ticks=%llu samples=%llu rejected=%llu rows_left_out=%llu",
                static_cast<unsigned long long>(summary.ticks), static_cast<unsigned long long>(summary.samples),
                static_cast<unsigned long long>(rejected),
                static_cast<unsigned long long>(summary.rows_after_time_jump));
  ff::host::write_metadata(*out, {{"summary", line}});
  if (!output_file.commit()) {
    std::cerr << "ff-replay: " << output_file.error() << "\n";
    return kExitBadUsage;
  }

  const ff::FaultCounters& f = summary.faults;
  if (!quiet) {
    const ff::PlanStats& ps = pipeline->plan().stats();
    std::fprintf(stderr, "ff-replay: %s, %s, tracker %s\n", input.c_str(), ff::host::scene_words(spec).c_str(),
                 tracker.c_str());
    std::fprintf(stderr, "  ticks %llu (%.2f s), with finger %llu\n", static_cast<unsigned long long>(summary.ticks),
                 static_cast<double>(summary.ticks) * ff::kTickPeriodUs * 1e-6,
                 static_cast<unsigned long long>(summary.ticks_with_finger));
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
  // Always said, also with -q when not 0: rejected samples change what was rendered.
  if (!quiet || rejected > 0) {
    std::fprintf(stderr, "ff-replay: samples %llu: used %llu, rejected %llu\n",
                 static_cast<unsigned long long>(summary.samples),
                 static_cast<unsigned long long>(summary.samples - rejected),
                 static_cast<unsigned long long>(rejected));
  }
  if (!scaled && f[ff::Fault::OffScreen] > summary.samples / 10) {
    std::fprintf(stderr,
                 "ff-replay: %u samples off the 800x480 screen: is the trace in another screen's coordinates? "
                 "(--screen WxH)\n", f[ff::Fault::OffScreen]);
  }
  if (summary.time_jump && summary.time_jump_to_us < summary.time_jump_from_us) {
    std::fprintf(stderr,
                 "ff-replay: %s:%zu: the clock steps back from t_us %llu (line %zu) to %llu (two rows in a row "
                 "more than %llu ms behind: a log restarted or two joined): the replay ends at the last plausible "
                 "report; %llu rows left out\n",
                 input.c_str(), summary.time_jump_to_line,
                 static_cast<unsigned long long>(summary.time_jump_from_us), summary.time_jump_from_line,
                 static_cast<unsigned long long>(summary.time_jump_to_us),
                 static_cast<unsigned long long>(ff::host::kClockStepBackUs / 1000),
                 static_cast<unsigned long long>(summary.rows_after_time_jump));
  } else if (summary.time_jump) {
    std::fprintf(stderr,
                 "ff-replay: %s:%zu: time jump from t_us %llu (line %zu) to %llu (more than --max-gap-s %g): the "
                 "replay ends at the last plausible report; %llu rows left out\n",
                 input.c_str(), summary.time_jump_to_line,
                 static_cast<unsigned long long>(summary.time_jump_from_us), summary.time_jump_from_line,
                 static_cast<unsigned long long>(summary.time_jump_to_us), max_gap_s,
                 static_cast<unsigned long long>(summary.rows_after_time_jump));
  }
  if (strict && (rejected > 0 || summary.time_jump)) {
    std::fprintf(stderr, "ff-replay: --strict: %llu samples rejected, %llu rows left out\n",
                 static_cast<unsigned long long>(rejected),
                 static_cast<unsigned long long>(summary.rows_after_time_jump));
    return kExitCheckFailed;
  }
  return kExitOk;
}
