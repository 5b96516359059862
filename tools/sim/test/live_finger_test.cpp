// The finger datagrams ff-sim reads (docs/tools.md: 'x y force_N' or 'up')
// and the zForce reports it makes of them: one every 5 ms while the finger is
// down, one "up" after it lifts, nothing while it is away.
#include <gtest/gtest.h>

#include "../live_finger.hpp"

namespace {

using ff::sim::FingerState;
using ff::sim::LiveFinger;
using ff::sim::parse_finger_datagram;

TEST(FingerDatagram, APositionAndForceIsAFingerDown) {
  FingerState f;
  std::string error;
  ASSERT_TRUE(parse_finger_datagram("120.5 240 0.4", f, error)) << error;
  EXPECT_TRUE(f.down);
  EXPECT_FLOAT_EQ(f.x, 120.5f);
  EXPECT_FLOAT_EQ(f.y, 240.0f);
  EXPECT_FLOAT_EQ(f.force_N, 0.4f);
  // As `echo` and netcat send it: line ends and trailing spaces are not part of it.
  ASSERT_TRUE(parse_finger_datagram("1 2 0\r\n", f, error)) << error;
  EXPECT_TRUE(f.down);
  EXPECT_FLOAT_EQ(f.force_N, 0.0f);
  ASSERT_TRUE(parse_finger_datagram("3 4 0.5  \n", f, error)) << error;
  EXPECT_FLOAT_EQ(f.x, 3.0f);
}

TEST(FingerDatagram, UpLiftsTheFingerItWasGiven) {
  FingerState f{true, 10.0f, 20.0f, 0.3f};
  std::string error;
  ASSERT_TRUE(parse_finger_datagram("up\n", f, error)) << error;
  EXPECT_FALSE(f.down);
  EXPECT_FLOAT_EQ(f.force_N, 0.0f);
}

TEST(FingerDatagram, AnythingElseIsRefusedWithTheDatagramNamed) {
  for (const char* bad : {"", "1 2", "1 2 3 4", "a b c", "nan 2 0.3", "1 inf 0.3", "1 2 nan", "1 2 -0.1", "down"}) {
    FingerState f{true, 10.0f, 20.0f, 0.3f};
    std::string error;
    EXPECT_FALSE(parse_finger_datagram(bad, f, error)) << bad;
    EXPECT_EQ(error, std::string("finger datagram '") + bad + "': expected 'x y force_N' or 'up'");
    EXPECT_TRUE(f.down) << "a refused datagram leaves the finger as it was: " << bad;
  }
  FingerState f;
  std::string error;
  EXPECT_FALSE(parse_finger_datagram(std::string(100, 'x'), f, error));
  EXPECT_EQ(error, "finger datagram '" + std::string(40, 'x') + "': expected 'x y force_N' or 'up'");
}

TEST(LiveFinger, ReportsEvery5msWhileDownOnceWhenLiftedAndNothingWhileAway) {
  ff::emulated::ZforceModel zforce;
  const size_t boot = zforce.frames_pending();  // the sensor's boot-complete notification
  LiveFinger finger;
  finger.step(1000, zforce);
  EXPECT_EQ(zforce.frames_pending(), boot) << "no finger: the sensor is quiet";
  finger.set({true, 100.0f, 200.0f, 0.3f});
  // The sensor's 5 ms grid starts at the first step (1 ms): reports at 6, 11 and 16 ms.
  finger.step(20000, zforce);
  EXPECT_EQ(zforce.frames_pending(), boot + 3);
  finger.step(20999, zforce);
  EXPECT_EQ(zforce.frames_pending(), boot + 3);
  finger.step(21000, zforce);
  EXPECT_EQ(zforce.frames_pending(), boot + 4);
  finger.set({});
  finger.step(26000, zforce);  // one "up"
  EXPECT_EQ(zforce.frames_pending(), boot + 5);
  finger.step(60000, zforce);
  EXPECT_EQ(zforce.frames_pending(), boot + 5) << "lifted: nothing more";
  EXPECT_EQ(finger.state().down, false);
}

}  // namespace
