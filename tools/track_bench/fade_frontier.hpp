#pragma once
// The direction confidence's trade (issue 14): the shipping tracker with the
// two levels of its fade (TrackerConfig::rest_sigmas, moving_sigmas) swept
// over a grid, per trace class: the heightmap error while the finger moves
// against the chatter at rest. Only the fade changes, so lag, position and
// frictionmap stay as shipped: this is the whole trade between the two goals
// the shipping tracker misses, and it shows whether any fade meets both.
#include <iosfwd>
#include <string>
#include <vector>

#include "proposed_config.hpp"
#include "tracking_evaluation.hpp"

namespace ff::bench {

struct FadeLevels {
  float rest_sigmas = 0.0f;    // at or below: the direction faded to nothing
  float moving_sigmas = 0.0f;  // at or above: the direction at full length
};

// The grid: every pair with moving_sigmas >= rest_sigmas + 1 (a narrower band
// is a step, and chatters at every noise peak).
constexpr float kFrontierRestSigmas[] = {0.5f, 1.0f, 1.5f, 2.0f, 2.5f, 3.0f, 4.0f};
constexpr float kFrontierMovingSigmas[] = {2.0f, 3.0f, 4.0f, 5.0f, 6.0f, 7.0f, 9.0f};
constexpr float kFrontierMinBandSigmas = 1.0f;
std::vector<FadeLevels> frontier_grid();

struct FrontierPoint {
  FadeLevels fade;
  double heightmap_ratio = 0.0;  // heightmap error while moving, over the thesis pipeline's
  double chatter = 0.0;          // RMS of A - 0.5 at rest
};

struct FrontierRow {
  std::string trace_class;
  double heightmap_goal = 0.0;    // the class's goal for heightmap_ratio
  double chatter_goal = 0.0;
  FadeLevels shipping;            // recommended()'s fade
  std::vector<FrontierPoint> points;  // in frontier_grid() order
};

// The class's cases through recommended(sensor) with `base`'s constants and
// each fade of the grid (the shipping fade included), against the thesis
// pipeline's heightmap error on the same cases.
FrontierRow fade_frontier(const std::string& trace_class, const std::vector<PreparedCase>& cases,
                          const SensorProfile& sensor, const ProposedConstants& base, const EvalOptions& options);

// The points no other point beats on both (a heightmap ratio and a chatter
// each no higher, one of them lower), by rising chatter.
std::vector<FrontierPoint> pareto_front(const std::vector<FrontierPoint>& points);
// The lowest heightmap ratio among the points with chatter <= chatter_bound;
// nullptr where none is that quiet.
const FrontierPoint* best_within(const std::vector<FrontierPoint>& points, double chatter_bound);
// The point of the shipping fade; nullptr if the grid does not hold it.
const FrontierPoint* shipping_point(const FrontierRow& row);

// Per class: the shipping fade, the best heightmap at the chatter goal, the
// best at any chatter, and whether any fade meets both goals.
void write_frontier_report(std::ostream& out, const std::vector<FrontierRow>& rows, double duration_s);
// Every point, one row each, with its Pareto membership, for
// tools/track_bench/plot_frontier.py. No metadata: the caller writes it first.
void write_frontier_csv(std::ostream& out, const std::vector<FrontierRow>& rows);

}  // namespace ff::bench
