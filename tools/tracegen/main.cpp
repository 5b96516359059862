// ff-tracegen: synthetic finger traces with ground truth, for the replay,
// the tracking benchmark and the stress tests.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "frictionfield/host/cli_conventions.hpp"
#include "frictionfield/host/output_file.hpp"
#include "frictionfield/host/trace_csv.hpp"
#include "support/models/sensor_model.hpp"
#include "support/models/trace_classes.hpp"
#include "trace_writer.hpp"

namespace {

// Seeds and the first stamp stay exact in a double (the trace readers' bound
// is 2^53 us); 10,000 faults, rests or lifts of a kind keep placement (up to 1000 tries per
// fault) in int and in seconds.
constexpr double kMaxSeed = 9007199254740992.0;  // 2^53
constexpr double kMaxStartUs = 4503599627370496.0;  // 2^52: far below the 2^53 us readers accept
constexpr int kMaxFaultsOfAKind = 10000;

using namespace ff::tracegen;

constexpr const char* kDescription =
    "ff-tracegen: synthetic finger traces for the frictionfield touchscreen, with ground truth.\n"
    "\n"
    "A simulated participant explores the 800 x 480 px screen (1 px ~ 0.2 mm) like the thesis'\n"
    "participants did: back and forth along the three paths (--strategy along), in strokes across\n"
    "them (across), or both in turn (mixed). Every stroke is a minimum-jerk movement whose peak\n"
    "speed is drawn between --speed-min and --speed-max; the finger pauses briefly at each reversal.\n"
    "The zForce sensor is simulated at --rate Hz with timing jitter, Gaussian noise and optional\n"
    "quantisation, and each fault the tracker must handle can be inserted on request.\n"
    "What real fingers and sensors add (slow strokes, hesitations, sharp reversals, 8-12 Hz tremor;\n"
    "stamp latency, period jitter, correlated noise, drift) is off by default and switched on one\n"
    "by one or as a named class (--class; docs/tracking.md#trace-classes).\n"
    "\n"
    "Output (docs/spec.md#trace-files): '#' metadata lines (tool, command, seed, motion, sensor,\n"
    "faults), then t_us,x,y,touch,x_true,y_true[,x_tremor,y_tremor][,event], then '# summary:'\n"
    "  x_true, y_true  the true finger at t_us (readers ignore these columns; nan while lifted):\n"
    "                  its voluntary motion, without tremor\n"
    "  x_tremor, y_tremor  with tremor: the tremor's displacement at t_us, on top of x_true, y_true\n"
    "  event           with --events: what each row exercises (touch-down, lift-off, late, jump, ...)\n"
    "The same seed and options always give the same file (so the metadata has no date).";

constexpr const char* kFooter =
    "Examples:\n"
    "  ff-tracegen --strategy along --duration 10 --seed 3 -o along.csv\n"
    "  ff-tracegen --strategy across --noise high --quantise px --truth-ticks truth.csv -o across.csv\n"
    "  ff-tracegen --all-faults --events --wrap -o faults.csv     # every fault, clock wrapping\n"
    "  ff-tracegen --duration 3600 --lifts 200 --rests 300 -o hour.csv   # an hour-long session\n"
    "  ff-tracegen --class realistic-1khz --seed 4 -o real.csv    # every effect, 1 kHz\n"
    "  ff-tracegen --correlated-noise-px 1.5 --correlated-tau-ms 30 --noise-px 0.5 -o wander.csv\n"
    "  ff-tracegen --rest-only --class correlated-noise --duration 10 -o rest.csv   # to calibrate";

// Whether two output names are one file, whether or not it exists yet.
bool same_path(const std::string& a, const std::string& b) {
  namespace fs = std::filesystem;
  return fs::weakly_canonical(fs::absolute(a)) == fs::weakly_canonical(fs::absolute(b));
}

struct Cli {
  std::string output = "-";
  std::string trace_class;
  std::string truth_ticks;
  std::string strategy = "mixed";
  std::string paths = "all";
  std::string noise = "low";
  double noise_px = -1.0;
  std::string quantise = "none";
  double quantum_px = -1.0;
  bool events = false;
  bool all_faults = false;
  bool progress = false;
  bool quiet = false;
};

void print_progress(const char* what, double fraction) {
  std::fprintf(stderr, "\rff-tracegen: %s %3d%%", what, static_cast<int>(std::lround(100.0 * fraction)));
  if (fraction >= 1.0) std::fprintf(stderr, "\n");
  std::fflush(stderr);
}

struct Counts {
  int strokes = 0, rests = 0, lifts = 0;
  double peak_max_px_s = 0.0, peak_mean_px_s = 0.0;
  std::string rows_by_kind;  // "touch-down=1 lift-off=1 late=2 ..."
};

Counts count(const GeneratedTrace& trace) {
  Counts c;
  double peak_sum = 0.0;
  for (const Segment& s : trace.motion.segments()) {
    if (s.kind == SegmentKind::Stroke) {
      ++c.strokes;
      peak_sum += s.peak_speed_px_s;
      c.peak_max_px_s = std::max(c.peak_max_px_s, s.peak_speed_px_s);
    } else if (s.kind == SegmentKind::Hold && s.rest) {
      ++c.rests;
    } else if (s.kind == SegmentKind::Lifted) {
      ++c.lifts;
    }
  }
  c.peak_mean_px_s = c.strokes ? peak_sum / c.strokes : 0.0;
  c.rows_by_kind = "touch-down=" + std::to_string(trace.events[static_cast<int>(SampleEvent::TouchDown)]) +
                   " lift-off=" + std::to_string(trace.events[static_cast<int>(SampleEvent::LiftReport)]);
  for (int e = static_cast<int>(SampleEvent::AfterGap); e < static_cast<int>(SampleEvent::kCount); ++e) {
    if (trace.events[e] == 0) continue;
    c.rows_by_kind += " " + std::string(to_string(static_cast<SampleEvent>(e))) + "=" + std::to_string(trace.events[e]);
  }
  return c;
}

__attribute__((format(printf, 1, 2))) std::string format(const char* fmt, ...) {
  char buf[512];
  va_list args;
  va_start(args, fmt);
  std::vsnprintf(buf, sizeof buf, fmt, args);
  va_end(args);
  return buf;
}

// The command as typed, quoted as a POSIX shell reads it back: an argument
// with spaces or quotes in single quotes, each ' in it written '\''.
std::string command_line(int argc, char** argv) {
  std::string line = "ff-tracegen";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (!a.empty() && a.find_first_of(" \t'\"\\$`") == std::string::npos) {
      line += " " + a;
      continue;
    }
    line += " '";
    for (char c : a) line += c == '\'' ? std::string("'\\''") : std::string(1, c);
    line += "'";
  }
  return line;
}

