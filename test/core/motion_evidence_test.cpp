// A filter's speed as evidence of motion (motion_evidence.hpp), against the
// fade's scale worked out by hand: z^2 = |v|^2 / (resting + excess P11),
// 0 at rest_sigmas^2 and 1 at moving_sigmas^2.
#include "frictionfield/core/motion_evidence.hpp"

#include <gtest/gtest.h>

namespace ff {
namespace {

// Levels 2 / 4 sigma: rest level 4, span 16 - 4 = 12. Settled P11 10, resting variance 5.
MotionEvidence settled_evidence() {
  MotionEvidence e;
  e.configure(true, 2.0f, 4.0f, SpeedNoise{10.0f, 5.0f});
  e.learn(10.0f);  // settled: no excess, the noise is the resting variance alone
  return e;
}

TEST(MotionEvidence, IsZeroAtTheRestLevelAndOneAtTheMovingLevel) {
  const MotionEvidence e = settled_evidence();
  EXPECT_FLOAT_EQ(e.of(4.0f * 5.0f), 0.0f);    // 2 sigma: (20 / 5 - 4) / 12
  EXPECT_FLOAT_EQ(e.of(16.0f * 5.0f), 1.0f);   // 4 sigma: (80 / 5 - 4) / 12
  EXPECT_FLOAT_EQ(e.of(10.0f * 5.0f), 0.5f);   // halfway in sigma^2: (50 / 5 - 4) / 12
  EXPECT_FLOAT_EQ(e.of(0.0f), -4.0f / 12.0f);  // unclamped: the fade clamps
}

TEST(MotionEvidence, CountsWhatTheFilterHasNotLearnedAsNoise) {
  MotionEvidence e = settled_evidence();
  e.learn(25.0f);  // P11 15 over its settled value: noise 5 + 15 = 20
  EXPECT_FLOAT_EQ(e.of(16.0f * 20.0f), 1.0f);
  EXPECT_FLOAT_EQ(e.of(4.0f * 20.0f), 0.0f);
  e.learn(3.0f);  // under the settled value (just started at rest): no credit, the resting variance alone
  EXPECT_FLOAT_EQ(e.of(16.0f * 5.0f), 1.0f);
}

// Configured again (a new condition or sensor profile), it forgets the noise
// it learned under the old one: until the next report, any speed reads as rest.
TEST(MotionEvidence, ConfiguredAgainItReadsRestUntilItLearns) {
  MotionEvidence e = settled_evidence();
  e.configure(true, 2.0f, 4.0f, SpeedNoise{1000.0f, 500.0f});
  EXPECT_FLOAT_EQ(e.of(1e6f), -4.0f / 12.0f);  // as at speed 0
  e.learn(1000.0f);
  EXPECT_FLOAT_EQ(e.of(16.0f * 500.0f), 1.0f);
}

TEST(MotionEvidence, IsUnusedWhenSwitchedOffOrWithoutASpan) {
  MotionEvidence off;
  off.configure(false, 2.0f, 4.0f, SpeedNoise{10.0f, 5.0f});
  EXPECT_FALSE(off.used());
  MotionEvidence flat;
  flat.configure(true, 4.0f, 4.0f, SpeedNoise{10.0f, 5.0f});
  EXPECT_FALSE(flat.used());
  MotionEvidence reversed;
  reversed.configure(true, 5.0f, 4.0f, SpeedNoise{10.0f, 5.0f});
  EXPECT_FALSE(reversed.used());
  EXPECT_TRUE(settled_evidence().used());
}

}  // namespace
}  // namespace ff
