// ff-track-bench: how well each tracker configuration renders what the
// finger should feel, on generated traces with ground truth.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <iterator>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "frictionfield/host/cli_conventions.hpp"
#include "frictionfield/host/output_file.hpp"
#include "frictionfield/host/sensor_profile_options.hpp"
#include "frictionfield/host/trace_csv.hpp"
#include "bench_report.hpp"
#include "class_report.hpp"
#include "fade_frontier.hpp"
#include "direction_bound.hpp"
#include "heading_bound.hpp"
#include "lookahead_bound.hpp"
#include "proposed_config.hpp"
#include "sensor_calibration.hpp"
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
    "thesis pipeline and recommended(), with recommended()'s ratio to the thesis pipeline; then where\n"
    "the heightmap error comes from (start floors, the tracker unfaded), the chatter at each stop, and\n"
    "the bound of a constant-velocity filter with a perfect motion detector seeing 0-100 ms ahead,\n"
    "an observer told only when each stroke starts (a heading model), and the floor of an observer\n"
    "told all but where each stroke goes; last, the heading model told nothing, each stroke ended where\n"
    "a minimum-jerk fit to its reports predicts (docs/tracking-research.md#predicted-ends).\n"
    "With --frontier: per class, recommended(profile) with its direction confidence's two fade levels swept\n"
    "over a grid: the heightmap error while moving against the chatter at rest, the whole trade\n"
    "between the two (docs/tracking.md#fade-frontier).\n"
    "With --calibrate: a SensorProfile estimated from a recording of a resting finger, and the line\n"
    "that sends it to the device (docs/tracking.md#calibration); of the sensor-profile flags it takes\n"
    "only --latency-us (a recording cannot show the latency).";

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
  SensorProfile sensor;    // what the trackers are told about the sensor
  bool generated = false;  // then each trace is told its own tremor's frequency, as calibrated
  SensorProfile profile_of(const PreparedCase& c) const { return generated ? nominal_profile(c) : sensor; }
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
    LevelSet level{label, noise, {}, {}, true};
    level.cases = prepare_cases(standard_cases(noise, duration_s));
    level.sensor = tracegen::nominal_profile(level.cases.front().spec.options);
    levels.push_back(std::move(level));
  }
  return levels;
}

// Grid search for the finger's acceleration densities and the direction
// confidence's fade. The objective is the heightmap amplitude error while
// moving (mean over the sets); candidates must keep the lag under max_lag_ms,
// the frictionmap error within max_fm_ratio of the thesis pipeline's, and the
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
      const LevelSet& level = levels[i];
      const Metrics m =
          evaluate([&](const PreparedCase& c) { return proposed_tracker(t, level.profile_of(c)); }, level.cases, options);
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
                  "%s dir q=%-5.0f pos q=%-5.0f fade=%.1f-%.1f sigma maneuver=%.0f/%.0fms  HM/thesis %.3f (%s)  |lag| %.2f ms  "
                  "FM/thesis %.3f  rest %.4f (%s)%s\n",
                  stage, static_cast<double>(s.t.direction_accel_px_s2), static_cast<double>(s.t.position_accel_px_s2),
                  static_cast<double>(s.t.rest_sigmas), static_cast<double>(s.t.moving_sigmas),
                  static_cast<double>(s.t.maneuver_threshold), static_cast<double>(s.t.maneuver_time_ms), s.hm,
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
        for (float width : {2.0f, 2.5f, 3.0f}) {
          for (float threshold : {9.0f, 12.0f, 16.0f}) {
            const Scored s = score({centre.direction_accel_px_s2 * qf, centre.position_accel_px_s2, lo, lo + width,
                                    threshold, centre.maneuver_time_ms});
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
                              direction.rest_sigmas, direction.moving_sigmas, direction.maneuver_threshold,
                              direction.maneuver_time_ms});
      print("pos   ", s);
      if (better(s, best)) best = s;
    }
  }
  // The trade-off: for each bound on rest chatter, the best moving error.
  log << "trade-off (|lag| <= " << max_lag_ms << " ms, frictionmap <= " << max_fm_ratio
      << "x the thesis pipeline's): rest chatter bound -> best\n";
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