std::string motion_words(const TraceOptions& o) {
  const MotionOptions& m = o.motion;
  const std::string tremor =
      o.tremor.amplitude_px > 0.0
          ? format("tremor %g px at %g-%g Hz", o.tremor.amplitude_px, o.tremor.min_hz, o.tremor.max_hz)
          : "no tremor";
  if (m.rest_only) return format("a finger at rest for %g s, %s", m.duration_s, tremor.c_str());
  return format("%s strategy, %s paths, %g s, peaks %g-%g mm/s, dwell up to %g s, %d rests, %d lifts, "
                "slow strokes %g %%, hesitations %g %%, reversals %g %%, %s",
                to_string(m.strategy), to_string(m.paths), m.duration_s, m.speed_min_mm_s, m.speed_max_mm_s,
                m.dwell_max_s, m.rests, m.lifts, 100.0 * m.slow_fraction, 100.0 * m.hesitation_fraction,
                100.0 * m.reversal_fraction, tremor.c_str());
}

std::string sensor_words(const SensorOptions& s) {
  return format("%g Hz, stamp jitter %g us, noise %g px, quantum %g px, latency %g-%g us, period jitter %g us, "
                "correlated noise %g px (tau %g ms), drift %g px (tau %g s)",
                s.rate_hz, s.jitter_us, s.noise_px, s.quantum_px, s.latency_us, s.latency_us + s.latency_spread_us,
                s.period_jitter_us, s.correlated_noise_px, s.correlated_noise_tau_s * 1e3, s.drift_px, s.drift_tau_s);
}

