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
#include "frictionfield/host/sensor_profile_options.hpp"
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
  std::string name;
  TrackerConfig config;
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


std::string tuned_name(const Tuned& t) {
  char name[160];
  std::snprintf(name, sizeof name, "tuned (direction q %.0f, position q %.0f, fade %.1f-%.1f sigma)",
                static_cast<double>(t.direction_accel_px_s2), static_cast<double>(t.position_accel_px_s2),
                static_cast<double>(t.rest_sigmas), static_cast<double>(t.moving_sigmas));
  return name;
}

std::vector<NamedConfig> standard_configs(const Tuned& tuned, bool with_tuned) {
  const TrackerConfig rec = TrackerConfig::recommended();
  std::vector<NamedConfig> configs = {
      {"thesis (ticks + 1-euro, filtered derivative)", TrackerConfig::thesis()},
      {"thesis, 1-euro raw derivative", with_derivative(TrackerConfig::thesis(), DerivativeFrom::PreviousRaw)},
      {"timed extrapolation + 1-euro (filtered)",
       with_derivative(with_estimator(rec, Estimator::TimedExtrapolation), DerivativeFrom::PreviousFiltered)},
      {"timed extrapolation + 1-euro (raw)",
       with_derivative(with_estimator(rec, Estimator::TimedExtrapolation), DerivativeFrom::PreviousRaw)},
      {"kalman, one filter (the direction filter alone)", with_estimator(rec, Estimator::Kalman)},
      {"recommended()", rec},
  };
  if (with_tuned) configs.emplace_back(tuned_name(tuned), proposed_tracker(tuned));
  return configs;
}

struct LevelSet {
  std::string label;
  double noise_px;
  std::vector<PreparedCase> cases;
  SensorProfile sensor;  // what the trackers are told about the sensor
};

// Trace files as one set: each judged against its truth columns or the offline smoother.
bool load_trace_level(const std::vector<std::string>& paths, const TraceFileOptions& options,
                      const SensorProfile& sensor, LevelSet& level, std::string& error) {
  level = LevelSet{"recorded", 0.0, {}, sensor};
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
    LevelSet level{label, noise, {}, {}};
    for (const TrackCase& c : standard_cases(noise, duration_s)) level.cases.push_back(prepare_case(c));
    level.sensor = tracegen::nominal_profile(level.cases.front().spec.options);
    levels.push_back(std::move(level));
  }
  return levels;
}