// No names: every class.
bool selected(const std::vector<std::string>& names, const char* trace_class) {
  return names.empty() || std::find(names.begin(), names.end(), trace_class) != names.end();
}

struct ClassResults {
  std::vector<ClassRow> rows;
  std::vector<StartFloorRow> floors;
  std::vector<LookaheadRow> lookahead;
};

// --dump-ticks: every tick of one case behind '#' metadata, written whole or
// not at all (host::ToolOutput). false after a one-line message.
bool write_tick_dump(const std::string& path, const Tuned& tuned, const SensorProfile& profile,
                     const PreparedCase& c) {
  host::ToolOutput out(path);
  if (out.open()) {
    host::write_metadata(out.stream(),
                         {{"tool", std::string("ff-track-bench --dump-ticks ") + host::project_version()},
                          {"date", host::utc_timestamp()},
                          {"trace", c.spec.name},
                          {"tracker", tuned_name(tuned)},
                          {"sensor_profile", host::sensor_profile_flags(profile)},
                          {"what", "every 500 us tick: the truth, the tracker's estimate, the rendered and the ideal "
                                   "amplitudes (0..1, strength 1); tools/track_bench/standstill_breakdown.py reads it"}});
    dump_ticks(out.stream(), proposed_tracker(tuned, profile), c);
    if (out.commit()) return true;
  }
  std::fprintf(stderr, "ff-track-bench: %s\n", out.error().c_str());
  return false;
}

// --class C --dump-ticks FILE: the first selected class's six traces as FILE,
// FILE.1 ... FILE.5, each told its own profile as the class table's
// recommended(profile) row is.
bool dump_class_ticks(const std::vector<std::string>& names, double duration_s, const Tuned& tuned,
                      const std::string& path) {
  for (const tracegen::TraceClass& trace_class : tracegen::trace_classes()) {
    if (!selected(names, trace_class.name)) continue;
    const std::vector<PreparedCase> cases = prepare_cases(class_cases(trace_class, duration_s));
    for (size_t i = 0; i < cases.size(); ++i)
      if (!write_tick_dump(i == 0 ? path : path + "." + std::to_string(i), tuned, nominal_profile(cases[i]), cases[i]))
        return false;
    return true;
  }
  return true;
}

// The per-class figures: the thesis pipeline and recommended() on each class.
ClassResults run_classes(const std::vector<std::string>& names, double duration_s, const EvalOptions& base,
                         const Tuned& candidate) {
  EvalOptions options = base;
  options.cost = false;
  std::vector<ClassRow> rows;
  std::vector<StartFloorRow> floors;
  std::vector<LookaheadRow> lookahead;
  for (const tracegen::TraceClass& trace_class : tracegen::trace_classes()) {
    if (!selected(names, trace_class.name)) continue;
    std::fprintf(stderr, "ff-track-bench: class %s: generating 6 traces of %.0f s...\n", trace_class.name, duration_s);
    const std::vector<PreparedCase> cases = prepare_cases(class_cases(trace_class, duration_s));
    const double slow = slow_share(cases, options.moving_speed_px_s);
    const SensorProfile sensor = tracegen::nominal_profile(cases.front().spec.options);
    rows.push_back({trace_class.name, "thesis", evaluate(TrackerConfig::thesis(), cases, options), slow});
    rows.push_back({trace_class.name, "recommended()", evaluate(TrackerConfig::recommended(), cases, options), slow});
    EvalOptions profile_options = options;
    profile_options.unfaded = true;
    auto calibrated = [&candidate](const PreparedCase& c) { return proposed_tracker(candidate, nominal_profile(c)); };
    rows.push_back({trace_class.name, "recommended(profile)", evaluate(calibrated, cases, profile_options), slow});
    StartFloorRow floor{trace_class.name, rows[rows.size() - 3].metrics.heightmap_rms, {}};
    floor.tracker_heightmap_rms = rows.back().metrics.heightmap_rms;
    floor.unfaded_heightmap_rms = rows.back().metrics.heightmap_unfaded_rms;
    for (size_t i = 0; i < std::size(kStartFloorDistancesPx); ++i)
      floor.floor_rms[i] = start_floor_rms(cases, options.moving_speed_px_s, kStartFloorDistancesPx[i]);
    floors.push_back(floor);
    LookaheadRow bound = lookahead_row(trace_class.name, cases, options.moving_speed_px_s,
                                       static_cast<double>(sensor.white_noise_px),
                                       static_cast<double>(sensor.correlated_noise_px), sensor.latency_us * 1e-6);
    bound.thesis_heightmap_rms = floor.thesis_heightmap_rms;
    bound.tracker_heightmap_rms = floor.tracker_heightmap_rms;
    bound.heading_bound_rms = heading_bound_heightmap_rms(cases, options.moving_speed_px_s, ReportNoise::of(sensor));
    bound.direction_bound_rms = class_direction_bound(trace_class, cases, duration_s, options.moving_speed_px_s);
    HeadingBoundOptions predicted;
    predicted.boundaries = StrokeBoundaries::PredictedEnds;
    bound.predicted_ends = heading_bound(cases, options.moving_speed_px_s, ReportNoise::of(sensor), predicted);
    predicted.boundaries = StrokeBoundaries::TrackerEnds;
    bound.tracker_ends = heading_bound(cases, options.moving_speed_px_s, ReportNoise::of(sensor), predicted);
    lookahead.push_back(bound);
  }
  return {rows, floors, lookahead};
}