// "missing 1 of 2, jumps 0 of 3": the kinds of which fewer found a site than
// were asked for ("" if all did).
std::string unplaced_words(const FaultOptions& asked, const FaultOptions& placed) {
  std::string words;
  const auto kind = [&words](const char* name, int a, int p) {
    if (p < a) words += format("%s%s %d of %d", words.empty() ? "" : ", ", name, p, a);
  };
  kind("missing", asked.missing, placed.missing);
  kind("late", asked.late, placed.late);
  kind("jumps", asked.jumps, placed.jumps);
  kind("duplicates", asked.duplicates, placed.duplicates);
  kind("non-finite", asked.non_finite, placed.non_finite);
  kind("off-screen", asked.off_screen, placed.off_screen);
  return words;
}

std::string fault_words(const FaultOptions& f) {
  const std::string start =
      f.wrap ? "the 32-bit clock wraps mid-stroke" : "first report at t_us " + std::to_string(f.start_us);
  return format("missing %d, late %d, jumps %d, duplicates %d, non-finite %d, off-screen %d, %s", f.missing, f.late,
                f.jumps, f.duplicates, f.non_finite, f.off_screen, start.c_str());
}

ff::host::Metadata metadata(const TraceOptions& o, const GeneratedTrace& trace, const std::string& trace_class,
                            const std::string& command) {
  ff::host::Metadata m = {{"tool", std::string("ff-tracegen ") + ff::host::project_version()},
                          {"command", command},
                          {"seed", std::to_string(o.seed)}};
  if (!trace_class.empty()) m.push_back({"class", trace_class});
  m.push_back({"motion", motion_words(o)});
  m.push_back({"sensor", sensor_words(o.sensor)});
  m.push_back({"faults", fault_words(o.faults)});
  const std::string unplaced = unplaced_words(o.faults, trace.faults_placed);
  if (!unplaced.empty()) m.push_back({"faults-placed", unplaced + " (no room for the rest)"});
  return m;
}

void print_summary(const GeneratedTrace& trace, const TraceOptions& o, const Counts& c) {
  std::fprintf(stderr, "ff-tracegen: %zu rows, %.2f s, %s strategy, seed %llu, noise %.2f px, t_us %llu..%llu%s\n",
               trace.samples.size(), trace.motion.duration_s(), to_string(o.motion.strategy),
               static_cast<unsigned long long>(o.seed), o.sensor.noise_px,
               static_cast<unsigned long long>(trace.samples.empty() ? 0 : trace.samples.front().t_us),
               static_cast<unsigned long long>(trace.end_us()),
               trace.end_us() >= (uint64_t{1} << 32) && trace.start_us < (uint64_t{1} << 32) ? " (32-bit clock wraps)" : "");
  std::fprintf(stderr, "ff-tracegen: %d strokes, peak speed mean %.0f mm/s, max %.0f mm/s; %d rests, %d lifts\n",
               c.strokes, c.peak_mean_px_s * kMmPerPx, c.peak_max_px_s * kMmPerPx, c.rests, c.lifts);
  const SensorOptions& so = o.sensor;
  if (trace.tremor.enabled() || o.motion.slow_fraction > 0.0 || o.motion.hesitation_fraction > 0.0 ||
      o.motion.reversal_fraction > 0.0 || so.latency_us > 0.0 || so.latency_spread_us > 0.0 ||
      so.period_jitter_us > 0.0 || so.correlated_noise_px > 0.0 || so.drift_px > 0.0) {
    char tremor[64] = "no tremor";
    if (trace.tremor.enabled())
      std::snprintf(tremor, sizeof tremor, "tremor %.2f px at %.1f Hz", o.tremor.amplitude_px, trace.tremor.frequency_hz());
    std::fprintf(stderr,
                 "ff-tracegen: slow strokes %.0f %%, hesitations %.0f %%, reversals %.0f %%, %s; "
                 "%.0f Hz, latency %.0f-%.0f us, period jitter %.0f us, correlated noise %.2f px (tau %.0f ms), drift %.2f px\n",
                 100.0 * o.motion.slow_fraction, 100.0 * o.motion.hesitation_fraction, 100.0 * o.motion.reversal_fraction,
                 tremor, so.rate_hz, so.latency_us,
                 so.latency_us + so.latency_spread_us, so.period_jitter_us, so.correlated_noise_px,
                 so.correlated_noise_tau_s * 1e3, so.drift_px);
  }
  std::fprintf(stderr, "ff-tracegen: rows by kind: %s\n", c.rows_by_kind.c_str());
}

