#pragma once
// Runs a tracker configuration over generated traces, tick for tick as the
// replay does (docs/spec.md#tick-timing), and measures what is felt:
// position, lag, direction and the rendered amplitude against an ideal
// renderer fed the true position and the true direction.
#include <functional>
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

#include "frictionfield/core/path_curve.hpp"
#include "frictionfield/core/scene_plan.hpp"
#include "frictionfield/core/tracker.hpp"
#include "reference_path.hpp"
#include "support/models/sensor_model.hpp"

namespace ff::bench {

struct TrackCase {
  std::string name;
  tracegen::TraceOptions options;
  Target target = Target::Middle;  // of the heightmap and frictionmap scenes
};

// The fixed benchmark set at one noise level (1 sigma, px): both search
// strategies, all three targets, zForce quantisation, 200 Hz with jitter,
// rests and a lift. The motion does not depend on the noise level.
std::vector<TrackCase> standard_cases(double noise_px, double duration_s);

// A generator point (double) as the core's vector (float).
Vec2 to_vec(tracegen::Point p);

// The finger's true unit direction of motion (0 at a standstill): what the
// ideal renderer is fed.
Vec2 true_direction(const tracegen::TrueState& s);

// Where every metric judges a tracker "while moving": the finger down, not
// resting, at least moving_speed_px_s fast.
bool judged_moving(const tracegen::TrueState& s, double moving_speed_px_s);

// Slower than this the finger stands still: where a start begins (the
// start floors, the anchored bound).
constexpr double kStandstillPxS = 1.0;
bool standing_still(const tracegen::TrueState& s);

// The truth at one tick and what the ideal renderer outputs there.
struct TickTruth {
  uint64_t t_us = 0;
  tracegen::TrueState state;
  float heightmap_ideal = 0.5f;
  float frictionmap_ideal = 0.0f;
};

struct PreparedCase {
  TrackCase spec;
  tracegen::GeneratedTrace trace;  // a loaded file: its reports, no motion
  std::vector<TickTruth> ticks;  // t0 + k * 500 us, t0 = the first report
  std::unique_ptr<ScenePlan> heightmap;
  std::unique_ptr<ScenePlan> frictionmap;
  // Where the finger was, s after the first report (for the lag).
  std::function<tracegen::Point(double t_s)> truth_position;
  bool truth_from_columns = true;  // false: judged against the offline smoother
};

// Generates the trace, prepares both scenes (closed form) and the ideal
// amplitudes at every tick.
PreparedCase prepare_case(const TrackCase& spec);
std::vector<PreparedCase> prepare_cases(const std::vector<TrackCase>& specs);

struct TraceFileOptions {
  Target target = Target::Middle;  // the heightmap and frictionmap the amplitudes are judged on
  bool use_truth_columns = true;   // x_true, y_true when the file has them
  double rest_speed_px_s = 10.0;   // a slower reference finger counts as resting
  SmootherOptions smoother;
};

// A trace file (t_us,x,y,touch[,x_true,y_true]) as a case, judged against its
// truth columns or, without them, the offline smoother (reference_path.hpp).
// false with a one-line `error` for an unreadable file or one without a stroke.
bool load_trace_case(const std::string& path, const TraceFileOptions& options, PreparedCase& out, std::string& error);

struct EvalOptions {
  double moving_speed_px_s = 50.0;  // the finger "moves" above 10 mm/s
  bool lag = true;                  // the slowest metric
  bool cost = true;                 // time the pipeline's tick
  bool unfaded = false;             // also Metrics::heightmap_unfaded_rms (one more amplitude per tick)
};

struct Metrics {
  double position_rmse_px = 0.0;
  double position_p95_px = 0.0;
  double lag_ms = 0.0;             // time shift minimising the position RMSE
  double direction_mean_deg = 0.0;
  double direction_p95_deg = 0.0;
  double heightmap_rms = 0.0;      // |A - A_ideal| while moving
  double heightmap_p95 = 0.0;
  double frictionmap_rms = 0.0;
  double frictionmap_p95 = 0.0;
  double heightmap_rest_rms = 0.0; // |A - 0.5| while the finger rests
  // The same split at each stop (rest_chatter.hpp): after the first
  // kStopTransientUs of each rest; that first part's share of the squares;
  // the stops, those that never settled, and how long the others took.
  double heightmap_steady_rest_rms = 0.0;
  double rest_transient_share = 0.0;
  size_t stops = 0;
  size_t unsettled_stops = 0;
  double stop_settle_median_ms = 0.0;
  double stop_settle_max_ms = 0.0;
  // |A - A_ideal| while moving had the direction never been faded (the
  // estimate's velocity at unit length): what a perfect motion oracle in place
  // of the direction confidence would leave. EvalOptions::unfaded only.
  double heightmap_unfaded_rms = 0.0;
  double ns_per_tick = 0.0;        // HapticPipeline::tick() on the heightmap, host
  size_t moving_ticks = 0;
  size_t rest_ticks = 0;
  size_t untracked_ticks = 0;      // finger down but no track (before the first tick after touch-down)
};

// Every tick of one case as CSV: t_us, truth (x, y, vx, vy, touching, resting),
// estimate (present, x, y, vx, vy, dx, dy), amplitudes (heightmap, ideal, frictionmap, ideal),
// and where the heightmap's error comes from: the heightmap with the true direction at the
// estimated position (the position's share) and with the estimate's unit direction, unfaded,
// at the true position (the direction's share without the fade).
void dump_ticks(std::ostream& out, const TrackerConfig& config, const PreparedCase& c);

// With `direction_from`, a second tracker with that configuration runs
// alongside and supplies the velocity and direction (a candidate estimator:
// position from one filter, direction from a smoother one).
Metrics evaluate(const TrackerConfig& config, const std::vector<PreparedCase>& cases, const EvalOptions& options,
                 const TrackerConfig* direction_from = nullptr);

// What calibrating a generated case's finger on its sensor would give
// (tracegen::nominal_profile with the trace's own tremor frequency).
SensorProfile nominal_profile(const PreparedCase& c);

// Each case with a configuration of its own: a tracker tuned to each trace's
// sensor and finger (e.g. recommended(nominal_profile(case))).
using ConfigOfCase = std::function<TrackerConfig(const PreparedCase&)>;
Metrics evaluate(const ConfigOfCase& config_of, const std::vector<PreparedCase>& cases, const EvalOptions& options,
                 const TrackerConfig* direction_from = nullptr);

}  // namespace ff::bench