// The five per-class tables.
std::string class_tables(const ClassResults& results, double duration_s, double moving_speed_px_s) {
  std::ostringstream table;
  write_class_report(table, results.rows, duration_s, moving_speed_px_s);
  table << "\n";
  write_start_floor(table, results.floors);
  table << "\n";
  write_rest_report(table, results.rows);
  table << "\n";
  write_lookahead_report(table, results.lookahead);
  table << "\n";
  write_predicted_ends_report(table, results.lookahead);
  return table.str();
}

// What a per-class run (--classes, --frontier) prints and, on request, writes:
// the table to stdout, the CSV behind the run's metadata, the table into the
// doc between the run's markers. The exit code.
struct ClassRunOutput {
  const char* flag;
  const char* what;    // the CSV's "what" metadata: where the figures are explained
  const char* marker;  // of the doc section
};
int emit_class_run(const ClassRunOutput& run, const std::string& table, const std::string& csv_body, double duration_s,
                   double moving_speed_px_s, const std::string& csv_path, const std::string& doc_path) {
  std::cout << table;
  if (!csv_path.empty()) {
    std::ostringstream csv, traces, moving;
    traces << "the standard set's 6 strokes per class, " << duration_s << " s each, generated (not a sensor)";
    moving << moving_speed_px_s;
    host::write_metadata(csv, {{"tool", std::string("ff-track-bench ") + run.flag + " " + host::project_version()},
                               {"date", host::utc_timestamp()},
                               {"traces", traces.str()},
                               {"moving_above_px_s", moving.str()},
                               {"what", run.what}});
    csv << csv_body;
    std::string error;
    if (!host::write_file_atomically(csv_path, csv.str(), error)) {
      std::fprintf(stderr, "ff-track-bench: %s\n", error.c_str());
      return host::kExitBadUsage;
    }
    std::fprintf(stderr, "ff-track-bench: figures written to %s\n", csv_path.c_str());
  }
  if (!doc_path.empty()) {
    std::string error;
    if (!replace_marked_section(doc_path, table, error, run.marker)) {
      std::fprintf(stderr, "ff-track-bench: %s\n", error.c_str());
      return host::kExitBadUsage;
    }
    std::fprintf(stderr, "ff-track-bench: table written to %s\n", doc_path.c_str());
  }
  return 0;
}

// --frontier: the fade's trade per class, printed, and as CSV and in a doc on request.
int run_frontier(const std::vector<std::string>& names, double duration_s, const EvalOptions& options,
                 const Tuned& base, const std::string& csv_path, const std::string& doc_path) {
  std::vector<FrontierRow> rows;
  for (const tracegen::TraceClass& trace_class : tracegen::trace_classes()) {
    if (!selected(names, trace_class.name)) continue;
    std::fprintf(stderr, "ff-track-bench: class %s: 6 traces of %.0f s, %zu fades...\n", trace_class.name, duration_s,
                 frontier_grid().size());
    const std::vector<PreparedCase> cases = prepare_cases(class_cases(trace_class, duration_s));
    rows.push_back(fade_frontier(trace_class.name, cases, tracegen::nominal_profile(cases.front().spec.options), base,
                                 options));
  }
  std::ostringstream table, csv;
  write_frontier_report(table, rows, duration_s);
  write_frontier_csv(csv, rows);
  return emit_class_run({"--frontier", "docs/tracking.md#fade-frontier; heightmap ratios are to the thesis pipeline",
                         "track-bench-frontier"},
                        table.str(), csv.str(), duration_s, options.moving_speed_px_s, csv_path, doc_path);
}

