#pragma once
// The finger's true motion: a chain of minimum-jerk strokes, holds (short
// dwells at a reversal, longer rests) and lifts. Host only, double precision:
// this is the ground truth the trackers are judged against.
#include <cstdint>
#include <vector>

namespace ff::tracegen {

struct Point {
  double x = 0.0;
  double y = 0.0;
};

// Screen units (docs/spec.md#coordinates): 1 px ~ 0.2 mm.
constexpr double kMmPerPx = 0.2;
constexpr double kPxPerMm = 1.0 / kMmPerPx;

// docs/spec.md#paths: y of the path to the target at 240 + rise.
double path_y(double x, double rise);
double path_slope(double x, double rise);

// Minimum-jerk profile s(tau) = 10 tau^3 - 15 tau^4 + 6 tau^5 on [0, 1], and
// its derivative; the peak of ds/dtau is 1.875 at tau = 0.5.
double min_jerk(double tau);
double min_jerk_rate(double tau);
constexpr double kMinJerkPeakRate = 1.875;

struct TrueState {
  bool touching = false;
  bool resting = false;   // inside a rest (a long deliberate hold)
  Point position;         // px
  Point velocity;         // px/s
};

enum class SegmentKind : uint8_t { Stroke, Hold, Lifted };
enum class StrokeShape : uint8_t {
  Bowed,      // p0 -> p1 along a straight line bent sideways by `bow` px at the middle
  AlongPath,  // x from p0.x to p1.x on y_path(x) + u, u from u0 to u1
};

struct Segment {
  SegmentKind kind = SegmentKind::Hold;
  double t_start_s = 0.0;
  double duration_s = 0.0;
  Point p0, p1;                 // Stroke: ends; Hold/Lifted: p0 (Lifted: p1 = landing point)
  StrokeShape shape = StrokeShape::Bowed;
  double bow_px = 0.0;          // Bowed
  double rise_px = 0.0;         // AlongPath: which path
  double u0 = 0.0, u1 = 0.0;    // AlongPath: offsets from the path at the ends
  bool rest = false;            // Hold: a rest rather than a dwell
  bool hesitation = false;      // Hold: a pause in the middle of a stroke
  double peak_speed_px_s = 0.0; // Stroke: the speed the stroke was planned for
};

class Motion {
 public:
  explicit Motion(Point start = {}) : cursor_(start) {}

  // A stroke from the current position, timed for the given peak speed.
  void stroke_to(Point p1, double peak_speed_px_s, double bow_px = 0.0);
  // A stroke from the current position that takes `duration_s` (> 0).
  void stroke_for(Point p1, double duration_s, double bow_px = 0.0);
  // Along the path with the given rise from the current x to x1, ending u1 px off it.
  void stroke_along_path(double x1, double rise_px, double u1, double peak_speed_px_s);
  void hold(double duration_s, bool rest, bool hesitation = false);
  // Finger off the screen for duration_s, then down again at `landing`.
  void lift(double duration_s, Point landing);

  TrueState at(double t_s) const;
  double duration_s() const { return end_s_; }
  Point position() const { return cursor_; }
  const std::vector<Segment>& segments() const { return segments_; }

 private:
  const Segment* find(double t_s) const;
  void push(Segment s);

  std::vector<Segment> segments_;
  Point cursor_;
  double end_s_ = 0.0;
};

// Curve point and tangent (d/dsigma) of a stroke at sigma in [0, 1].
void stroke_curve(const Segment& s, double sigma, Point& point, Point& tangent);
// Arc length of a stroke (numerical, 64 pieces).
double stroke_length(const Segment& s);

}  // namespace ff::tracegen
