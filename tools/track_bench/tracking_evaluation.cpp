#include "tracking_evaluation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <ostream>

#include "rest_chatter.hpp"
#include "support/models/trace_classes.hpp"
#include "support/statistics.hpp"
#include "frictionfield/core/haptic_pipeline.hpp"
#include "frictionfield/core/scenes.hpp"
#include "frictionfield/host/input_file.hpp"

namespace ff::bench {

using support::angle_deg;
using support::best_lag_ms;
using support::mean;
using support::percentile;
using support::Position2;
using support::rms;
using support::TimedPosition;

namespace {

constexpr uint64_t kTickUs = kTickPeriodUs;
constexpr double kCaseTimeOffsetS = 1e6;  // separates cases on one time axis for the lag

std::unique_ptr<ScenePlan> prepared(const SceneDefinition& def) {
  auto plan = std::make_unique<ScenePlan>();
  plan->prepare(def, nullptr, 0);  // closed form: no table memory
  return plan;
}

SensorSample to_sample(const tracegen::TraceSample& s) {
  return {static_cast<uint32_t>(s.t_us), static_cast<float>(s.x), static_cast<float>(s.y), s.touch};
}

// The tick schedule of docs/spec.md#tick-timing (the rule host::replay applies
// to trace files): every report stamped at or before a tick is delivered
// before that tick. The one tick loop of this file.
template <typename OnSample, typename OnTick>
void run_ticks(const PreparedCase& c, OnSample&& on_sample, OnTick&& on_tick) {
  const auto& samples = c.trace.samples;
  size_t next = 0;
  for (const TickTruth& tick : c.ticks) {
    while (next < samples.size() && samples[next].t_us <= tick.t_us) on_sample(to_sample(samples[next++]));
    on_tick(tick);
  }
}

// Host ns per tick of `Runner` (fresh for each pass): best of three passes.
template <typename Runner>
double best_ns_per_tick(const PreparedCase& c, const Runner& make) {
  double best = 1e300;
  for (int pass = 0; pass < 3; ++pass) {
    auto runner = make();
    float sink = 0.0f;
    const auto start = std::chrono::steady_clock::now();
    run_ticks(
        c, [&](const SensorSample& s) { runner->on_sample(s); },
        [&](const TickTruth& tick) { sink += runner->on_tick(static_cast<uint32_t>(tick.t_us)); });
    const auto stop = std::chrono::steady_clock::now();
    volatile float keep = sink;
    (void)keep;
    const double ns = std::chrono::duration<double, std::nano>(stop - start).count();
    best = std::min(best, ns / static_cast<double>(c.ticks.size()));
  }
  return best;
}

// The firmware's tick on the heightmap, and a tracker alone (a second, direction-only tracker).
struct PipelineRunner {
  HapticPipeline pipeline;
  explicit PipelineRunner(const TrackerConfig& config, Target target) : pipeline(config) {
    Condition condition;
    condition.scene = scenes::heightmap(target);
    pipeline.set_condition(condition);
  }
  void on_sample(const SensorSample& s) { pipeline.post_sample(s); }
  float on_tick(uint32_t t) { return pipeline.tick(t).amplitude; }
};
struct TrackerRunner {
  Tracker tracker;
  explicit TrackerRunner(const TrackerConfig& config) : tracker(config) {}
  void on_sample(const SensorSample& s) { tracker.on_sample(s); }
  float on_tick(uint32_t t) { return tracker.on_tick(t).direction.x; }
};

}  // namespace

Vec2 to_vec(tracegen::Point p) { return {static_cast<float>(p.x), static_cast<float>(p.y)}; }

Vec2 true_direction(const tracegen::TrueState& s) {
  const double speed = std::hypot(s.velocity.x, s.velocity.y);
  return speed > 0.0 ? to_vec({s.velocity.x / speed, s.velocity.y / speed}) : Vec2{};
}

bool judged_moving(const tracegen::TrueState& s, double moving_speed_px_s) {
  return s.touching && !s.resting && std::hypot(s.velocity.x, s.velocity.y) >= moving_speed_px_s;
}

bool standing_still(const tracegen::TrueState& s) { return std::hypot(s.velocity.x, s.velocity.y) < kStandstillPxS; }

std::vector<TrackCase> standard_cases(double noise_px, double duration_s) {
  struct Shape {
    const char* name;
    tracegen::Strategy strategy;
    Target target;
  };
  static constexpr Shape kShapes[] = {
      {"along-top", tracegen::Strategy::Along, Target::Top},
      {"along-middle", tracegen::Strategy::Along, Target::Middle},
      {"along-bottom", tracegen::Strategy::Along, Target::Bottom},
      {"across-top", tracegen::Strategy::Across, Target::Top},
      {"across-middle", tracegen::Strategy::Across, Target::Middle},
      {"across-bottom", tracegen::Strategy::Across, Target::Bottom},
  };
  std::vector<TrackCase> cases;
  uint64_t seed = 101;
  for (const Shape& shape : kShapes) {
    TrackCase c;
    c.name = shape.name;
    c.target = shape.target;
    tracegen::TraceOptions& o = c.options;
    o.seed = seed++;
    o.motion.strategy = shape.strategy;
    o.motion.paths = tracegen::PathChoice::All;
    o.motion.duration_s = duration_s;
    o.motion.rests = std::max(1, static_cast<int>(duration_s / 15.0));
    o.motion.lifts = 1;
    o.sensor.noise_px = noise_px;
    o.sensor.quantum_px = tracegen::kZForceQuantumPx;
    cases.push_back(c);
  }
  return cases;
}

namespace {

// Ticks from the first report to the tick at or after the last, with the
// truth there and what the ideal renderer outputs for it.
template <typename Truth>
void fill_ticks(PreparedCase& c, const Truth& truth_at) {
  c.heightmap = prepared(scenes::heightmap(c.spec.target));
  c.frictionmap = prepared(scenes::frictionmap(c.spec.target));
  if (c.trace.samples.empty()) return;
  const uint64_t t0 = c.trace.samples.front().t_us;
  const uint64_t last = (c.trace.end_us() - t0 + kTickUs - 1) / kTickUs;
  c.ticks.reserve(last + 1);
  for (uint64_t k = 0; k <= last; ++k) {
    TickTruth t;
    t.t_us = t0 + k * kTickUs;
    t.state = truth_at(t.t_us);
    const Vec2 p = to_vec(t.state.position);
    // The ideal renderer: true position, true unit direction (0.5 where undefined).
    t.heightmap_ideal = c.heightmap->amplitude(p, true_direction(t.state));
    t.frictionmap_ideal = c.frictionmap->amplitude(p, {});
    c.ticks.push_back(t);
  }
}

}  // namespace

PreparedCase prepare_case(const TrackCase& spec) {
  PreparedCase c;
  c.spec = spec;
  c.trace = tracegen::generate_trace(spec.options);
  fill_ticks(c, [&c](uint64_t t_us) { return c.trace.truth_at(t_us); });
  // Its own copy: a PreparedCase moves (into vectors), its members with it.
  auto motion = std::make_shared<const tracegen::Motion>(c.trace.motion);
  c.truth_position = [motion](double t_s) { return motion->at(t_s).position; };
  return c;
}

std::vector<PreparedCase> prepare_cases(const std::vector<TrackCase>& specs) {
  std::vector<PreparedCase> cases;
  cases.reserve(specs.size());
  for (const TrackCase& c : specs) cases.push_back(prepare_case(c));
  return cases;
}

bool load_trace_case(const std::string& path, const TraceFileOptions& options, PreparedCase& out, std::string& error) {
  std::ifstream in;
  std::string why;
  if (!host::open_input_file(path, in, why)) {
    error = path + ": " + why;
    return false;
  }
  host::SensorTraceReader reader(in);
  host::TraceError e;
  std::vector<host::TraceRow> rows;
  std::vector<host::TruthPoint> truth;
  if (!reader.read_header(e)) {
    error = e.to_string(path);
    return false;
  }
  host::TraceRow row;
  host::TruthPoint point;
  while (reader.next(row, e, &point)) {
    rows.push_back(row);
    truth.push_back(point);
  }
  if (!e.message.empty()) {
    error = e.to_string(path);
    return false;
  }
  if (rows.empty()) {
    error = path + ": no reports";
    return false;
  }
  PreparedCase c;
  c.spec.name = path;
  c.spec.target = options.target;
  const uint64_t t0 = rows.front().t_us;
  c.trace.start_us = t0;
  for (size_t i = 0; i < rows.size(); ++i) {
    tracegen::TraceSample s;
    s.t_us = rows[i].t_us;
    s.x = static_cast<double>(rows[i].x);
    s.y = static_cast<double>(rows[i].y);
    s.touch = rows[i].touch;
    s.x_true = truth[i].x;
    s.y_true = truth[i].y;
    c.trace.samples.push_back(s);
  }
  c.truth_from_columns = options.use_truth_columns && reader.has_truth();
  auto reference = std::make_shared<ReferencePath>(c.truth_from_columns ? ReferencePath::from_truth(rows, truth, t0)
                                                                         : ReferencePath::smoothed(rows, t0, options.smoother));
  if (reference->segments().empty()) {
    error = path + ": no stroke to judge (fewer than two usable touch reports in a row)";
    return false;
  }
  const double rest = options.rest_speed_px_s;
  fill_ticks(c, [&](uint64_t t_us) { return reference->at(static_cast<double>(t_us - t0) * 1e-6, rest); });
  c.truth_position = [reference, rest](double t_s) { return reference->at(t_s, rest).position; };
  out = std::move(c);
  return true;
}

void dump_ticks(std::ostream& out, const TrackerConfig& config, const PreparedCase& c) {
  out << "t_us,x_true,y_true,vx_true,vy_true,touching,resting,present,x,y,vx,vy,dx,dy,hm,hm_ideal,fm,fm_ideal,hm_true_dir,hm_unit_dir\n";
  Tracker tracker(config);
  run_ticks(c, [&](const SensorSample& sample) { tracker.on_sample(sample); }, [&](const TickTruth& tick) {
    const TrackState s = tracker.on_tick(static_cast<uint32_t>(tick.t_us));
    const float hm = c.heightmap->amplitude(s.position, s.direction);
    const float fm = c.frictionmap->amplitude(s.position, {});
    const float hm_true_dir = c.heightmap->amplitude(s.position, true_direction(tick.state));
    const float vl = length(s.velocity);
    const Vec2 unit = vl > 0.0f ? (1.0f / vl) * s.velocity : Vec2{};
    const float hm_unit_dir = c.heightmap->amplitude(to_vec(tick.state.position), unit);
    char line[512];
    std::snprintf(line, sizeof line, "%llu,%.3f,%.3f,%.2f,%.2f,%d,%d,%d,%.3f,%.3f,%.2f,%.2f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f\n",
                  static_cast<unsigned long long>(tick.t_us), tick.state.position.x, tick.state.position.y,
                  tick.state.velocity.x, tick.state.velocity.y, tick.state.touching ? 1 : 0, tick.state.resting ? 1 : 0,
                  s.present ? 1 : 0, static_cast<double>(s.position.x), static_cast<double>(s.position.y),
                  static_cast<double>(s.velocity.x), static_cast<double>(s.velocity.y), static_cast<double>(s.direction.x),
                  static_cast<double>(s.direction.y), static_cast<double>(hm), static_cast<double>(tick.heightmap_ideal),
                  static_cast<double>(fm), static_cast<double>(tick.frictionmap_ideal), static_cast<double>(hm_true_dir),
                  static_cast<double>(hm_unit_dir));
    out << line;
  });
}

SensorProfile nominal_profile(const PreparedCase& c) { return tracegen::nominal_profile(c.spec.options, c.trace); }

Metrics evaluate(const TrackerConfig& config, const std::vector<PreparedCase>& cases, const EvalOptions& options,
                 const TrackerConfig* direction_from) {
  return evaluate([&config](const PreparedCase&) { return config; }, cases, options, direction_from);
}

Metrics evaluate(const ConfigOfCase& config_of, const std::vector<PreparedCase>& cases, const EvalOptions& options,
                 const TrackerConfig* direction_from) {
  Metrics m;
  std::vector<double> position_error, direction_error, heightmap_error, frictionmap_error, unfaded_error;
  RestChatter rest;
  struct Estimate {
    const PreparedCase* c;
    uint64_t t_us;
    double x, y;
  };
  std::vector<Estimate> estimates;  // moving ticks, for the lag

  for (const PreparedCase& c : cases) {
    const TrackerConfig config = config_of(c);
    Tracker tracker(config);
    Tracker direction_tracker(direction_from != nullptr ? *direction_from : config);
    auto deliver = [&](const SensorSample& sample) {
      tracker.on_sample(sample);
      if (direction_from != nullptr) direction_tracker.on_sample(sample);
    };
    run_ticks(c, deliver, [&](const TickTruth& tick) {
      TrackState s = tracker.on_tick(static_cast<uint32_t>(tick.t_us));
      if (direction_from != nullptr) {
        const TrackState d = direction_tracker.on_tick(static_cast<uint32_t>(tick.t_us));
        s.velocity = d.velocity;
        s.direction = d.direction;
      }
      if (!tick.state.touching || !s.present) {
        rest.not_resting();
        if (tick.state.touching) ++m.untracked_ticks;
        return;
      }
      const float hm = c.heightmap->amplitude(s.position, s.direction);
      if (tick.state.resting) {
        rest.resting(tick.t_us, static_cast<double>(hm) - 0.5);
        return;
      }
      rest.not_resting();
      if (!judged_moving(tick.state, options.moving_speed_px_s)) return;
      ++m.moving_ticks;
      const double ex = static_cast<double>(s.position.x) - tick.state.position.x;
      const double ey = static_cast<double>(s.position.y) - tick.state.position.y;
      position_error.push_back(std::hypot(ex, ey));
      direction_error.push_back(angle_deg(static_cast<double>(s.velocity.x), static_cast<double>(s.velocity.y),
                                          tick.state.velocity.x, tick.state.velocity.y));
      heightmap_error.push_back(std::fabs(static_cast<double>(hm - tick.heightmap_ideal)));
      if (options.unfaded) {
        const float speed_estimate = length(s.velocity);
        const Vec2 unit = speed_estimate > 0.0f ? (1.0f / speed_estimate) * s.velocity : Vec2{};
        const float unfaded = c.heightmap->amplitude(s.position, unit);
        unfaded_error.push_back(std::fabs(static_cast<double>(unfaded - tick.heightmap_ideal)));
      }
      const float fm = c.frictionmap->amplitude(s.position, {});
      frictionmap_error.push_back(std::fabs(static_cast<double>(fm - tick.frictionmap_ideal)));
      estimates.push_back({&c, tick.t_us, static_cast<double>(s.position.x), static_cast<double>(s.position.y)});
    });
    rest.not_resting();  // a rest ends with its trace
  }

  m.position_rmse_px = rms(position_error);
  m.position_p95_px = percentile(position_error, 95.0);
  m.direction_mean_deg = mean(direction_error);
  m.direction_p95_deg = percentile(direction_error, 95.0);
  m.heightmap_rms = rms(heightmap_error);
  m.heightmap_p95 = percentile(heightmap_error, 95.0);
  m.frictionmap_rms = rms(frictionmap_error);
  m.frictionmap_p95 = percentile(frictionmap_error, 95.0);
  m.rest_ticks = rest.ticks();
  m.heightmap_rest_rms = rest.rms();
  m.heightmap_steady_rest_rms = rest.steady_rms();
  m.rest_transient_share = rest.transient_share();
  m.stops = rest.stops();
  m.unsettled_stops = rest.unsettled();
  m.stop_settle_median_ms = rest.settle_median_ms();
  m.stop_settle_max_ms = rest.settle_max_ms();
  m.heightmap_unfaded_rms = rms(unfaded_error);

  if (options.lag && !estimates.empty()) {
    // Times are global (case index * 1e6 s + motion time) so that one truth
    // function serves every case.
    std::vector<TimedPosition> timed;
    timed.reserve(estimates.size());
    for (const Estimate& e : estimates) {
      const double t_rel = static_cast<double>(static_cast<int64_t>(e.t_us - e.c->trace.start_us)) * 1e-6;
      timed.push_back({static_cast<double>(e.c - cases.data()) * kCaseTimeOffsetS + t_rel, e.x, e.y});
    }
    auto truth = [&cases](double t_s) {
      const size_t i = static_cast<size_t>(std::max(0.0, std::floor((t_s + 0.5 * kCaseTimeOffsetS) / kCaseTimeOffsetS)));
      const PreparedCase& c = cases[std::min(i, cases.size() - 1)];
      const tracegen::Point p = c.truth_position(t_s - static_cast<double>(i) * kCaseTimeOffsetS);
      return Position2{p.x, p.y};
    };
    m.lag_ms = best_lag_ms(timed, truth);
  }
  if (options.cost && !cases.empty()) {
    const PreparedCase& c = cases.front();
    const TrackerConfig config = config_of(c);
    m.ns_per_tick = best_ns_per_tick(c, [&] { return std::make_unique<PipelineRunner>(config, c.spec.target); });
    if (direction_from != nullptr) {
      m.ns_per_tick += best_ns_per_tick(c, [&] { return std::make_unique<TrackerRunner>(*direction_from); });
    }
  }
  return m;
}

}  // namespace ff::bench
