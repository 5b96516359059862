// ff-track-bench: how well each tracker configuration renders what the
// finger should feel, on generated traces with ground truth.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "frictionfield/host/cli_conventions.hpp"
#include "bench_report.hpp"
#include "class_report.hpp"
#include "proposed_config.hpp"
#include "tracking_evaluation.hpp"

namespace {

using namespace ff;
using namespace ff::bench;

constexpr const char* kDescription =
    "ff-track-bench: accuracy of what is felt, for each tracker configuration.\n"
    "\n"
    "Generates a fixed set of traces with ff-tracegen's model (6 traces: back and forth along the\n"
    "paths and strokes across them, targets top/middle/bottom, zForce quantisation, 200 Hz with\n"
    "jitter, rests and a lift) at two noise levels, runs each tracker tick by tick at 2 kHz exactly\n"
    "as ff-replay does, and compares it with the ground truth at every tick:\n"
    "  position RMSE and p95 (px, 1 px ~ 0.2 mm) while the finger moves (> 10 mm/s),\n"
    "  lag: the time shift of the truth that minimises the position RMSE (ms),\n"
    "  direction error (degrees) of the velocity estimate while moving,\n"
    "  rendered-amplitude error |A - A_ideal| (RMS, p95; 0..1 scale, strength 1) while moving, where\n"
    "  A_ideal comes from the same prepared scene fed the true position and true direction:\n"
    "  heightmap (direction-dependent) and frictionmap (position only),\n"
    "  heightmap at rest: RMS of A - 0.5 while the finger rests (chatter; ideal is 0.5),\n"
    "  host cost of HapticPipeline::tick() on the heightmap (ns per tick, this machine).\n"
    "With --classes: the same metrics per class of finger and sensor (white noise at 200 Hz, slow\n"
    "fingers, tremor, stamp latency, correlated noise, everything at 100 Hz / 200 Hz / 1 kHz), for the\n"
    "thesis pipeline and recommended(), with recommended()'s ratio to the thesis pipeline.";

struct NamedConfig {
  NamedConfig(std::string n, const TrackerConfig& c) : name(std::move(n)), config(c) {}
  NamedConfig(std::string n, const TrackerConfig& c, const TrackerConfig& d)
      : name(std::move(n)), config(c), split(true), direction(d) {}
  std::string name;
  TrackerConfig config;
  bool split = false;  // direction from `direction` (a second tracker)
  TrackerConfig direction;
};

TrackerConfig with_derivative(TrackerConfig c, DerivativeFrom d) {
  c.one_euro.derivative_from = d;
  return c;
}

TrackerConfig with_estimator(TrackerConfig c, Estimator e) {
  c.estimator = e;
  return c;
}

using Tuned = ProposedConstants;

TrackerConfig tuned_config(const Tuned& t) { return proposed_tracker(t); }


// Candidate: position from a fast Kalman (no lag), direction from the tuned one.
constexpr float kSplitPositionQ = 700.0f;
constexpr float kSplitPositionR = 1.5f;

std::vector<NamedConfig> standard_configs(const Tuned& tuned, const Tuned& split_position) {
  const TrackerConfig rec = TrackerConfig::recommended();
  std::vector<NamedConfig> configs = {
      {"thesis (ticks + 1-euro, filtered derivative)", TrackerConfig::thesis()},
      {"thesis, 1-euro raw derivative", with_derivative(TrackerConfig::thesis(), DerivativeFrom::PreviousRaw)},
      {"timed extrapolation + 1-euro (filtered)",
       with_derivative(with_estimator(rec, Estimator::TimedExtrapolation), DerivativeFrom::PreviousFiltered)},
      {"timed extrapolation + 1-euro (raw)",
       with_derivative(with_estimator(rec, Estimator::TimedExtrapolation), DerivativeFrom::PreviousRaw)},
      {"kalman, one filter (recommended() constants)", with_estimator(TrackerConfig{}, Estimator::Kalman)},
      {"recommended()", rec},
  };
  if (tuned.accel_noise_px_s2 > 0.0f) {
    char name[160];
    std::snprintf(name, sizeof name, "kalman tuned (q %.0f, r %.1f, fade %.0f-%.0f px/s)",
                  static_cast<double>(tuned.accel_noise_px_s2), static_cast<double>(tuned.measurement_noise_px),
                  static_cast<double>(tuned.rest_speed_px_s), static_cast<double>(tuned.moving_speed_px_s));
    configs.emplace_back(name, tuned_config(tuned));
    if (split_position.accel_noise_px_s2 > 0.0f) {
      Tuned position = tuned;
      position.accel_noise_px_s2 = split_position.accel_noise_px_s2;
      position.measurement_noise_px = split_position.measurement_noise_px;
      std::snprintf(name, sizeof name, "candidate: position kalman (q %.0f, r %.1f) + direction from the tuned one",
                    static_cast<double>(position.accel_noise_px_s2), static_cast<double>(position.measurement_noise_px));
      configs.emplace_back(name, tuned_config(position), tuned_config(tuned));
    }
  }
  return configs;
}

struct LevelSet {
  std::string label;
  double noise_px;
  std::vector<PreparedCase> cases;
};

// Trace files as one set: each judged against its truth columns or the offline smoother.
bool load_trace_level(const std::vector<std::string>& paths, const TraceFileOptions& options, LevelSet& level,
                      std::string& error) {
  level = LevelSet{"recorded", 0.0, {}};
  for (const std::string& path : paths) {
    PreparedCase c;
    if (!load_trace_case(path, options, c, error)) return false;
    std::fprintf(stderr, "ff-track-bench: %s: %zu reports, %zu ticks, judged against %s\n", path.c_str(),
                 c.trace.samples.size(), c.ticks.size(),
                 c.truth_from_columns ? "its x_true, y_true columns" : "the offline smoother (no truth columns)");
    level.cases.push_back(std::move(c));
  }
  return true;
}

std::vector<LevelSet> prepare_levels(double duration_s) {
  std::vector<LevelSet> levels;
  for (auto [label, noise] : {std::pair<const char*, double>{"low", 1.0}, {"high", 2.5}}) {
    LevelSet level{label, noise, {}};
    for (const TrackCase& c : standard_cases(noise, duration_s)) level.cases.push_back(prepare_case(c));
    levels.push_back(std::move(level));
  }
  return levels;
}

// Grid search for the Kalman constants and the rest-fade speeds. The
// objective is the heightmap amplitude error while moving (mean over both
// noise levels); candidates must keep the lag under max_lag_ms (the goal: 2
// ms), the frictionmap error no
// worse than the thesis pipeline's, and the heightmap chatter at rest (RMS of
// A - 0.5, worst level) under `rest_bound`. Every candidate is logged, and
// the trade-off between moving error and rest chatter is printed at the end.
Tuned tune(const std::vector<LevelSet>& levels, double rest_bound, double max_lag_ms, std::ostream& log) {
  EvalOptions options;
  options.cost = false;
  std::vector<double> thesis_fm;
  for (const LevelSet& l : levels) thesis_fm.push_back(evaluate(TrackerConfig::thesis(), l.cases, options).frictionmap_rms);

  struct Scored {
    Tuned t;
    double hm = 0.0, fm_ratio = 0.0, lag = 0.0, rest = 0.0;
    std::vector<double> hm_level, rest_level;
    bool fits = false;  // lag and frictionmap constraints
    bool ok() const { return fits; }
  };
  std::vector<Scored> all;
  auto score = [&](const Tuned& t) {
    Scored s{t, 0.0, 0.0, 0.0, 0.0, {}, {}, false};
    for (size_t i = 0; i < levels.size(); ++i) {
      const Metrics m = evaluate(tuned_config(t), levels[i].cases, options);
      s.hm += m.heightmap_rms / static_cast<double>(levels.size());
      s.hm_level.push_back(m.heightmap_rms);
      s.rest_level.push_back(m.heightmap_rest_rms);
      s.lag = std::max(s.lag, m.lag_ms);
      s.rest = std::max(s.rest, m.heightmap_rest_rms);
      s.fm_ratio = std::max(s.fm_ratio, m.frictionmap_rms / thesis_fm[i]);
    }
    s.fits = s.lag <= max_lag_ms && s.fm_ratio <= 1.0;
    all.push_back(s);
    return s;
  };
  auto print = [&log](const char* stage, const Scored& s) {
    auto per_level = [](const std::vector<double>& v) {
      std::string out;
      for (double x : v) {
        char b[16];
        std::snprintf(b, sizeof b, "%s%.4f", out.empty() ? "" : "/", x);
        out += b;
      }
      return out;
    };
    char line[320];
    std::snprintf(line, sizeof line,
                  "%s q=%-6.0f r=%-5.2f rest=%-4.0f moving=%-4.0f  HM RMS %.4f (%s)  lag %.2f ms  "
                  "FM/thesis %.3f  rest %.4f (%s)%s\n",
                  stage, static_cast<double>(s.t.accel_noise_px_s2), static_cast<double>(s.t.measurement_noise_px),
                  static_cast<double>(s.t.rest_speed_px_s), static_cast<double>(s.t.moving_speed_px_s), s.hm,
                  per_level(s.hm_level).c_str(), s.lag, s.fm_ratio, s.rest, per_level(s.rest_level).c_str(),
                  s.fits ? "" : "  (lag or frictionmap constraint violated)");
    log << line;
    log.flush();
  };
  auto better = [rest_bound](const Scored& a, const Scored& b) {
    const bool a_ok = a.fits && a.rest <= rest_bound, b_ok = b.fits && b.rest <= rest_bound;
    if (a_ok != b_ok) return a_ok;
    return a_ok ? a.hm < b.hm : a.hm + a.rest < b.hm + b.rest;
  };

  const TrackerConfig rec = TrackerConfig::recommended();
  Scored best = score({rec.kalman.accel_noise_px_s2, rec.kalman.measurement_noise_px, rec.rest_speed_px_s,
                       rec.moving_speed_px_s});
  print("start ", best);
  // Stage 1: Kalman constants, fade at the recommended speeds.
  for (float q : {250.0f, 400.0f, 600.0f, 900.0f, 1300.0f, 2000.0f, 3000.0f, 6000.0f}) {
    for (float r : {1.5f, 3.0f, 4.5f, 6.5f, 9.0f, 13.0f}) {
      const Scored s = score({q, r, best.t.rest_speed_px_s, best.t.moving_speed_px_s});
      print("kalman", s);
      if (better(s, best)) best = s;
    }
  }
  // Stage 2: fade speeds at the best constants.
  for (int round = 0; round < 2; ++round) {
    const Tuned centre = best.t;
    for (float lo : {0.0f, 10.0f, 20.0f, 30.0f, 45.0f, 60.0f}) {
      for (float width : {15.0f, 30.0f, 50.0f, 80.0f, 120.0f}) {
        const Scored s = score({centre.accel_noise_px_s2, centre.measurement_noise_px, lo, lo + width});
        print("fade  ", s);
        if (better(s, best)) best = s;
      }
    }
    // Stage 3: constants again around the best, at the chosen fade.
    const Tuned fade = best.t;
    for (float qf : {0.6f, 0.8f, 1.0f, 1.25f, 1.6f}) {
      for (float rf : {0.6f, 0.8f, 1.0f, 1.25f, 1.6f}) {
        const Scored s = score({fade.accel_noise_px_s2 * qf, fade.measurement_noise_px * rf, fade.rest_speed_px_s,
                                fade.moving_speed_px_s});
        print("refine", s);
        if (better(s, best)) best = s;
      }
    }
  }
  // The trade-off: for each bound on rest chatter, the best moving error.
  log << "trade-off (lag <= " << max_lag_ms << " ms, frictionmap no worse than thesis): rest chatter bound -> best\n";
  for (double bound : {0.02, 0.04, 0.06, 0.08, 0.10, 0.15, 0.20, 0.30}) {
    const Scored* pick = nullptr;
    for (const Scored& s : all)
      if (s.fits && s.rest <= bound && (pick == nullptr || s.hm < pick->hm)) pick = &s;
    if (pick != nullptr) {
      char tag[32];
      std::snprintf(tag, sizeof tag, "<=%.2f", bound);
      print(tag, *pick);
    }
  }
  print("best  ", best);
  return best.t;
}

// The per-class table: the thesis pipeline and recommended() on each class.
std::string run_classes(const std::vector<std::string>& names, double duration_s, const EvalOptions& base) {
  EvalOptions options = base;
  options.cost = false;
  std::vector<ClassRow> rows;
  for (const tracegen::TraceClass& trace_class : tracegen::trace_classes()) {
    if (!names.empty() && std::find(names.begin(), names.end(), trace_class.name) == names.end()) continue;
    std::fprintf(stderr, "ff-track-bench: class %s: generating 6 traces of %.0f s...\n", trace_class.name, duration_s);
    std::vector<PreparedCase> cases;
    for (const TrackCase& c : class_cases(trace_class, duration_s)) cases.push_back(prepare_case(c));
    const double slow = slow_share(cases, options.moving_speed_px_s);
    for (const auto& [name, config] : {std::pair<const char*, TrackerConfig>{"thesis", TrackerConfig::thesis()},
                                       {"recommended()", TrackerConfig::recommended()}}) {
      rows.push_back({trace_class.name, name, evaluate(config, cases, options), slow});
    }
  }
  std::ostringstream table;
  write_class_report(table, rows, duration_s, options.moving_speed_px_s);
  return table.str();
}

}  // namespace

