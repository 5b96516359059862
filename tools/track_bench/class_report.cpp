#include "class_report.hpp"

#include "bench_report.hpp"
#include "rest_chatter.hpp"

#include <cmath>
#include <cstdio>
#include <ostream>

namespace ff::bench {

namespace {

// "0.45x"; "-" where the baseline is 0.
std::string ratio(double value, double baseline) {
  return baseline > 0.0 ? fixed(value / baseline, 2) + "×" : "-";
}

}  // namespace

double class_heightmap_goal(const std::string& trace_class) {
  return trace_class == "white-200hz" ? kClassMaxHeightmapRatioWhite : kClassMaxHeightmapRatio;
}

std::vector<TrackCase> class_cases(const tracegen::TraceClass& trace_class, double duration_s) {
  std::vector<TrackCase> cases = standard_cases(tracegen::kNoiseLowPx, duration_s);
  for (TrackCase& c : cases) {
    trace_class.apply(c.options);
    c.name = std::string(trace_class.name) + " " + c.name;
  }
  return cases;
}

double slow_share(const std::vector<PreparedCase>& cases, double moving_speed_px_s) {
  size_t moving = 0, slow = 0;
  for (const PreparedCase& c : cases) {
    for (const TickTruth& t : c.ticks) {
      if (!judged_moving(t.state, moving_speed_px_s)) continue;
      const double speed = std::hypot(t.state.velocity.x, t.state.velocity.y);
      ++moving;
      if (speed >= 20.0 && speed <= 70.0) ++slow;
    }
  }
  return moving > 0 ? static_cast<double>(slow) / static_cast<double>(moving) : 0.0;
}

void write_class_report(std::ostream& out, const std::vector<ClassRow>& rows, double duration_s,
                        double moving_speed_px_s) {
  out << "| class | tracker | lag ms | pos RMSE px | dir err mean ° | HM amp RMS | HM vs thesis | FM amp RMS "
         "| FM vs thesis | HM at rest RMS | rest vs thesis | slow ticks |\n";
  out << "|---|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n";
  const ClassRow* baseline = nullptr;
  for (const ClassRow& r : rows) {
    if (baseline == nullptr || baseline->trace_class != r.trace_class) baseline = &r;
    const Metrics& m = r.metrics;
    const Metrics& b = baseline->metrics;
    out << "| " << r.trace_class << " | " << r.tracker << " | " << fixed(m.lag_ms, 2) << " | "
        << fixed(m.position_rmse_px, 2) << " | " << fixed(m.direction_mean_deg, 1) << " | " << fixed(m.heightmap_rms, 3)
        << " | " << ratio(m.heightmap_rms, b.heightmap_rms) << " | " << fixed(m.frictionmap_rms, 3) << " | "
        << ratio(m.frictionmap_rms, b.frictionmap_rms) << " | " << fixed(m.heightmap_rest_rms, 3) << " | "
        << ratio(m.heightmap_rest_rms, b.heightmap_rest_rms) << " | " << fixed(100.0 * r.slow_share, 0) << " % |\n";
  }
  out << "\nEach class: the 6 generated traces of " << fixed(duration_s, 0)
      << " s of the standard set (same seeds, strategies and targets) with the class's finger and sensor; "
         "metrics while the finger moves above "
      << fixed(moving_speed_px_s * 0.2, 0)
      << " mm/s, against its voluntary motion (tremor excluded) and the ideal renderer fed the true position "
         "and the voluntary direction; \"vs thesis\": the ratio to the thesis pipeline on the same class; "
         "\"slow ticks\": share of those moving ticks at 20-70 px/s (4-14 mm/s). Generated traces, not a sensor.\n";
}

void write_rest_report(std::ostream& out, const std::vector<ClassRow>& rows) {
  out << "| class | tracker | HM at rest RMS | of its squares in the first " << fixed(kStopTransientUs * 1e-3, 0)
      << " ms of each rest | after them, RMS | stops | back within " << fixed(kSettledBand, 2)
      << " of 0.5, median ms | max ms | never |\n";
  out << "|---|---|--:|--:|--:|--:|--:|--:|--:|\n";
  for (const ClassRow& r : rows) {
    const Metrics& m = r.metrics;
    const bool any_settled = m.stops > m.unsettled_stops;
    out << "| " << r.trace_class << " | " << r.tracker << " | " << fixed(m.heightmap_rest_rms, 3) << " | "
        << fixed(100.0 * m.rest_transient_share, 0) << " % | " << fixed(m.heightmap_steady_rest_rms, 3) << " | " << m.stops
        << " | " << (any_settled ? fixed(m.stop_settle_median_ms, 1) : "-") << " | "
        << (any_settled ? fixed(m.stop_settle_max_ms, 1) : "-") << " | " << m.unsettled_stops << " |\n";
  }
  out << "\nThe chatter at rest, split at each stop (the generator's rests, 0.6-2 s after a stroke): the first "
      << fixed(kStopTransientUs * 1e-3, 0)
      << " ms of each rest, while the direction filter still reads the stroke's deceleration, and the steady rest "
         "after them. \"Back within\": from the rest's first tick until the amplitude stays within "
      << fixed(kSettledBand, 2) << " of 0.5 for " << fixed(kSettledHoldUs * 1e-3, 0)
      << " ms; \"never\": rests that ended before that (a tracker without a fade).\n";
}

void write_class_csv(std::ostream& out, const std::vector<ClassRow>& rows, const std::vector<StartFloorRow>& floors,
                     const std::vector<LookaheadRow>& lookahead) {
  out << "class,tracker,lag_ms,position_rmse_px,direction_mean_deg,heightmap_rms,heightmap_vs_thesis,frictionmap_rms,"
         "frictionmap_vs_thesis,rest_rms,rest_vs_thesis,rest_first_share,rest_steady_rms,stops,settle_median_ms,"
         "settle_max_ms,unsettled_stops,slow_share";
  for (double d : kStartFloorDistancesPx) out << ",floor_" << fixed(d, 1) << "px_rms";
  out << ",unfaded_heightmap_rms";
  for (double ms : kLookaheadsMs) out << ",lookahead_" << (std::isinf(ms) ? std::string("whole") : fixed(ms, 0) + "ms") << "_rms";
  out << ",anchored_0ms_rms,heading_bound_rms,direction_bound_rms,predicted_ends_rms,predicted_ends_rest_rms,"
         "standstills,predicted_ends_found,predicted_ends_delay_ms,predicted_ends_other,tracker_ends_rms,"
         "tracker_ends_found,tracker_ends_delay_ms,tracker_ends_other\n";
  auto number = [](double v) { return fixed(v, 6); };
  auto over = [&](double value, double baseline) { return baseline > 0.0 ? number(value / baseline) : std::string(); };
  const ClassRow* baseline = nullptr;
  for (const ClassRow& r : rows) {
    if (baseline == nullptr || baseline->trace_class != r.trace_class) baseline = &r;
    const Metrics& m = r.metrics;
    const Metrics& b = baseline->metrics;
    out << r.trace_class << "," << r.tracker << "," << number(m.lag_ms) << "," << number(m.position_rmse_px) << ","
        << number(m.direction_mean_deg) << "," << number(m.heightmap_rms) << "," << over(m.heightmap_rms, b.heightmap_rms)
        << "," << number(m.frictionmap_rms) << "," << over(m.frictionmap_rms, b.frictionmap_rms) << ","
        << number(m.heightmap_rest_rms) << "," << over(m.heightmap_rest_rms, b.heightmap_rest_rms) << ","
        << number(m.rest_transient_share) << "," << number(m.heightmap_steady_rest_rms) << "," << m.stops << ","
        << number(m.stop_settle_median_ms) << "," << number(m.stop_settle_max_ms) << "," << m.unsettled_stops << ","
        << number(r.slow_share);
    const StartFloorRow* floor = nullptr;
    for (const StartFloorRow& f : floors)
      if (f.trace_class == r.trace_class) floor = &f;
    for (size_t i = 0; i < std::size(kStartFloorDistancesPx); ++i)
      out << "," << (floor != nullptr ? number(floor->floor_rms[i]) : std::string());
    out << "," << (m.heightmap_unfaded_rms > 0.0 ? number(m.heightmap_unfaded_rms) : std::string());
    const LookaheadRow* bound = nullptr;
    for (const LookaheadRow& l : lookahead)
      if (l.trace_class == r.trace_class) bound = &l;
    for (size_t i = 0; i < std::size(kLookaheadsMs); ++i)
      out << "," << (bound != nullptr ? number(bound->best_rms[i]) : std::string());
    out << "," << (bound != nullptr ? number(bound->anchored_rms) : std::string());
    for (double v : {bound != nullptr ? bound->heading_bound_rms : double{NAN},
                     bound != nullptr ? bound->direction_bound_rms : double{NAN},
                     bound != nullptr ? bound->predicted_ends.heightmap_rms : double{NAN},
                     bound != nullptr ? bound->predicted_ends.rest_rms : double{NAN}})
      out << "," << (!std::isnan(v) ? number(v) : std::string());
    if (bound != nullptr) {
      const StrokeEndStats& p = bound->predicted_ends.ends;
      const StrokeEndStats& t = bound->tracker_ends.ends;
      out << "," << p.standstills << "," << p.found << "," << number(p.median_delay_ms) << "," << p.other_ends << ","
          << number(bound->tracker_ends.heightmap_rms) << "," << t.found << "," << number(t.median_delay_ms) << ","
          << t.other_ends;
    } else {
      out << ",,,,,,,,";
    }
    out << "\n";
  }
}

double start_floor_rms(const std::vector<PreparedCase>& cases, double moving_speed_px_s, double distance_px) {
  double sum = 0.0;
  size_t moving = 0;
  for (const PreparedCase& c : cases) {
    bool stood = false;  // the finger has stood still since the trace began
    tracegen::Point from;
    for (const TickTruth& t : c.ticks) {
      if (!t.state.touching) {
        stood = false;  // a new touch is a new start: from where it lands
        continue;
      }
      if (standing_still(t.state) || !stood) {
        from = t.state.position;
        stood = true;
      }
      if (!judged_moving(t.state, moving_speed_px_s)) continue;
      ++moving;
      const double moved = std::hypot(t.state.position.x - from.x, t.state.position.y - from.y);
      if (moved < distance_px) {
        const double e = static_cast<double>(t.heightmap_ideal) - 0.5;
        sum += e * e;
      }
    }
  }
  return moving > 0 ? std::sqrt(sum / static_cast<double>(moving)) : 0.0;
}

void write_start_floor(std::ostream& out, const std::vector<StartFloorRow>& rows) {
  out << "| class | thesis HM amp RMS |";
  for (double d : kStartFloorDistancesPx) out << " floor, direction from " << fixed(d, 1) << " px |";
  out << " recommended(profile) | the same, never faded while moving |\n|---|--:|";
  for (size_t i = 0; i < std::size(kStartFloorDistancesPx); ++i) out << "--:|";
  out << "--:|--:|\n";
  auto cell = [&out](double value, double thesis) { out << " " << fixed(value, 3) << " (" << ratio(value, thesis) << ") |"; };
  for (const StartFloorRow& r : rows) {
    out << "| " << r.trace_class << " | " << fixed(r.thesis_heightmap_rms, 3) << " |";
    for (double f : r.floor_rms) cell(f, r.thesis_heightmap_rms);
    cell(r.tracker_heightmap_rms, r.thesis_heightmap_rms);
    cell(r.unfaded_heightmap_rms, r.thesis_heightmap_rms);
    out << "\n";
  }
  out << "\nWhere the heightmap error comes from. Floors: the error of a tracker that knows the finger's position and "
         "direction exactly, except during the first 0.5, 1 or 2 px of motion after every standstill (below "
      << fixed(kStandstillPxS, 0)
      << " px/s), where it renders 0.5: what no tracker avoids if it cannot tell the direction before the finger has "
         "moved that far (1 px = 1 sigma of white-200hz's report noise). Last two columns: the shipping tracker, and "
         "the same with its direction at full length whenever the finger moves (a perfect motion oracle in place of "
         "the direction confidence): what remains there is its direction's and position's error, the difference is "
         "the confidence's. In parentheses: the ratio to the thesis pipeline's error, to hold against the goals.\n";
}

}  // namespace ff::bench
