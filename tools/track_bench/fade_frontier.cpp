#include "fade_frontier.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <ostream>

#include "class_report.hpp"

namespace ff::bench {

namespace {

std::string fade_name(FadeLevels f) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.1f / %.1f σ", static_cast<double>(f.rest_sigmas),
                static_cast<double>(f.moving_sigmas));
  return buf;
}

std::string point_cell(const FrontierPoint* p, bool with_chatter) {
  if (p == nullptr) return "none";
  char buf[96];
  if (with_chatter)
    std::snprintf(buf, sizeof buf, "%.2f× at %.3f (%s)", p->heightmap_ratio, p->chatter, fade_name(p->fade).c_str());
  else
    std::snprintf(buf, sizeof buf, "%.2f× (%s)", p->heightmap_ratio, fade_name(p->fade).c_str());
  return buf;
}

bool same(FadeLevels a, FadeLevels b) { return a.rest_sigmas == b.rest_sigmas && a.moving_sigmas == b.moving_sigmas; }

bool dominates(const FrontierPoint& a, const FrontierPoint& b) {
  return a.heightmap_ratio <= b.heightmap_ratio && a.chatter <= b.chatter &&
         (a.heightmap_ratio < b.heightmap_ratio || a.chatter < b.chatter);
}

}  // namespace

std::vector<FadeLevels> frontier_grid() {
  std::vector<FadeLevels> grid;
  for (float rest : kFrontierRestSigmas)
    for (float moving : kFrontierMovingSigmas)
      if (moving >= rest + kFrontierMinBandSigmas) grid.push_back({rest, moving});
  return grid;
}

FrontierRow fade_frontier(const std::string& trace_class, const std::vector<PreparedCase>& cases,
                          const SensorProfile& sensor, const ProposedConstants& base, const EvalOptions& options) {
  EvalOptions fast = options;
  fast.lag = false;  // the fade moves neither the position nor its lag
  fast.cost = false;
  fast.unfaded = false;
  const double thesis = evaluate(TrackerConfig::thesis(), cases, fast).heightmap_rms;
  const TrackerConfig shipping = TrackerConfig::recommended(sensor);
  FrontierRow row{trace_class, class_heightmap_goal(trace_class), kClassRestBound,
                  {shipping.rest_sigmas, shipping.moving_sigmas}, {}};
  for (FadeLevels fade : frontier_grid()) {
    ProposedConstants constants = base;
    constants.rest_sigmas = fade.rest_sigmas;
    constants.moving_sigmas = fade.moving_sigmas;
    const Metrics m = evaluate([&](const PreparedCase& c) { return proposed_tracker(constants, nominal_profile(c)); },
                               cases, fast);
    row.points.push_back({fade, thesis > 0.0 ? m.heightmap_rms / thesis : 0.0, m.heightmap_rest_rms});
  }
  return row;
}

std::vector<FrontierPoint> pareto_front(const std::vector<FrontierPoint>& points) {
  std::vector<FrontierPoint> front;
  for (const FrontierPoint& p : points) {
    bool beaten = false;
    for (const FrontierPoint& q : points) beaten = beaten || dominates(q, p);
    if (!beaten) front.push_back(p);
  }
  std::sort(front.begin(), front.end(), [](const FrontierPoint& a, const FrontierPoint& b) {
    return a.chatter < b.chatter || (a.chatter == b.chatter && a.heightmap_ratio < b.heightmap_ratio);
  });
  return front;
}

const FrontierPoint* best_within(const std::vector<FrontierPoint>& points, double chatter_bound) {
  const FrontierPoint* best = nullptr;
  for (const FrontierPoint& p : points)
    if (p.chatter <= chatter_bound && (best == nullptr || p.heightmap_ratio < best->heightmap_ratio)) best = &p;
  return best;
}

const FrontierPoint* shipping_point(const FrontierRow& row) {
  for (const FrontierPoint& p : row.points)
    if (same(p.fade, row.shipping)) return &p;
  return nullptr;
}

void write_frontier_report(std::ostream& out, const std::vector<FrontierRow>& rows, double duration_s) {
  out << "| class | shipping fade | best at chatter ≤ goal | best at any chatter | heightmap goal | "
         "both goals by some fade |\n";
  out << "|---|--:|--:|--:|--:|---|\n";
  for (const FrontierRow& r : rows) {
    const FrontierPoint* quiet = best_within(r.points, r.chatter_goal);
    const FrontierPoint* any = best_within(r.points, INFINITY);
    char goal[32];
    std::snprintf(goal, sizeof goal, "%.2f×", r.heightmap_goal);
    const bool met = quiet != nullptr && quiet->heightmap_ratio <= r.heightmap_goal;
    out << "| " << r.trace_class << " | " << point_cell(shipping_point(r), true) << " | " << point_cell(quiet, false)
        << " | " << point_cell(any, true) << " | " << goal << " | " << (met ? "yes" : "no") << " |\n";
  }
  char grid[160];
  std::snprintf(grid, sizeof grid, "faded to nothing at or below %g-%g, at full length from %g-%g sigmas of the "
                "velocity's noise, %zu pairs",
                static_cast<double>(kFrontierRestSigmas[0]), static_cast<double>(std::end(kFrontierRestSigmas)[-1]),
                static_cast<double>(kFrontierMovingSigmas[0]), static_cast<double>(std::end(kFrontierMovingSigmas)[-1]),
                frontier_grid().size());
  out << "\nThe direction confidence's trade, per class: recommended(profile) with only its fade's two levels "
         "changed ("
      << grid << "), on the 6 generated traces of " << duration_s
      << " s of each class. Heightmap: the amplitude error while the finger moves, over the thesis pipeline's; "
         "chatter: the RMS of A - 0.5 at rest (goal "
      << kClassRestBound
      << "). The fade moves neither the position, its lag nor the frictionmap, so this is the whole trade between "
         "the two goals the shipping tracker misses. Generated traces, not a sensor.\n";
}

void write_frontier_csv(std::ostream& out, const std::vector<FrontierRow>& rows) {
  out << "class,rest_sigmas,moving_sigmas,heightmap_vs_thesis,rest_rms,pareto,shipping,heightmap_goal,rest_goal\n";
  for (const FrontierRow& r : rows) {
    const std::vector<FrontierPoint> front = pareto_front(r.points);
    for (const FrontierPoint& p : r.points) {
      bool on_front = false;
      for (const FrontierPoint& f : front) on_front = on_front || same(f.fade, p.fade);
      char line[256];
      std::snprintf(line, sizeof line, "%s,%.2f,%.2f,%.9g,%.9g,%d,%d,%.2f,%.3f\n", r.trace_class.c_str(),
                    static_cast<double>(p.fade.rest_sigmas), static_cast<double>(p.fade.moving_sigmas),
                    p.heightmap_ratio, p.chatter, on_front ? 1 : 0, same(p.fade, r.shipping) ? 1 : 0, r.heightmap_goal,
                    r.chatter_goal);
      out << line;
    }
  }
}

}  // namespace ff::bench