int main(int argc, char** argv) {
  double duration_s = 30.0;
  std::string doc_path;
  bool run_tune = false;
  double rest_bound = 0.08;
  double max_lag_ms = 2.0;
  Tuned tuned = kProposed;
  Tuned split{kSplitPositionQ, kSplitPositionR, 0.0f, 0.0f};
  EvalOptions options;

  CLI::App app{kDescription, "ff-track-bench"};
  app.add_option("--duration", duration_s, "Length of each generated trace (s); 6 traces per noise level")
      ->capture_default_str()->check(CLI::Range(2.0, 3600.0));
  app.add_option("--moving-above", options.moving_speed_px_s, "Speed above which the finger counts as moving (px/s)")
      ->capture_default_str()->check(CLI::Range(0.0, 10000.0));
  app.add_option("--write-doc", doc_path, "Also write the table into this markdown file, between the markers "
                                          "<!-- track-bench:begin --> and <!-- track-bench:end -->");
  app.add_flag("--tune", run_tune, "Grid-search the Kalman constants and the rest-fade speeds first, log every "
                                   "candidate to stderr, and add the best as a row");
  app.add_option("--max-lag", max_lag_ms, "Tuning: largest allowed lag (ms)")->capture_default_str();
  app.add_option("--rest-bound", rest_bound, "Tuning: largest allowed heightmap chatter at rest (RMS of A - 0.5)")
      ->capture_default_str();
  auto* row = "The tuned row (defaults: the proposed constants, docs/tracking.md)";
  app.add_option("--kalman-q", tuned.accel_noise_px_s2, "KalmanConfig::accel_noise_px_s2")->capture_default_str()->group(row);
  app.add_option("--kalman-r", tuned.measurement_noise_px, "KalmanConfig::measurement_noise_px")->capture_default_str()->group(row);
  app.add_option("--rest-speed", tuned.rest_speed_px_s, "TrackerConfig::rest_speed_px_s")->capture_default_str()->group(row);
  app.add_option("--moving-speed-fade", tuned.moving_speed_px_s, "TrackerConfig::moving_speed_px_s")
      ->capture_default_str()->group(row);
  app.add_option("--split-q", split.accel_noise_px_s2, "Candidate row: the position filter's accel_noise_px_s2 "
                                                       "(0: no candidate row)")->capture_default_str()->group(row);
  app.add_option("--split-r", split.measurement_noise_px, "Candidate row: the position filter's measurement_noise_px")
      ->capture_default_str()->group(row);
  std::vector<std::string> trace_paths;
  TraceFileOptions trace_options;
  std::string target_word = "middle";
  auto* traces = "Trace files instead of the generated set";
  app.add_option("--trace", trace_paths,
                 "Evaluate (and with --tune, tune) on these trace files (t_us,x,y,touch[,x_true,y_true]) instead of "
                 "the generated set. With x_true, y_true columns (ff-tracegen, or a motion-capture reference) the "
                 "trackers are judged against them; without, against an offline Rauch-Tung-Striebel smoother of the "
                 "reports themselves: no lag and little noise, but not ground truth (docs/tracking.md)")
      ->check(CLI::ExistingFile)->group(traces);
  app.add_option("--target", target_word, "The heightmap and frictionmap the amplitude errors are judged on")
      ->check(CLI::IsMember({"top", "middle", "bottom"}))->capture_default_str()->group(traces);
  app.add_flag("--smoothed", [&](std::int64_t) { trace_options.use_truth_columns = false; },
               "Judge against the offline smoother even where the file has truth columns (to see how far the "
               "smoother itself is from the truth)")->group(traces);
  app.add_option("--smoother-q", trace_options.smoother.accel_noise_px2_s3,
                 "Offline smoother: white-acceleration spectral density (px^2/s^3)")
      ->capture_default_str()->check(CLI::PositiveNumber)->group(traces);
  app.add_option("--smoother-r", trace_options.smoother.measurement_noise_px,
                 "Offline smoother: report noise, 1 sigma per axis (px)")
      ->capture_default_str()->check(CLI::PositiveNumber)->group(traces);
  bool classes = false;
  std::vector<std::string> class_names;
  std::vector<std::string> known_classes;
  for (const tracegen::TraceClass& c : tracegen::trace_classes()) known_classes.push_back(c.name);
  auto* per_class = "Per class of finger and sensor (docs/tracking.md#trace-classes)";
  app.add_flag("--classes", classes, "Instead of the table above: the thesis pipeline and recommended() on each "
                                     "trace class, with the ratios to the thesis pipeline; the finger counts as "
                                     "moving above 4 mm/s unless --moving-above is given. With --write-doc, "
                                     "between <!-- track-bench-classes:begin --> and <!-- track-bench-classes:end -->")
      ->group(per_class);
  app.add_option("--class", class_names, "Only these classes (implies --classes)")
      ->check(CLI::IsMember(known_classes))->group(per_class);
  std::string dump_path;
  app.add_option("--dump-ticks", dump_path, "Write every tick of the first low-noise trace for the tuned configuration "
                                            "(truth, estimate, amplitudes) to this CSV, for plots");
  if (const int code = ff::host::parse_command_line(app, argc, argv); code >= 0) return code;

  if (classes || !class_names.empty()) {
    if (!trace_paths.empty() || run_tune) {
      std::fprintf(stderr, "ff-track-bench: --classes works on generated traces; it takes neither --trace nor --tune\n");
      return 2;
    }
    if (app.count("--moving-above") == 0) options.moving_speed_px_s = kClassMovingSpeedPxS;
    const std::string table = run_classes(class_names, duration_s, options);
    std::cout << table;
    if (!doc_path.empty()) {
      std::string error;
      if (!replace_marked_section(doc_path, table, error, "track-bench-classes")) {
        std::fprintf(stderr, "ff-track-bench: %s\n", error.c_str());
        return 1;
      }
      std::fprintf(stderr, "ff-track-bench: table written to %s\n", doc_path.c_str());
    }
    return 0;
  }

  std::vector<LevelSet> levels;
  if (trace_paths.empty()) {
    std::fprintf(stderr, "ff-track-bench: generating 2 x 6 traces of %.0f s...\n", duration_s);
    levels = prepare_levels(duration_s);
  } else {
    trace_options.target = target_word == "top" ? Target::Top : (target_word == "bottom" ? Target::Bottom : Target::Middle);
    LevelSet level;
    std::string error;
    if (!load_trace_level(trace_paths, trace_options, level, error)) {
      std::fprintf(stderr, "ff-track-bench: %s\n", error.c_str());
      return 2;
    }
    levels.push_back(std::move(level));
  }
  if (run_tune) tuned = tune(levels, rest_bound, max_lag_ms, std::cerr);

  std::vector<ReportRow> rows;
  const std::vector<NamedConfig> configs = standard_configs(tuned, split);
  for (const NamedConfig& nc : configs) {
    for (const LevelSet& level : levels) {
      std::fprintf(stderr, "ff-track-bench: %s, %s noise\n", nc.name.c_str(), level.label.c_str());
      rows.push_back({nc.name, level.label,
                      evaluate(nc.config, level.cases, options, nc.split ? &nc.direction : nullptr)});
    }
  }
  if (!dump_path.empty()) {
    std::ofstream dump(dump_path);
    dump_ticks(dump, tuned_config(tuned), levels.front().cases.front());
  }
  std::ostringstream table;
  std::string description = generated_set_description(duration_s);
  if (!trace_paths.empty()) {
    size_t with_truth = 0;
    for (const PreparedCase& c : levels.front().cases) with_truth += c.truth_from_columns ? 1 : 0;
    description = std::to_string(trace_paths.size()) + " trace file(s), " + std::to_string(with_truth) +
                  " judged against their x_true, y_true columns, " + std::to_string(trace_paths.size() - with_truth) +
                  " against the offline smoother (not ground truth)";
  }
  write_report(table, rows, description, options.moving_speed_px_s);
  std::cout << table.str();
  if (!doc_path.empty()) {
    std::string error;
    if (!replace_marked_section(doc_path, table.str(), error)) {
      std::fprintf(stderr, "ff-track-bench: %s\n", error.c_str());
      return 1;
    }
    std::fprintf(stderr, "ff-track-bench: table written to %s\n", doc_path.c_str());
  }
  return 0;
}
