#pragma once
// How a participant explores the screen (thesis section 6.4, figure 10): back
// and forth along the paths (typical of the frictionmap), strokes across
// them (typical of the heightmap), or a mix. Produces the true motion.
#include <string>

#include "support/models/motion.hpp"
#include "support/random.hpp"

namespace ff::tracegen {

using support::Random;
using support::Stream;

enum class Strategy : uint8_t { Along, Across, Mixed };
const char* to_string(Strategy s);
bool parse_strategy(const std::string& text, Strategy& out);

// Which path(s) the along-strategy follows.
enum class PathChoice : uint8_t { All, Top, Middle, Bottom };
const char* to_string(PathChoice p);
bool parse_path_choice(const std::string& text, PathChoice& out);

struct MotionOptions {
  Strategy strategy = Strategy::Mixed;
  PathChoice paths = PathChoice::All;
  double duration_s = 10.0;
  // Peak speed of each stroke, log-uniform between these (mm/s).
  double speed_min_mm_s = 50.0;
  double speed_max_mm_s = 400.0;
  // Pause at each reversal (s), uniform.
  double dwell_min_s = 0.0;
  double dwell_max_s = 0.12;
  // Deliberate rests and lifts, spread over the trace.
  int rests = 0;
  double rest_min_s = 0.6;
  double rest_max_s = 2.0;
  int lifts = 0;
  double lift_min_s = 0.15;
  double lift_max_s = 0.6;

  // What real fingers add (issue 14), each off by default and drawn from its
  // own random stream, so that the default motion stays exactly as it was.
  // Slow strokes: this share of strokes peaks at slow_min..slow_max px/s
  // (log-uniform; starts, stops, careful tracing) and is shortened to last
  // 0.8-2 s.
  double slow_fraction = 0.0;
  double slow_min_px_s = 20.0;
  double slow_max_px_s = 70.0;
  // Hesitations: this share of strokes stops once mid-way (35-65 % of the
  // way) for hesitation_min..max s and then goes on.
  double hesitation_fraction = 0.0;
  double hesitation_min_s = 0.08;
  double hesitation_max_s = 0.3;
  // Sharp reversals: this share of strokes turns straight back (no dwell)
  // for 15-40 % of its length at the same peak speed.
  double reversal_fraction = 0.0;

  // A calibration recording (ff-track-bench --calibrate): the finger rests
  // at the middle of the screen for the whole duration, nothing else.
  bool rest_only = false;
};

// The motion is at least options.duration_s long (it ends after the stroke
// that crosses the duration). The same seed and options, the same motion.
Motion plan_motion(const MotionOptions& options, uint64_t seed);

}  // namespace ff::tracegen