// The value of --class NAME / --class=NAME, read before the other options
// so that the class is the starting point they modify ("" if none).
std::string class_argument(int argc, char** argv) {
  const std::string flag = "--class";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == flag && i + 1 < argc) return argv[i + 1];
    if (a.rfind(flag + "=", 0) == 0) return a.substr(flag.size() + 1);
  }
  return "";
}

}  // namespace

int main(int argc, char** argv) {
  TraceOptions o;
  Cli cli;
  std::vector<std::string> known_classes;
  for (const TraceClass& c : trace_classes()) known_classes.push_back(c.name);
  if (const TraceClass* preset = find_trace_class(class_argument(argc, argv))) preset->apply(o);
  CLI::App app{kDescription, "ff-tracegen"};
  app.footer(kFooter);
  app.get_formatter()->column_width(34);

  app.add_option("-o,--output", cli.output, "Trace file to write ('-' = standard output)")->capture_default_str();
  app.add_option("--truth-ticks", cli.truth_ticks,
                 "Also write the true finger at every 500 us tick (t_us,x_true,y_true,vx_true,vy_true,touch) "
                 "from the first report on, for comparing a replay tick by tick");
  // Integer options are range-checked as doubles: CLI11 would wrap -1 to 2^64 - 1 for an unsigned option.
  app.add_option("--seed", o.seed, "Random seed: same seed and options, same trace")
      ->check(CLI::Range(0.0, kMaxSeed))
      ->capture_default_str();
  app.add_option("--duration", o.motion.duration_s, "Length of the exploration in seconds")
      ->capture_default_str()->check(CLI::Range(0.05, 24.0 * 3600.0));

  std::string class_help = "Start from a named class of finger and sensor; the options below change it "
                           "(docs/tracking.md#trace-classes):";
  for (const TraceClass& c : trace_classes()) class_help += std::string("\n  ") + c.name + ": " + c.description;
  app.add_option("--class", cli.trace_class, class_help)->check(CLI::IsMember(known_classes));

  auto* motion = "Motion";
  std::vector<CLI::Option*> strokes;  // what --rest-only leaves out
  strokes.push_back(app.add_option("--strategy", cli.strategy,
                                   "along: back and forth along the paths; across: strokes across them; "
                                   "mixed: both in turn")
                        ->capture_default_str()->check(CLI::IsMember({"along", "across", "mixed"}))->group(motion));
  strokes.push_back(app.add_option("--paths", cli.paths,
                                   "Which path(s) the along-strategy follows: all, top, middle, bottom")
                        ->capture_default_str()->check(CLI::IsMember({"all", "top", "middle", "bottom"}))
                        ->group(motion));
  strokes.push_back(app.add_option("--speed-min", o.motion.speed_min_mm_s, "Slowest stroke's peak speed (mm/s)")
                        ->capture_default_str()->check(CLI::Range(1.0, 5000.0))->group(motion));
  strokes.push_back(app.add_option("--speed-max", o.motion.speed_max_mm_s, "Fastest stroke's peak speed (mm/s)")
                        ->capture_default_str()->check(CLI::Range(1.0, 5000.0))->group(motion));
  strokes.push_back(app.add_option("--dwell-max", o.motion.dwell_max_s, "Longest pause at a reversal (s; uniform from 0)")
                        ->capture_default_str()->check(CLI::Range(0.0, 10.0))->group(motion));
  strokes.push_back(app.add_option("--rests", o.motion.rests, "Rests: the finger stays still on the screen for 0.6-2 s")
                        ->capture_default_str()->check(CLI::Range(0, kMaxFaultsOfAKind))->group(motion));
  strokes.push_back(app.add_option("--lifts", o.motion.lifts,
                                   "Lift-offs: the finger leaves for 0.15-0.6 s and lands elsewhere")
                        ->capture_default_str()->check(CLI::Range(0, kMaxFaultsOfAKind))->group(motion));
  strokes.push_back(app.add_option("--slow-strokes", o.motion.slow_fraction,
                                   "Share of strokes that are slow: peak 20-70 px/s (4-14 mm/s), lasting 0.8-2 s")
                        ->capture_default_str()->check(CLI::Range(0.0, 1.0))->group(motion));
  strokes.push_back(app.add_option("--hesitations", o.motion.hesitation_fraction,
                                   "Share of strokes that stop mid-way for 0.08-0.3 s")
                        ->capture_default_str()->check(CLI::Range(0.0, 1.0))->group(motion));
  strokes.push_back(app.add_option("--reversals", o.motion.reversal_fraction,
                                   "Share of strokes that turn straight back (no dwell) for 15-40 % of their length")
                        ->capture_default_str()->check(CLI::Range(0.0, 1.0))->group(motion));
  CLI::Option* rest_only =
      app.add_flag("--rest-only", o.motion.rest_only,
                   "No strokes: the finger rests at the middle of the screen for --duration (with tremor if "
                   "asked), a calibration recording for ff-track-bench --calibrate; with --all-faults, no rests "
                   "or lifts")
          ->group(motion);
  // A resting finger makes no strokes: an option about them would be ignored.
  for (CLI::Option* stroke_option : strokes) rest_only->excludes(stroke_option);
  app.add_option("--tremor-px", o.tremor.amplitude_px, "Tremor amplitude, peak per axis (px; physiological "
                                                       "0.5-2.5 px = 0.1-0.5 mm); in the reports, not in x_true")
      ->capture_default_str()->check(CLI::Range(0.0, 50.0))->group(motion);
  app.add_option("--tremor-hz", o.tremor.min_hz, "Lowest tremor frequency (Hz; drawn once per trace up to --tremor-hz-max)")
      ->capture_default_str()->check(CLI::Range(0.1, 100.0))->group(motion);
  app.add_option("--tremor-hz-max", o.tremor.max_hz, "Highest tremor frequency (Hz)")
      ->capture_default_str()->check(CLI::Range(0.1, 100.0))->group(motion);

  auto* sensor = "Sensor";
  app.add_option("--rate", o.sensor.rate_hz, "Sensor report rate (Hz)")
      ->capture_default_str()->check(CLI::Range(10.0, 2000.0))->group(sensor);
  app.add_option("--jitter-us", o.sensor.jitter_us, "Timing jitter, 1 sigma (us; clipped to 30 % of the period)")
      ->capture_default_str()->check(CLI::Range(0.0, 1e5))->group(sensor);
  app.add_option("--noise", cli.noise, "Position noise: none, low (1 px = 0.2 mm, 1 sigma per axis) or "
                                       "high (2.5 px = 0.5 mm: 95 % within ~1.2 mm)")
      ->capture_default_str()->check(CLI::IsMember({"none", "low", "high"}))->group(sensor);
  app.add_option("--noise-px", cli.noise_px, "Position noise, 1 sigma per axis in px (overrides --noise)")
      ->check(CLI::Range(0.0, 100.0))->group(sensor);
  app.add_option("--quantise", cli.quantise, "Round reported coordinates: none, px (whole pixels) or "
                                             "zforce (0.1 mm = 0.5 px, the zForce's unit)")
      ->capture_default_str()->check(CLI::IsMember({"none", "px", "zforce"}))->group(sensor);
  app.add_option("--quantum-px", cli.quantum_px, "Round reported coordinates to this step in px (overrides --quantise)")
      ->check(CLI::Range(0.0, 100.0))->group(sensor);
  app.add_option("--latency-us", o.sensor.latency_us, "Reports describe the finger this long before their timestamp")
      ->capture_default_str()->check(CLI::Range(0.0, 1e6))->group(sensor);
  app.add_option("--latency-spread-us", o.sensor.latency_spread_us, "Each report's latency varies: --latency-us "
                                                                    "+ uniform(0, this) (us)")
      ->capture_default_str()->check(CLI::Range(0.0, 1e6))->group(sensor);
  app.add_option("--period-jitter-us", o.sensor.period_jitter_us, "The scan interval varies, 1 sigma (us; clipped to "
                                                                  "30 % of the period): the report clock wanders")
      ->capture_default_str()->check(CLI::Range(0.0, 1e5))->group(sensor);
  double correlated_tau_ms = o.sensor.correlated_noise_tau_s * 1e3;
  app.add_option("--correlated-noise-px", o.sensor.correlated_noise_px, "Temporally correlated noise (first-order "
                                                                        "Gauss-Markov), 1 sigma per axis (px), added to the white noise")
      ->capture_default_str()->check(CLI::Range(0.0, 100.0))->group(sensor);
  app.add_option("--correlated-tau-ms", correlated_tau_ms, "Its correlation time (ms)")
      ->capture_default_str()->check(CLI::Range(0.01, 1e5))->group(sensor);
  app.add_option("--drift-px", o.sensor.drift_px, "Slow drift of the reported frame, 1 sigma per axis (px)")
      ->capture_default_str()->check(CLI::Range(0.0, 1000.0))->group(sensor);
  app.add_option("--drift-tau-s", o.sensor.drift_tau_s, "Its correlation time (s)")
      ->capture_default_str()->check(CLI::Range(0.01, 1e5))->group(sensor);

  auto* faults = "Faults (each inserted N times at seeded random places, away from each other)";
  app.add_option("--missing", o.faults.missing, "Gaps of 1-6 missing reports")->check(CLI::Range(0, kMaxFaultsOfAKind))->group(faults);
  app.add_option("--late", o.faults.late, "Reports read 1-12 ms late (stamped at the read, measured at the scan)")
      ->check(CLI::Range(0, kMaxFaultsOfAKind))->group(faults);
  app.add_option("--jumps", o.faults.jumps, "1-3 reports from a second finger or a glitch, >= 150 px away")
      ->check(CLI::Range(0, kMaxFaultsOfAKind))->group(faults);
  app.add_option("--duplicates", o.faults.duplicates,
                 "Non-increasing timestamps, in turn: an exact duplicate row, a new report with the same "
                 "timestamp, a report stamped before its predecessor")
      ->check(CLI::Range(0, kMaxFaultsOfAKind))->group(faults);
  app.add_option("--nan", o.faults.non_finite, "Reports with nan or infinite coordinates")
      ->check(CLI::Range(0, kMaxFaultsOfAKind))->group(faults);
  app.add_option("--off-screen", o.faults.off_screen, "Reports far outside the screen (-300, 900, 65535, 880)")
      ->check(CLI::Range(0, kMaxFaultsOfAKind))->group(faults);
  app.add_flag("--wrap", o.faults.wrap, "Start so that the 32-bit microsecond clock wraps mid-stroke near the "
                                        "middle (t_us passes 2^32 = 4294967296 in the file)")->group(faults);
  app.add_option("--start-us", o.faults.start_us, "Time stamp of the first report (ignored with --wrap)")
      ->check(CLI::Range(0.0, kMaxStartUs))
      ->capture_default_str()->group(faults);
  app.add_flag("--all-faults", cli.all_faults, "Shorthand: 2 of each fault above, 2 rests and 2 lifts "
                                               "(explicit counts win)")->group(faults);

  auto* output = "Output";
  app.add_flag("--events", cli.events, "Add an 'event' column naming what each row exercises")->group(output);
  app.add_flag("--progress", cli.progress, "Show progress (on by default for traces over 5 minutes)")->group(output);
  app.add_flag("-q,--quiet", cli.quiet, "No summary or progress on standard error")->group(output);

  if (const int code = ff::host::parse_command_line(app, argc, argv); code >= 0) return code;

  parse_strategy(cli.strategy, o.motion.strategy);
  parse_path_choice(cli.paths, o.motion.paths);
  if (o.motion.speed_max_mm_s < o.motion.speed_min_mm_s) {
    std::fprintf(stderr, "ff-tracegen: --speed-max (%g) is below --speed-min (%g)\n", o.motion.speed_max_mm_s,
                 o.motion.speed_min_mm_s);
    return 2;
  }
  if (o.tremor.max_hz < o.tremor.min_hz) {
    std::fprintf(stderr, "ff-tracegen: --tremor-hz-max (%g) is below --tremor-hz (%g)\n", o.tremor.max_hz,
                 o.tremor.min_hz);
    return 2;
  }
  if (!cli.truth_ticks.empty() && cli.truth_ticks != "-" && cli.output != "-" &&
      same_path(cli.truth_ticks, cli.output)) {
    std::fprintf(stderr, "ff-tracegen: --truth-ticks %s is the trace's own file (-o): choose another\n",
                 cli.truth_ticks.c_str());
    return ff::host::kExitBadUsage;
  }
  o.sensor.correlated_noise_tau_s = correlated_tau_ms * 1e-3;
  // A class brings its own noise and quantum; --noise and --quantise change them when given.
  const bool from_class = !cli.trace_class.empty();
  if (!from_class || app.count("--noise") > 0)
    o.sensor.noise_px = cli.noise == "none" ? 0.0 : (cli.noise == "high" ? kNoiseHighPx : kNoiseLowPx);
  if (cli.noise_px >= 0.0) o.sensor.noise_px = cli.noise_px;
  if (!from_class || app.count("--quantise") > 0)
    o.sensor.quantum_px = cli.quantise == "px" ? 1.0 : (cli.quantise == "zforce" ? kZForceQuantumPx : 0.0);
  if (cli.quantum_px >= 0.0) o.sensor.quantum_px = cli.quantum_px;
  if (cli.all_faults) {
    auto at_least = [&app](const char* option, int& count, int value) {
      if (app.count(option) == 0) count = value;
    };
    at_least("--missing", o.faults.missing, 2);
    at_least("--late", o.faults.late, 2);
    at_least("--jumps", o.faults.jumps, 2);
    at_least("--duplicates", o.faults.duplicates, 3);
    at_least("--nan", o.faults.non_finite, 2);
    at_least("--off-screen", o.faults.off_screen, 2);
    at_least("--rests", o.motion.rests, 2);
    at_least("--lifts", o.motion.lifts, 2);
  }
  const bool show_progress = !cli.quiet && (cli.progress || o.motion.duration_s > 300.0);

  if (show_progress) print_progress("planning and sampling", 0.0);
  const GeneratedTrace trace = generate_trace(o);
  if (show_progress) print_progress("planning and sampling", 1.0);

  const Counts counts = count(trace);
  const std::string command = command_line(argc, argv);
  ff::host::ToolOutput out(cli.output);
  if (!out.open()) {
    std::fprintf(stderr, "ff-tracegen: %s\n", out.error().c_str());
    return ff::host::kExitBadUsage;
  }
  ff::host::write_metadata(out.stream(), metadata(o, trace, cli.trace_class, command));
  write_trace(out.stream(), trace, cli.events);
  std::string summary = format("rows=%zu strokes=%d rests=%d lifts=%d %s", trace.samples.size(), counts.strokes,
                               counts.rests, counts.lifts, counts.rows_by_kind.c_str());
  if (trace.tremor.enabled()) summary += format(" tremor_hz=%.2f", trace.tremor.frequency_hz());  // drawn per trace
  ff::host::write_metadata(out.stream(), {{"summary", summary}});
  if (!out.commit()) {
    std::fprintf(stderr, "ff-tracegen: %s\n", out.error().c_str());
    return ff::host::kExitBadUsage;
  }

  if (!cli.truth_ticks.empty()) {
    ff::host::ToolOutput ticks(cli.truth_ticks);
    if (!ticks.open()) {
      std::fprintf(stderr, "ff-tracegen: %s\n", ticks.error().c_str());
      return ff::host::kExitBadUsage;
    }
    ff::host::Metadata m = metadata(o, trace, cli.trace_class, command);
    m.insert(m.begin() + 1, {"what", "the true finger at every 500 us tick of the trace " + cli.output});
    ff::host::write_metadata(ticks.stream(), m);
    Progress progress;
    if (show_progress) progress = [](double f) { print_progress("truth at ticks", f); };
    const uint64_t rows = write_truth_ticks(ticks.stream(), trace, progress);
    if (!ticks.commit()) {
      std::fprintf(stderr, "ff-tracegen: %s\n", ticks.error().c_str());
      return ff::host::kExitBadUsage;
    }
    if (!cli.quiet) std::fprintf(stderr, "ff-tracegen: %llu tick rows in %s\n", static_cast<unsigned long long>(rows),
                                 cli.truth_ticks.c_str());
  }
  if (!cli.quiet) print_summary(trace, o, counts);
  // Said also with -q: the trace holds fewer faults than its command asks for.
  if (const std::string unplaced = unplaced_words(o.faults, trace.faults_placed); !unplaced.empty())
    std::fprintf(stderr,
                 "ff-tracegen: warning: not every fault found a site (%s): each needs 8 ordinary reports of a "
                 "finger on either side, away from the others; a longer --duration makes room\n",
                 unplaced.c_str());
  return 0;
}
