#pragma once
// Where a stroke ends, before the reports can show it. A stroke from one
// standstill to the next is close to a minimum-jerk movement (min_jerk.hpp):
// from + travel * s((t - start) / duration). Fitted to the stroke's reports,
// once the finger has slowed past its peak speed the fit says when it stops.
// The tracker widens its direction filter there, so that the rendered
// direction settles at rest at once instead of chattering while the filter
// unlearns the stroke's speed (docs/tracking.md#predicted-stroke-ends).
//
// Bounded and allocation-free: the stroke's reports are kept decimated to
// kCapacity points, and refine() takes one step of a compass search on the
// start or the end (from and travel in closed form at each): three fits of
// O(kCapacity).
#include <cstdint>

#include "frictionfield/bus/clock.hpp"
#include "frictionfield/core/geometry.hpp"

namespace ff {

struct StrokeEndConfig {
  float min_travel_px = 10.0f;  // a shorter fitted stroke is noise or tremor: no end from it
  // The fitted travel must stand out of its own uncertainty by this many
  // standard errors: the best of many timings fitted to a resting finger's
  // noise can travel 10 px, never 8 sigma.
  float min_sigmas = 8.0f;
  float motion_px = 4.0f;  // a stroke begins once a report is this far from where the finger rested
  uint32_t refine_interval_us = 4000;  // at most one refinement per this much report time
  // Before the fitted end: from where the fitted speed falls below this, the
  // direction fades out with it (stopping_gain), so that a stop is quiet on
  // time rather than a report or two after it. 0: not faded.
  float quiet_speed_px_s = 10.0f;
};

class StrokeEndPredictor {
 public:
  static constexpr int kCapacity = 32;      // points of a stroke kept (decimated)
  static constexpr int kRestPoints = 8;     // of the rest before it
  static constexpr uint32_t kRestSpacingUs = 20000;  // between those
  static constexpr uint32_t kSpacingUs = 5000;  // between kept points, doubled whenever they fill up
  static constexpr float kMaxStrokeS = 4.0f;     // longer without an end: given up, begun again
  static constexpr float kGiveUpS = 0.1f;        // this long past a fitted end too small to be a stroke: given up

  explicit StrokeEndPredictor(const StrokeEndConfig& config = {}) { configure(config); }
  void configure(const StrokeEndConfig& config);
  // Nothing known (a touch-down, a jump, a gap).
  void restart();
  // A report, seen at t_us (the tracker's clock): O(kRestPoints), and
  // O(kCapacity) when the kept points fill up. One not after the newest is
  // ignored.
  void add(uint32_t t_us, Vec2 p);
  // A refinement is due: the stroke has begun and refine_interval_us of
  // reports have come since the last one.
  bool refine_due() const;
  // One step of the fit on the reports so far. True if the stroke has ended
  // by the newest report: the next stroke begins with it.
  bool refine();

  // What the direction is worth at now_us: 1, or towards the fitted end of a
  // stroke that stands out of the noise, falling from 1 where the fitted
  // speed is quiet_speed_px_s to 0 at the end (and 0 after it, until the
  // next refinement ends the stroke). O(1): for every tick.
  float stopping_gain(uint32_t now_us) const {
    return quiet_known_ && signed_elapsed(now_us, quiet_from_us_) > 0 ? quiet_gain(now_us) : 1.0f;
  }

  bool moving() const { return moving_; }
  float fitted_end_s() const { return end_s_; }      // from the stroke's first kept report
  float fitted_start_s() const { return start_s_; }
  uint32_t origin_us() const { return origin_us_; }  // the clock at its first kept report
  uint32_t refinements() const { return refinements_; }  // since configure(): the cost

 private:
  struct Point {
    float t, x, y;   // s and px from the origin
    uint32_t t_us;   // its stamp, for exact re-origins
  };
  struct Fit {
    float explained = -1.0f;  // the sum of squares the profile explains (px^2); < 0: no fit
    float profile_spread = 0.0f;  // sum of (s_i - mean s)^2
  };
  Fit evaluate(float start_s, float end_s, int n, Vec2 mean) const;
  void begin_stroke_at(const Point& newest);
  void keep_moving(const Point& p);
  void keep_resting(const Point& p);
  void reorigin_at_first();
  float quiet_gain(uint32_t now_us) const;  // past quiet_from_us_

  StrokeEndConfig config_;
  Point points_[kCapacity + 1];  // + the newest report when not kept
  int count_ = 0;
  uint32_t spacing_us_ = kSpacingUs;
  uint32_t origin_us_ = 0;
  Vec2 origin_;
  bool started_ = false;  // any report since restart()
  bool moving_ = false;
  Point newest_{};
  bool newest_kept_ = false;
  float motion_s_ = 0.0f;  // when the stroke began to move
  float start_s_ = 0.0f, end_s_ = 0.0f;        // the fitted timing
  float start_step_s_ = 0.0f, end_step_s_ = 0.0f;  // the search's
  float last_refine_s_ = 0.0f;
  float refine_interval_s_ = 0.0f;
  uint32_t refinements_ = 0;
  // The fitted stroke's quiet end (stopping_gain): from quiet_from_us_, 1 / its length in us.
  bool quiet_known_ = false;
  uint32_t quiet_from_us_ = 0;
  float inverse_quiet_us_ = 0.0f;
};

}  // namespace ff