// Each configuration on each level: the report table. With `tell_sensor`,
// every tracker is told the level's sensor; without, each keeps its own.
std::string judge(const std::vector<NamedConfig>& configs, const std::vector<LevelSet>& levels,
                  const EvalOptions& options, const std::string& description, bool tell_sensor) {
  std::vector<ReportRow> rows;
  for (const NamedConfig& nc : configs) {
    for (const LevelSet& level : levels) {
      std::fprintf(stderr, "ff-track-bench: %s, %s noise\n", nc.name.c_str(), level.label.c_str());
      TrackerConfig config = nc.config;
      if (tell_sensor) config.sensor = level.sensor;  // as calibrated: the thesis pipeline ignores it
      rows.push_back({nc.name, level.label, evaluate(config, level.cases, options)});
    }
  }
  std::ostringstream table;
  write_report(table, rows, description, options.moving_speed_px_s);
  return table.str();
}

std::string recorded_set_description(const LevelSet& level) {
  size_t with_truth = 0;
  for (const PreparedCase& c : level.cases) with_truth += c.truth_from_columns ? 1 : 0;
  return std::to_string(level.cases.size()) + " trace file(s), " + std::to_string(with_truth) +
         " judged against their x_true, y_true columns, " + std::to_string(level.cases.size() - with_truth) +
         " against the offline smoother (not ground truth)";
}

// The estimates as a table, then the lines that use them.
void print_calibration(std::ostream& out, const std::string& path, const Calibration& c,
                       const CalibrationOptions& o) {
  const SensorProfile& p = c.profile;
  char line[400];
  std::snprintf(line, sizeof line,
                "Sensor profile from %s: %zu touch reports in %zu run(s), %.2f s; %zu of %zu intervals outside "
                "%.1f-%.1f x the median (%.0f us) left out of rate and jitter (missed or late reports).\n\n",
                path.c_str(), c.reports, c.runs, c.duration_s, c.dropped_intervals, c.intervals + c.dropped_intervals,
                2.0 - o.max_interval_factor, o.max_interval_factor, c.median_interval_us);
  out << line;
  if (c.off_screen + c.not_after > 0) {
    std::snprintf(line, sizeof line,
                  "Left out: %zu touch row(s) off the screen or not finite, %zu stamped at or before the one before.\n\n",
                  c.off_screen, c.not_after);
    out << line;
  }
  if (c.glitches > 0) {
    std::snprintf(line, sizeof line,
                  "Left out of the noise: %zu report(s) more than %.0f px from where the finger rests (a glitch or "
                  "a second finger); their stamps count for the timing.\n\n",
                  c.glitches, c.glitch_threshold_px);
    out << line;
  }
  out << "| quantity | estimate | unit | how |\n|---|--:|---|---|\n";
  auto row = [&](const char* what, double value, int decimals, const char* unit, const std::string& how) {
    std::snprintf(line, sizeof line, "| %s | %.*f | %s | %s |\n", what, decimals, value, unit, how.c_str());
    out << line;
  };
  row("white noise (with quantisation), 1 sigma per axis", p.white_noise_px, 2, "px", "C(0) minus the terms below");
  char how[200];
  std::snprintf(how, sizeof how, "exponential term of the autocovariance fit%s",
                p.correlated_noise_px > 0.0f ? "" : " (not significant: 0)");
  row("correlated noise, 1 sigma per axis", p.correlated_noise_px, 2, "px", how);
  // A time constant at the longest tried: the wander is slower than the fit can tell (a drift).
  std::snprintf(how, sizeof how, "its time constant");
  if (p.correlated_noise_px > 0.0f && static_cast<double>(p.correlation_time_ms) >= 0.999 * o.max_tau_s * 1e3) {
    std::snprintf(how, sizeof how,
                  "its time constant, the longest the fit tries: a slower wander (a drift?) of which only what "
                  "varies within %.0f ms is in the profile",
                  o.max_tau_s * 1e3);
  }
  row("correlation time", p.correlation_time_ms, 1, "ms", how);
  if (c.tremor_hz > 0.0)
    std::snprintf(how, sizeof how, "cosine term at the spectral peak, %.2f Hz (%.0f x its neighbourhood)", c.tremor_hz,
                  c.tremor_peak_ratio);
  else
    std::snprintf(how, sizeof how, "no peak in %.0f-%.0f Hz (strongest %.1f x its neighbourhood; needs > %.0f): 0",
                  o.tremor_min_hz, o.tremor_max_hz, c.tremor_peak_ratio, o.tremor_peak_ratio);
  row("tremor, peak per axis", p.tremor_px, 2, "px", how);
  row("tremor frequency", p.tremor_hz, 2, "Hz", p.tremor_hz > 0.0f ? "the spectral peak" : "no tremor found: 0");
  row("report rate", p.report_rate_hz, 1, "Hz", "1 / mean interval");
  row("jitter, 1 sigma of the report interval", p.jitter_us, 0, "us", "standard deviation of the intervals");
  row("latency", static_cast<double>(p.latency_us), 0, "us",
      "not measurable from a recording: as given by --latency-us");
  std::snprintf(line, sizeof line,
                "\nFit: total noise %.2f px (sqrt C(0)), slow part %.3f px^2, residual RMS %.4f px^2 over %zu lag bins "
                "up to %.0f ms; correlated term improves the fit %.0f x (needs > %.0f); the finger's %.0f s mean moved "
                "%.1f px (at most %.0f).\n\n",
                c.total_noise_px, c.slow_px2, c.fit_rms_px2, c.lag_bins, o.max_lag_s * 1e3, c.correlated_improvement,
                o.correlated_improvement, o.detrend_window_s, c.range_px, o.max_range_px);
  out << line;
  out << "To send it to the device:\n  ffctl sensor-profile " << host::sensor_profile_flags(p) << "\n";
  out << "For ff-replay and ff-track-bench:\n  " << host::sensor_profile_flags(p) << "\n";
}

