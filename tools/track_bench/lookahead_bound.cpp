#include "lookahead_bound.hpp"

#include <algorithm>
#include <cstdio>
#include <ostream>
#include <utility>

#include "frictionfield/core/stroke_end_predictor.hpp"
#include "heading_bound.hpp"
#include "stroke_end_predictor.hpp"

namespace ff::bench {

FixedLagAxis::FixedLagAxis(AxisPass pass, double lookahead_s, double latency_s)
    : pass_(std::move(pass)), lookahead_s_(lookahead_s), latency_s_(latency_s) {
  if (std::isinf(lookahead_s_)) smooth_pass(pass_, smoothed_p_, smoothed_v_);
}

AxisState FixedLagAxis::at(double t_s) {
  const std::vector<double>& t = pass_.t;
  const auto last_at_or_before = [&t](double time) {
    const auto it = std::upper_bound(t.begin(), t.end(), time);
    return it == t.begin() ? size_t{0} : static_cast<size_t>(it - t.begin()) - 1;
  };
  size_t k = last_at_or_before(t_s);
  AxisState s;
  if (std::isinf(lookahead_s_)) {
    s = {smoothed_p_[k], smoothed_v_[k]};
  } else {
    // Seen by then: stamped by t_s + lookahead, so scanned latency earlier
    // (a later scan is not known yet, however early it was dated).
    const size_t m = last_at_or_before(t_s + lookahead_s_ - latency_s_);
    k = std::min(k, m);
    if (k != cached_k_ || m != cached_m_) {
      double p = pass_.filtered_p[m], v = pass_.filtered_v[m];
      for (size_t j = m; j-- > k;) smooth_step(pass_, j, p, v);
      cached_ = {p, v};
      cached_k_ = k;
      cached_m_ = m;
    }
    s = cached_;
  }
  s.p += s.v * (t_s - t[k]);
  return s;
}

double lookahead_heightmap_rms(const std::vector<PreparedCase>& cases, double moving_speed_px_s,
                               const SmootherOptions& smoother, double latency_s, double lookahead_s,
                               BoundModel model) {
  const bool anchored = model == BoundModel::AnchoredAtRest;
  if (anchored && lookahead_s != 0.0) return NAN;  // no smoother over a singular covariance
  double sum = 0.0;
  size_t moving = 0;
  for (const PreparedCase& c : cases) {
    std::vector<host::TraceRow> rows;
    rows.reserve(c.trace.samples.size());
    for (const tracegen::TraceSample& s : c.trace.samples)
      rows.push_back({s.t_us, static_cast<float>(s.x), static_cast<float>(s.y), s.touch});
    struct Run {
      double first = 0.0, last = 0.0;
      FixedLagAxis x, y;
    };
    std::vector<Run> runs;
    for (ReportRun& run : touch_runs(rows, c.trace.start_us, smoother.max_gap_s)) {
      for (double& t : run.t) t -= latency_s;  // when the sensor scanned
      std::vector<bool> standstill;
      if (anchored) {
        for (double t : run.t) {
          const double scanned_us = std::max(0.0, t * 1e6);
          standstill.push_back(
              standing_still(c.trace.truth_at(c.trace.start_us + static_cast<uint64_t>(std::llround(scanned_us)))));
        }
      }
      const std::vector<bool>* oracle = anchored ? &standstill : nullptr;
      runs.push_back({run.t.front() + latency_s, run.t.back(),
                      FixedLagAxis(filter_axis(run.t, run.x, smoother, oracle), lookahead_s, latency_s),
                      FixedLagAxis(filter_axis(run.t, run.y, smoother, oracle), lookahead_s, latency_s)});
    }
    size_t r = 0;
    for (const TickTruth& tick : c.ticks) {
      const double t_s = static_cast<double>(tick.t_us - c.trace.start_us) * 1e-6;
      while (r < runs.size() && t_s > runs[r].last + smoother.max_gap_s) ++r;
      if (r == runs.size()) break;
      if (t_s < runs[r].first || !judged_moving(tick.state, moving_speed_px_s)) continue;  // untracked, or not moving
      const AxisState x = runs[r].x.at(t_s), y = runs[r].y.at(t_s);
      const double v = std::hypot(x.v, y.v);
      const Vec2 direction = v > 0.0 ? Vec2{static_cast<float>(x.v / v), static_cast<float>(y.v / v)} : Vec2{};
      const float hm = c.heightmap->amplitude(to_vec(tick.state.position), direction);
      const double e = static_cast<double>(hm - tick.heightmap_ideal);
      sum += e * e;
      ++moving;
    }
  }
  return moving > 0 ? std::sqrt(sum / static_cast<double>(moving)) : 0.0;
}

LookaheadRow lookahead_row(const std::string& trace_class, const std::vector<PreparedCase>& cases,
                           double moving_speed_px_s, double white_noise_px, double correlated_noise_px,
                           double latency_s) {
  LookaheadRow row;
  row.trace_class = trace_class;
  SmootherOptions smoother;
  smoother.measurement_noise_px = std::hypot(white_noise_px, correlated_noise_px);
  // The grid's best acceleration noise for one lookahead and model.
  const auto best = [&](double lookahead_s, BoundModel model, double& best_rms, double& best_q) {
    best_rms = INFINITY;
    for (double q : kLookaheadAccelNoise) {
      smoother.accel_noise_px2_s3 = q;
      const double rms = lookahead_heightmap_rms(cases, moving_speed_px_s, smoother, latency_s, lookahead_s, model);
      if (rms < best_rms) {
        best_rms = rms;
        best_q = q;
      }
    }
  };
  for (size_t i = 0; i < std::size(kLookaheadsMs); ++i)
    best(kLookaheadsMs[i] * 1e-3, BoundModel::ConstantVelocity, row.best_rms[i], row.best_accel_noise[i]);
  best(0.0, BoundModel::AnchoredAtRest, row.anchored_rms, row.anchored_accel_noise);
  return row;
}

void write_lookahead_report(std::ostream& out, const std::vector<LookaheadRow>& rows) {
  char cell[96];
  out << "| class | thesis HM amp RMS | recommended(profile) |";
  for (double ms : kLookaheadsMs) {
    if (std::isinf(ms)) {
      out << " whole stroke (RTS) |";
    } else {
      std::snprintf(cell, sizeof cell, " %.0f ms ahead |", ms);
      out << (ms == 0.0 ? std::string(" causal, 0 ms ahead |") : std::string(cell));
    }
  }
  out << " causal, anchored at rest | told when each stroke starts | told all but each stroke's direction |";
  out << "\n|---|--:|--:|";
  for (size_t i = 0; i <= std::size(kLookaheadsMs) + 2; ++i) out << "--:|";
  out << "\n";
  for (const LookaheadRow& r : rows) {
    const double base = r.thesis_heightmap_rms;
    auto ratio = [base](double v) { return base > 0.0 ? v / base : 0.0; };
    std::snprintf(cell, sizeof cell, "| %s | %.3f | %.3f (%.2f×) |", r.trace_class.c_str(), base, r.tracker_heightmap_rms,
                  ratio(r.tracker_heightmap_rms));
    out << cell;
    for (size_t i = 0; i < std::size(kLookaheadsMs); ++i) {
      std::snprintf(cell, sizeof cell, " %.3f (%.2f×, q %.0e) |", r.best_rms[i], ratio(r.best_rms[i]), r.best_accel_noise[i]);
      out << cell;
    }
    std::snprintf(cell, sizeof cell, " %.3f (%.2f×, q %.0e) |", r.anchored_rms, ratio(r.anchored_rms), r.anchored_accel_noise);
    out << cell;
    for (double v : {r.heading_bound_rms, r.direction_bound_rms}) {
      if (std::isnan(v)) {
        out << " - |";
      } else {
        std::snprintf(cell, sizeof cell, " %.3f (%.2f×) |", v, ratio(v));
        out << cell;
      }
    }
    out << "\n";
  }
  out << "\nWhat knowing the future would buy: a constant-velocity Kalman smoother that at each tick has seen "
         "every report up to 0, 10, 30 or 100 ms after it, or the whole stroke, its direction at full length "
         "whenever the finger moves (a perfect motion oracle) and its white-acceleration density q (px²/s³) the "
         "best of 3e1-1e6 for each class and lookahead, told the profile's latency and its white and "
         "correlated noise together as one white noise (no wander state) (`tools/track_bench/lookahead_bound.*`). Not a tracker (it sees the future, and picks q against the "
         "truth): the causal column is a constant-velocity filter's best with a perfect motion detector, the "
         "others what waiting for the future would remove, at the cost of that much lag. Last column: the causal "
         "filter also told when the finger stands still (below " << kStandstillPxS << " px/s, by the truth): its "
         "velocity held at 0 and its position averaged there, its velocity unknown again at each start (1 sigma "
         << kStartSpeedSigmaPxS << " px/s): the best of a tracker with a resting mode and a perfect start "
         "detector, starting from a settled anchor. Next: an observer told only when the finger stands still (by the "
         "truth), which learns each stroke's heading from the reports, a heading that turns per px travelled "
         "rather than per second (white noise of " << HeadingBoundOptions{}.turn_variance_per_px << " per px), the "
         "distance from a constant-velocity filter's speed (sqrt q "
         << HeadingBoundOptions{}.speed_accel_noise_px_s2 << " px/s²), the heading unknown again at each standstill, "
         "rendering the amplitude's posterior mean at the true position (`tools/track_bench/heading_bound.*`): what "
         "a tracker that found every start and stop would be left with. The very last: an observer told everything but where each "
         "stroke goes (the stroke's true path up to a rotation about where the finger last stood still, when it "
         "starts, the tremor, the drift, the latency, the noise's model; the rotation uniform a priori), rendering "
         "the amplitude's posterior mean (`tools/track_bench/direction_bound.*`): the least error with that knowledge "
         "on average over strokes turned at random, a floor for trackers that assume nothing about where a stroke "
         "goes.\n";
}

void write_predicted_ends_report(std::ostream& out, const std::vector<LookaheadRow>& rows) {
  char cell[160];
  out << "| class | thesis HM amp RMS | recommended(profile) | heading model, told the standstills | "
         "told nothing, strokes ended where predicted | its HM at rest RMS | standstills | predicted within "
      << kPredictedEndToleranceMs << " ms | median delay ms | other predicted ends | the tracker's predictor: within "
      << kPredictedEndToleranceMs << " ms | median delay ms | other ends |\n";
  out << "|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n";
  for (const LookaheadRow& r : rows) {
    const double base = r.thesis_heightmap_rms;
    auto ratio = [base](double v) { return base > 0.0 ? v / base : 0.0; };
    const HeadingBoundResult& p = r.predicted_ends;
    std::snprintf(cell, sizeof cell, "| %s | %.3f | %.3f (%.2f×) | %.3f (%.2f×) | %.3f (%.2f×) | %.3f |", r.trace_class.c_str(),
                  base, r.tracker_heightmap_rms, ratio(r.tracker_heightmap_rms), r.heading_bound_rms,
                  ratio(r.heading_bound_rms), p.heightmap_rms, ratio(p.heightmap_rms), p.rest_rms);
    out << cell;
    const StrokeEndStats& t = r.tracker_ends.ends;
    std::snprintf(cell, sizeof cell, " %zu | %zu | %.0f | %zu | %zu | %.0f | %zu |\n", p.ends.standstills,
                  p.ends.found, p.ends.median_delay_ms, p.ends.other_ends, t.found, t.median_delay_ms, t.other_ends);
    out << cell;
  }
  const HeadingBoundOptions d;
  out << "\nWhere strokes end, predicted: the heading model of the table above told nothing of the standstills; "
         "instead each stroke starts afresh where a minimum-jerk profile fitted to the reports since the last one "
         "says it has ended (`tools/track_bench/stroke_end_predictor.*`: the stroke's start, duration and "
         "displacement by least squares, ended once it is at least "
      << StrokeEndPredictor::Options{}.min_distance_px << " px and " << StrokeEndPredictor::Options{}.min_sigmas
      << " standard errors long), and the heading forgotten at " << d.forget_variance_per_s
      << " per s while the speed reads below " << d.forget_below_px_s
      << " px/s (for strokes too short or slow to fit). It never decides that the finger rests, so it renders "
         "the heading it learnt from the noise there: its chatter at rest is not a tracker's. Standstills: the "
         "truth's (below "
      << kStandstillPxS
      << " px/s; not those a touch begins with), found when a predicted end falls within "
      << kPredictedEndToleranceMs << " ms of one (the delay "
         "from its first report); other ends: predicted near none. Generated traces, whose strokes are exactly "
         "minimum-jerk: a finger's are only close to it. The tracker's predictor (`core/stroke_end_predictor.*`, "
         "what the shipping tracker widens its direction filter by at each end) fits the same profile in float "
         "on at most "
      << ff::StrokeEndPredictor::kCapacity << " decimated reports, one step of a compass search on the start or "
         "the end per "
      << ff::StrokeEndConfig{}.refine_interval_us / 1000.0 << " ms of reports instead of the full search.\n";
}

}  // namespace ff::bench