// Grid search for the finger's acceleration densities and the direction
// confidence's fade. The objective is the heightmap amplitude error while
// moving (mean over the sets); candidates must keep the lag under max_lag_ms,
// the frictionmap error no worse than the thesis pipeline's, and the
// heightmap chatter at rest (RMS of A - 0.5, worst set) under `rest_bound`.
// Every candidate is logged, and the trade-off between moving error and rest
// chatter is printed at the end.
Tuned tune(const std::vector<LevelSet>& levels, double rest_bound, double max_lag_ms, double max_fm_ratio,
           const EvalOptions& base, std::ostream& log) {
  EvalOptions options = base;
  options.cost = false;
  std::vector<double> thesis_fm, thesis_hm;
  for (const LevelSet& l : levels) {
    const Metrics m = evaluate(TrackerConfig::thesis(), l.cases, options);
    thesis_fm.push_back(m.frictionmap_rms);
    thesis_hm.push_back(m.heightmap_rms);
  }

  struct Scored {
    Tuned t;
    double hm = 0.0, fm_ratio = 0.0, lag = 0.0, rest = 0.0;
    std::vector<double> hm_level, rest_level;
    bool fits = false;  // lag and frictionmap constraints
  };
  std::vector<Scored> all;
  auto score = [&](const Tuned& t) {
    Scored s{t, 0.0, 0.0, 0.0, 0.0, {}, {}, false};
    for (size_t i = 0; i < levels.size(); ++i) {
      const Metrics m = evaluate(proposed_tracker(t, levels[i].sensor), levels[i].cases, options);
      s.hm += m.heightmap_rms / thesis_hm[i] / static_cast<double>(levels.size());
      s.hm_level.push_back(m.heightmap_rms / thesis_hm[i]);
      s.rest_level.push_back(m.heightmap_rest_rms);
      s.lag = std::max(s.lag, std::fabs(m.lag_ms));
      s.rest = std::max(s.rest, m.heightmap_rest_rms);
      s.fm_ratio = std::max(s.fm_ratio, m.frictionmap_rms / thesis_fm[i]);
    }
    s.fits = s.lag <= max_lag_ms && s.fm_ratio <= max_fm_ratio;
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
    char line[360];
    std::snprintf(line, sizeof line,
                  "%s dir q=%-5.0f pos q=%-5.0f fade=%.1f-%.1f sigma nis=%.0f  HM/thesis %.3f (%s)  |lag| %.2f ms  "
                  "FM/thesis %.3f  rest %.4f (%s)%s\n",
                  stage, static_cast<double>(s.t.direction_accel_px_s2), static_cast<double>(s.t.position_accel_px_s2),
                  static_cast<double>(s.t.rest_sigmas), static_cast<double>(s.t.moving_sigmas),
                  static_cast<double>(s.t.maneuver_nis), s.hm,
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

  Scored best = score(recommended_constants());
  print("start ", best);
  for (int round = 0; round < 2; ++round) {
    // The direction filter, the fade and the widening together: a smoother
    // filter allows a lower fade, a readier widening a smoother filter.
    const Tuned centre = best.t;
    for (float qf : {0.7f, 1.0f, 1.4f}) {
      for (float lo : {2.0f, 2.5f, 3.0f}) {
        for (float width : {2.0f, 3.0f}) {
          for (float nis : {6.0f, 9.0f, 16.0f}) {
            const Scored s = score({centre.direction_accel_px_s2 * qf, centre.position_accel_px_s2, lo, lo + width, nis});
            print("dir   ", s);
            if (better(s, best)) best = s;
          }
        }
      }
    }
    // The position filter: lag against the frictionmap.
    const Tuned direction = best.t;
    for (float qf : {0.6f, 1.5f, 2.2f}) {
      const Scored s = score({direction.direction_accel_px_s2, direction.position_accel_px_s2 * qf,
                              direction.rest_sigmas, direction.moving_sigmas, direction.maneuver_nis});
      print("pos   ", s);
      if (better(s, best)) best = s;
    }
  }
  // The trade-off: for each bound on rest chatter, the best moving error.
  log << "trade-off (|lag| <= " << max_lag_ms << " ms, frictionmap no worse than thesis): rest chatter bound -> best\n";
  for (double bound : {0.005, 0.01, 0.02, 0.04, 0.08}) {
    const Scored* pick = nullptr;
    for (const Scored& s : all)
      if (s.fits && s.rest <= bound && (pick == nullptr || s.hm < pick->hm)) pick = &s;
    if (pick != nullptr) {
      char tag[32];
      std::snprintf(tag, sizeof tag, "<=%.3f", bound);
      print(tag, *pick);
    }
  }
  print("best  ", best);
  return best.t;
}

// The per-class table: the thesis pipeline and recommended() on each class.
std::string run_classes(const std::vector<std::string>& names, double duration_s, const EvalOptions& base,
                        const Tuned& candidate, const std::string& dump_path) {
  EvalOptions options = base;
  options.cost = false;
  std::vector<ClassRow> rows;
  for (const tracegen::TraceClass& trace_class : tracegen::trace_classes()) {
    if (!names.empty() && std::find(names.begin(), names.end(), trace_class.name) == names.end()) continue;
    std::fprintf(stderr, "ff-track-bench: class %s: generating 6 traces of %.0f s...\n", trace_class.name, duration_s);
    std::vector<PreparedCase> cases;
    for (const TrackCase& c : class_cases(trace_class, duration_s)) cases.push_back(prepare_case(c));
    const double slow = slow_share(cases, options.moving_speed_px_s);
    const SensorProfile sensor = tracegen::nominal_profile(cases.front().spec.options);
    if (!dump_path.empty() && rows.empty()) {
      for (size_t i = 0; i < cases.size(); ++i) {
        std::ofstream dump(i == 0 ? dump_path : dump_path + "." + std::to_string(i));
        dump_ticks(dump, proposed_tracker(candidate, sensor), cases[i]);
      }
    }
    for (const auto& [name, config] : {std::pair<const char*, TrackerConfig>{"thesis", TrackerConfig::thesis()},
                                       {"recommended()", TrackerConfig::recommended()},
                                       {"recommended(profile)", proposed_tracker(candidate, sensor)}}) {
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
  Tuned tuned = recommended_constants();
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
  app.add_option("--direction-q", tuned.direction_accel_px_s2, "The direction filter's KalmanConfig::accel_noise_px_s2")
      ->capture_default_str()->group(row);
  app.add_option("--position-q", tuned.position_accel_px_s2, "The position filter's KalmanConfig::accel_noise_px_s2")
      ->capture_default_str()->group(row);
  app.add_option("--rest-sigmas", tuned.rest_sigmas, "TrackerConfig::rest_sigmas")->capture_default_str()->group(row);
  app.add_option("--moving-sigmas", tuned.moving_sigmas, "TrackerConfig::moving_sigmas")->capture_default_str()->group(row);
  app.add_option("--maneuver-nis", tuned.maneuver_nis, "TrackerConfig::maneuver_nis (0: never widen)")
      ->capture_default_str()->group(row);
  std::vector<std::string> trace_paths;
  TraceFileOptions trace_options;
  SensorProfile trace_sensor;
  ff::host::add_sensor_profile_options(app, trace_sensor);
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
    if (!trace_paths.empty()) {
      std::fprintf(stderr, "ff-track-bench: --classes works on generated traces; it takes no --trace\n");
      return 2;
    }
    if (app.count("--moving-above") == 0) options.moving_speed_px_s = kClassMovingSpeedPxS;
    if (run_tune) {
      std::vector<LevelSet> levels;
      for (const tracegen::TraceClass& trace_class : tracegen::trace_classes()) {
        if (!class_names.empty() && std::find(class_names.begin(), class_names.end(), trace_class.name) == class_names.end())
          continue;
        LevelSet level{trace_class.name, 0.0, {}, {}};
        for (const TrackCase& c : class_cases(trace_class, duration_s)) level.cases.push_back(prepare_case(c));
        level.sensor = tracegen::nominal_profile(level.cases.front().spec.options);
        levels.push_back(std::move(level));
      }
      const bool bounds_given = app.count("--max-lag") + app.count("--rest-bound") > 0;
      tuned = tune(levels, bounds_given ? rest_bound : kClassRestBound, bounds_given ? max_lag_ms : kClassMaxLagMs,
                   kClassMaxFrictionmapRatio, options, std::cerr);
    }
    const std::string table = run_classes(class_names, duration_s, options, tuned, dump_path);
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
    if (!load_trace_level(trace_paths, trace_options, trace_sensor, level, error)) {
      std::fprintf(stderr, "ff-track-bench: %s\n", error.c_str());
      return 2;
    }
    levels.push_back(std::move(level));
  }
  if (run_tune) tuned = tune(levels, rest_bound, max_lag_ms, 1.0, options, std::cerr);

  std::vector<ReportRow> rows;
  const bool with_tuned = run_tune || app.count("--direction-q") + app.count("--position-q") +
                                           app.count("--rest-sigmas") + app.count("--moving-sigmas") +
                                           app.count("--maneuver-nis") > 0;
  for (const NamedConfig& nc : standard_configs(tuned, with_tuned)) {
    for (const LevelSet& level : levels) {
      std::fprintf(stderr, "ff-track-bench: %s, %s noise\n", nc.name.c_str(), level.label.c_str());
      TrackerConfig config = nc.config;
      config.sensor = level.sensor;  // as calibrated: the thesis pipeline ignores it
      rows.push_back({nc.name, level.label, evaluate(config, level.cases, options)});
    }
  }
  if (!dump_path.empty()) {
    std::ofstream dump(dump_path);
    dump_ticks(dump, proposed_tracker(tuned, levels.front().sensor), levels.front().cases.front());
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
