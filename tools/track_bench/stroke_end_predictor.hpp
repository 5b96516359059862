#pragma once
// Where a stroke will end, from its reports so far (issue 14). A finger's
// stroke from one standstill to the next is close to a minimum-jerk movement
// (Flash & Hogan 1985; the generator's strokes are exactly that): its
// position runs from `from` to `from + travel` as s(tau) = 10 tau^3 -
// 15 tau^4 + 6 tau^5, tau = (t - start) / duration. Fitted to the reports
// since the last predicted end, once the stroke has slowed past its peak the
// fit says when it stops, before the reports can show it: what the heading
// model of heading_bound.hpp needs to start each stroke afresh. Host only,
// double precision, O(reports of the stroke) per report: a benchmark, not a
// tracker (a tracker would keep a bank of durations with running sums).
#include <cmath>
#include <vector>

namespace ff::bench {

struct MinJerkFit {
  double start_s = 0.0, duration_s = 0.0;
  double from_x = 0.0, from_y = 0.0;      // px, where the stroke starts
  double travel_x = 0.0, travel_y = 0.0;  // px, its displacement
  double cost = INFINITY;                 // sum of squared residuals, px^2 (infinite: no fit)
  double travel_variance = INFINITY;      // of each component of travel, px^2, from the residuals

  bool valid() const { return std::isfinite(cost); }
  double end_s() const { return start_s + duration_s; }
  double distance_px() const { return std::hypot(travel_x, travel_y); }
};

struct TimedReport {
  double t_s = 0.0, x = 0.0, y = 0.0;
};

// The least-squares stroke at a given start and duration: from and travel in
// closed form (linear in them). Invalid if the reports cannot tell them apart
// (all before or all after the stroke).
MinJerkFit fit_min_jerk_at(const std::vector<TimedReport>& reports, double start_s, double duration_s);

// The least-squares stroke: start and duration refined by a pattern search
// from `guess` if valid, else from the best of a grid (durations 60 ms-3 s,
// starts up to 150 ms before `first_motion_s`).
MinJerkFit fit_min_jerk(const std::vector<TimedReport>& reports, const MinJerkFit& guess, double first_motion_s);

class StrokeEndPredictor {
 public:
  struct Options {
    double min_distance_px = 10.0;  // a shorter fitted stroke is noise or tremor: no end from it
    double min_motion_px = 4.0;     // fit once the reports have moved this far from the stroke's first
    // The fitted travel must stand out of its own uncertainty by this many
    // standard errors: the best of many timings fitted to a resting finger's
    // noise can travel 10 px, never 8 sigma.
    double min_sigmas = 8.0;
  };
  StrokeEndPredictor() = default;
  explicit StrokeEndPredictor(const Options& options) : options_(options) {}

  // Nothing known (a touch-down).
  void restart();
  // The report scanned at t_s. True when the fit says the stroke has ended
  // by t_s: a new stroke begins with this report.
  bool report(double t_s, double x, double y);
  const MinJerkFit& fit() const { return fit_; }

 private:
  Options options_;
  std::vector<TimedReport> stroke_;  // the reports since the last end
  double first_motion_s_ = NAN;      // its first report min_motion_px from the first; NaN: none yet
  MinJerkFit fit_;
};

}  // namespace ff::bench