// The flags line with a '#' header.
bool write_profile_file(const std::string& path, const std::string& input, const SensorProfile& profile,
                        std::string& error) {
  std::ostringstream out;
  host::write_metadata(out, {{"tool", std::string("ff-track-bench --calibrate ") + host::project_version()},
                             {"input", input},
                             {"date", host::utc_timestamp()},
                             {"what", "a SensorProfile estimated from a resting finger (docs/tracking.md#calibration); "
                                      "latency_us is not measurable from a recording: as given by --latency-us"}});
  out << host::sensor_profile_flags(profile) << "\n";
  return host::write_file_atomically(path, out.str(), error);
}

// --calibrate REST.csv [STROKES.csv]: 0, or 2 with one line for a recording that gives no profile.
int run_calibration(const std::vector<std::string>& paths, const SensorProfile& given, const std::string& profile_out,
                    const TraceFileOptions& trace_options, const EvalOptions& options) {
  std::vector<host::TraceRow> rows;
  host::TraceError read_error;
  if (!host::read_sensor_trace_file(paths[0], rows, read_error)) {
    std::fprintf(stderr, "ff-track-bench: %s\n", read_error.to_string(paths[0]).c_str());
    return 2;
  }
  const CalibrationOptions calibration_options;
  Calibration calibration;
  std::string error;
  if (!calibrate_from_rest(rows, calibration_options, given.latency_us, calibration, error)) {
    std::fprintf(stderr, "ff-track-bench: %s: %s\n", paths[0].c_str(), error.c_str());
    return 2;
  }
  print_calibration(std::cout, paths[0], calibration, calibration_options);
  std::cout.flush();
  if (!profile_out.empty()) {
    if (!write_profile_file(profile_out, paths[0], calibration.profile, error)) {
      std::fprintf(stderr, "ff-track-bench: %s\n", error.c_str());
      return host::kExitBadUsage;
    }
    std::fprintf(stderr, "ff-track-bench: profile written to %s\n", profile_out.c_str());
  }
  if (paths.size() < 2) return 0;
  std::vector<LevelSet> levels(1);
  if (!load_trace_level({paths[1]}, trace_options, calibration.profile, levels.front(), error)) {
    std::fprintf(stderr, "ff-track-bench: %s\n", error.c_str());
    return 2;
  }
  const std::vector<NamedConfig> configs = {
      {"thesis (ticks + 1-euro, filtered derivative)", TrackerConfig::thesis()},
      {"recommended()", TrackerConfig::recommended()},
      {"recommended(calibrated profile)", TrackerConfig::recommended(calibration.profile)},
  };
  std::cout << "\nOn " << paths[1] << ": the thesis pipeline, recommended() for the default profile and for the "
                                      "calibrated one.\n\n"
            << judge(configs, levels, options, recorded_set_description(levels.front()), false);
  return 0;
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
  app.add_option("--maneuver-threshold", tuned.maneuver_threshold,
                 "TrackerConfig::maneuver_threshold (chi^2, 2 dof; 0: never widen)")
      ->capture_default_str()->group(row);
  app.add_option("--maneuver-time-ms", tuned.maneuver_time_ms, "TrackerConfig::maneuver_time_ms")
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
  bool frontier = false;
  app.add_flag("--frontier", frontier, "Instead of the class tables: recommended(profile) with its fade's two levels "
                                       "swept over a grid, the heightmap error while moving against the chatter at "
                                       "rest per class (docs/tracking.md#fade-frontier); --csv for "
                                       "tools/track_bench/plot_frontier.py. With --write-doc, between "
                                       "<!-- track-bench-frontier:begin --> and <!-- track-bench-frontier:end -->")
      ->group(per_class);
  app.add_option("--class", class_names, "Only these classes (implies --classes)")
      ->check(CLI::IsMember(known_classes))->group(per_class);
  std::vector<std::string> calibrate_paths;
  std::string profile_out;
  auto* calibration = "Calibration (docs/tracking.md#calibration)";
  app.add_option("--calibrate", calibrate_paths,
                 "REST.csv [STROKES.csv]: estimate the sensor profile from a recording of a finger resting still "
                 "(t_us,x,y,touch; >= 1 s and 100 reports, 10 s recommended) and print it with the ffctl "
                 "sensor-profile line that sends it to the device; latency comes from --latency-us. With STROKES.csv, "
                 "judge the thesis pipeline, recommended() and recommended(calibrated profile) on it as --trace does")
      ->expected(1, 2)->check(CLI::ExistingFile)->group(calibration);
  app.add_option("--profile-out", profile_out, "With --calibrate: also write the profile's flags (with a '#' header: "
                                               "tool, version, input, date) to this file")
      ->group(calibration);
  std::string dump_path;
  std::string csv_path;
  app.add_option("--csv", csv_path, "With --classes: also write every figure of the tables to this CSV (with '#' "
                                    "metadata), for tools/track_bench/plot_classes.py");
  app.add_option("--dump-ticks", dump_path, "Write every tick of the first low-noise trace for the tuned configuration "
                                            "(truth, estimate, amplitudes) to this CSV (with '#' metadata), for plots "
                                            "and tools/track_bench/standstill_breakdown.py; with --class, the first "
                                            "class's six traces as FILE, FILE.1 ... FILE.5");
  if (const int code = ff::host::parse_command_line(app, argc, argv); code >= 0) return code;

  trace_options.target = target_word == "top" ? Target::Top : (target_word == "bottom" ? Target::Bottom : Target::Middle);
  if (!calibrate_paths.empty()) {
    if (classes || !class_names.empty() || !trace_paths.empty() || run_tune || !doc_path.empty()) {
      std::fprintf(stderr, "ff-track-bench: --calibrate takes none of --classes, --class, --trace, --tune, --write-doc\n");
      return 2;
    }
    if (!profile_out.empty() && host::same_file(calibrate_paths[0], profile_out)) {
      std::fprintf(stderr, "ff-track-bench: --profile-out %s would overwrite the recording\n", profile_out.c_str());
      return 2;
    }
    return run_calibration(calibrate_paths, trace_sensor, profile_out, trace_options, options);
  }
  if (!profile_out.empty()) {
    std::fprintf(stderr, "ff-track-bench: --profile-out needs --calibrate\n");
    return 2;
  }

  if (!csv_path.empty() && !classes && class_names.empty() && !frontier) {
    std::fprintf(stderr, "ff-track-bench: --csv needs --classes, --class or --frontier\n");
    return 2;
  }
  if (frontier) {
    if (!trace_paths.empty() || run_tune || !dump_path.empty()) {
      std::fprintf(stderr, "ff-track-bench: --frontier works on generated traces; it takes none of --trace, --tune, "
                           "--dump-ticks\n");
      return 2;
    }
    if (app.count("--moving-above") == 0) options.moving_speed_px_s = kClassMovingSpeedPxS;
    return run_frontier(class_names, duration_s, options, tuned, csv_path, doc_path);
  }
  if (classes || !class_names.empty()) {
    if (!trace_paths.empty()) {
      std::fprintf(stderr, "ff-track-bench: --classes works on generated traces; it takes no --trace\n");
      return 2;
    }
    if (app.count("--moving-above") == 0) options.moving_speed_px_s = kClassMovingSpeedPxS;
    if (run_tune) {
      std::vector<LevelSet> levels;
      for (const tracegen::TraceClass& trace_class : tracegen::trace_classes()) {
        if (!selected(class_names, trace_class.name)) continue;
        LevelSet level{trace_class.name, 0.0, {}, {}, true};
        level.cases = prepare_cases(class_cases(trace_class, duration_s));
        level.sensor = tracegen::nominal_profile(level.cases.front().spec.options);
        levels.push_back(std::move(level));
      }
      const bool bounds_given = app.count("--max-lag") + app.count("--rest-bound") > 0;
      tuned = tune(levels, bounds_given ? rest_bound : kClassRestBound, bounds_given ? max_lag_ms : kClassMaxLagMs,
                   kClassMaxFrictionmapRatio, options, std::cerr);
    }
    if (!dump_path.empty() && !dump_class_ticks(class_names, duration_s, tuned, dump_path)) return host::kExitBadUsage;
    const ClassResults results = run_classes(class_names, duration_s, options, tuned);
    const std::string table = class_tables(results, duration_s, options.moving_speed_px_s);
    std::ostringstream csv;
    write_class_csv(csv, results.rows, results.floors, results.lookahead);
    return emit_class_run({"--classes", "docs/tracking.md#trace-classes; ratios are to the thesis row of each class",
                           "track-bench-classes"},
                          table, csv.str(), duration_s, options.moving_speed_px_s, csv_path, doc_path);
  }

  std::vector<LevelSet> levels;
  if (trace_paths.empty()) {
    std::fprintf(stderr, "ff-track-bench: generating 2 x 6 traces of %.0f s...\n", duration_s);
    levels = prepare_levels(duration_s);
  } else {
    LevelSet level;
    std::string error;
    if (!load_trace_level(trace_paths, trace_options, trace_sensor, level, error)) {
      std::fprintf(stderr, "ff-track-bench: %s\n", error.c_str());
      return 2;
    }
    levels.push_back(std::move(level));
  }
  if (run_tune) tuned = tune(levels, rest_bound, max_lag_ms, 1.0, options, std::cerr);

  const bool with_tuned = run_tune || app.count("--direction-q") + app.count("--position-q") +
                                           app.count("--rest-sigmas") + app.count("--moving-sigmas") +
                                           app.count("--maneuver-threshold") + app.count("--maneuver-time-ms") > 0;
  if (!dump_path.empty()) {
    const LevelSet& first = levels.front();
    if (!write_tick_dump(dump_path, tuned, first.profile_of(first.cases.front()), first.cases.front()))
      return host::kExitBadUsage;
  }
  const std::string table =
      judge(standard_configs(tuned, with_tuned), levels, options,
            trace_paths.empty() ? generated_set_description(duration_s) : recorded_set_description(levels.front()),
            true);
  std::cout << table;
  if (!doc_path.empty()) {
    std::string error;
    if (!replace_marked_section(doc_path, table, error)) {
      std::fprintf(stderr, "ff-track-bench: %s\n", error.c_str());
      return host::kExitBadUsage;
    }
    std::fprintf(stderr, "ff-track-bench: table written to %s\n", doc_path.c_str());
  }
  return 0;
}
