// At a predicted stroke end the direction filter takes over the position
// filter's estimate only when the position filter reads the finger slower
// (TrackerConfig::stroke_end_takes_position), on the generated trace where
// taking it over regardless made a rest chatter.
#include <gtest/gtest.h>

#include <vector>

#include "class_report.hpp"
#include "support/models/trace_classes.hpp"
#include "tracking_evaluation.hpp"

namespace ff::bench {
namespace {

TEST(StrokeEndTakeover, AFasterPositionFilterIsNotTakenOver) {
  // realistic-100hz's third 30 s trace: 20.5 s in, a stroke of 17 px in
  // 50 ms (615 px/s at its peak) ends. At the predicted end the position
  // filter read 424 px/s and the direction filter 71; taken over, that speed
  // rendered up to a third of the direction through the first 130 ms of the
  // rest, and this trace's chatter rose to 0.041 (measured; 0.0036 widened
  // instead, as the shipping tracker does there). So the take-over waits for
  // the slower reading.
  const tracegen::TraceClass* realistic = tracegen::find_trace_class("realistic-100hz");
  ASSERT_NE(realistic, nullptr);
  const std::vector<TrackCase> all = class_cases(*realistic, 30.0);
  ASSERT_GE(all.size(), 3u);
  const std::vector<PreparedCase> cases = prepare_cases({all[2]});
  ASSERT_EQ(cases.size(), 1u);
  EvalOptions options;
  options.cost = false;
  options.moving_speed_px_s = kClassMovingSpeedPxS;
  const TrackerConfig shipping = TrackerConfig::recommended(nominal_profile(cases.front()));
  TrackerConfig widened = shipping;
  widened.stroke_end_takes_position = false;
  const Metrics taken = evaluate(shipping, cases, options);
  const Metrics without = evaluate(widened, cases, options);
  EXPECT_LE(taken.heightmap_rest_rms, 0.01);
  EXPECT_LE(taken.heightmap_rest_rms, without.heightmap_rest_rms + 0.002);
}

}  // namespace
}  // namespace ff::bench
