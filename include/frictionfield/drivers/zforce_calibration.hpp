#pragma once
// Sensor coordinates to screen pixels: the one place this mapping is stated.
//
//   (u, v) = swap_xy ? (raw_y, raw_x) : (raw_x, raw_y)
//   u'     = flip_x ? range_x - u : u          (same for v with flip_y, range_y)
//   x_px   = offset_x + scale_x * u'
//   y_px   = offset_y + scale_y * v'
//
// range_x, range_y are the ranges of u and v: the resolution the sensor was
// told to report in (its coordinates run 0..range; swapped with swap_xy). The default maps the sensor's active area onto
// the 800 x 480 screen with the sensor along the top edge, x to the right and
// y growing away from the sensor (downwards), as on the thesis' prototype; a
// measured calibration (offsets of the mounted sensor against the LCD)
// replaces it.
#include <cstdint>

namespace ff {

struct ScreenCalibration {
  uint32_t range_x = 3200;
  uint32_t range_y = 1920;
  float scale_x = 0.25f;  // px per sensor unit
  float scale_y = 0.25f;
  float offset_x = 0.0f;  // px
  float offset_y = 0.0f;
  bool flip_x = false;
  bool flip_y = false;
  bool swap_xy = false;

  // range -> (width, height) px, no offset, no flips.
  static ScreenCalibration fit(uint32_t range_x, uint32_t range_y, float width_px = 800.0f,
                               float height_px = 480.0f);
  // Finite scales and offsets, non-zero ranges.
  bool valid() const;
  void to_screen(uint32_t raw_x, uint32_t raw_y, float& x_px, float& y_px) const;
};

}  // namespace ff
