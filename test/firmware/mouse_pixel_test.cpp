// The mouse pixel of a filtered position: rounded half up, and on the screen
// (0..799 here) for every float, by hand.
#include "firmware/app/mouse_pixel.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace ff::firmware {
namespace {

TEST(MousePixel, RoundsToTheNearestPixel) {
  EXPECT_EQ(mouse_pixel(0.49f, 799.0f), 0);
  EXPECT_EQ(mouse_pixel(0.5f, 799.0f), 1);
  EXPECT_EQ(mouse_pixel(400.6f, 799.0f), 401);
  EXPECT_EQ(mouse_pixel(798.4f, 799.0f), 798);
  EXPECT_EQ(mouse_pixel(798.6f, 799.0f), 799);
}

TEST(MousePixel, StaysOnTheScreenWhateverTheFloat) {
  const float inf = std::numeric_limits<float>::infinity();
  EXPECT_EQ(mouse_pixel(-0.2f, 799.0f), 0);
  EXPECT_EQ(mouse_pixel(-3.0f, 799.0f), 0);
  EXPECT_EQ(mouse_pixel(-inf, 799.0f), 0);
  EXPECT_EQ(mouse_pixel(std::numeric_limits<float>::quiet_NaN(), 799.0f), 0);
  EXPECT_EQ(mouse_pixel(799.0f, 799.0f), 799);
  EXPECT_EQ(mouse_pixel(1e9f, 799.0f), 799);
  EXPECT_EQ(mouse_pixel(inf, 799.0f), 799);
}

}  // namespace
}  // namespace ff::firmware
