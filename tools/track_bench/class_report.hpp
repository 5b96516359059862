#pragma once
// Tracking accuracy per trace class (issue 14): each named class of finger
// and sensor (support/models/trace_classes.hpp) on the standard strokes, for
// the thesis pipeline and recommended(), and each metric as a ratio to the
// thesis pipeline's on the same class.
#include <iosfwd>
#include <iterator>
#include <string>
#include <vector>

#include "lookahead_bound.hpp"
#include "support/models/trace_classes.hpp"
#include "tracking_evaluation.hpp"

namespace ff::bench {

// The finger "moves" above 4 mm/s in the class table, so that slow strokes,
// starts and stops (20-70 px/s) are judged too.
constexpr double kClassMovingSpeedPxS = 20.0;

// Issue 14's goals on every class: heightmap error at most 0.45x the thesis
// pipeline's (0.35x on white-200hz), lag at most 1 ms, frictionmap at most
// 0.8x, chatter at rest at most 0.01 (RMS of A - 0.5).
constexpr double kClassMaxHeightmapRatio = 0.45;
constexpr double kClassMaxHeightmapRatioWhite = 0.35;
constexpr double kClassMaxLagMs = 1.0;
constexpr double kClassMaxFrictionmapRatio = 0.8;
constexpr double kClassRestBound = 0.01;
// The heightmap goal of one class: the white-noise class has its own.
double class_heightmap_goal(const std::string& trace_class);

// standard_cases' six strokes and targets with the class's finger and sensor.
std::vector<TrackCase> class_cases(const tracegen::TraceClass& trace_class, double duration_s);

// Share of the moving ticks (speed >= moving_speed_px_s) at 20-70 px/s: how slow a class is.
double slow_share(const std::vector<PreparedCase>& cases, double moving_speed_px_s);

struct ClassRow {
  std::string trace_class;
  std::string tracker;  // per class, the first row is the thesis pipeline, the baseline of the ratios
  Metrics metrics;
  double slow_share = 0.0;
};

void write_class_report(std::ostream& out, const std::vector<ClassRow>& rows, double duration_s,
                        double moving_speed_px_s);

// The chatter at rest split at every stop (rest_chatter.hpp): what of it is
// the ~20 ms after the finger stops, what is steady, and how long each stop
// takes to settle; every row of the class table.
void write_rest_report(std::ostream& out, const std::vector<ClassRow>& rows);

// The heightmap error no tracker can avoid at the starts of strokes: that of
// a tracker that knows the finger's position and direction exactly, except
// during the first `distance_px` of motion after every standstill (true
// speed below kStandstillPxS, tracking_evaluation.hpp), where it renders 0.5, as a direction cannot be
// told from the reports' noise before the finger has moved about that far.
// RMS over the moving ticks (speed >= moving_speed_px_s, not resting), as
// Metrics::heightmap_rms.
constexpr double kStartFloorDistancesPx[] = {0.5, 1.0, 2.0};
double start_floor_rms(const std::vector<PreparedCase>& cases, double moving_speed_px_s, double distance_px);

struct StartFloorRow {
  std::string trace_class;
  double thesis_heightmap_rms = 0.0;
  double floor_rms[std::size(kStartFloorDistancesPx)] = {};
  // The shipping tracker's heightmap error, and the same never faded while
  // the finger moves (Metrics::heightmap_unfaded_rms): the part a perfect
  // direction confidence would remove, against the part its direction causes.
  double tracker_heightmap_rms = 0.0;
  double unfaded_heightmap_rms = 0.0;
};
void write_start_floor(std::ostream& out, const std::vector<StartFloorRow>& rows);

// Every figure of the four tables as CSV, one row per class and tracker
// (the class's floors and lookahead bounds on each of its rows, the unfaded
// error on the rows that measured it), for plots
// (tools/track_bench/plot_classes.py). No metadata: the caller writes it first.
void write_class_csv(std::ostream& out, const std::vector<ClassRow>& rows, const std::vector<StartFloorRow>& floors,
                     const std::vector<LookaheadRow>& lookahead);

}  // namespace ff::bench
