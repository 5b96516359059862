#include "frictionfield/drivers/zforce_calibration.hpp"

#include <cmath>

namespace ff {

ScreenCalibration ScreenCalibration::fit(uint32_t range_x, uint32_t range_y, float width_px, float height_px) {
  ScreenCalibration c;
  c.range_x = range_x == 0 ? 1 : range_x;
  c.range_y = range_y == 0 ? 1 : range_y;
  c.scale_x = width_px / static_cast<float>(c.range_x);
  c.scale_y = height_px / static_cast<float>(c.range_y);
  return c;
}

bool ScreenCalibration::valid() const {
  return range_x > 0 && range_y > 0 && std::isfinite(scale_x) && std::isfinite(scale_y) && std::isfinite(offset_x) &&
         std::isfinite(offset_y);
}

void ScreenCalibration::to_screen(uint32_t raw_x, uint32_t raw_y, float& x_px, float& y_px) const {
  float u = static_cast<float>(swap_xy ? raw_y : raw_x);
  float v = static_cast<float>(swap_xy ? raw_x : raw_y);
  if (flip_x) u = static_cast<float>(range_x) - u;
  if (flip_y) v = static_cast<float>(range_y) - v;
  x_px = offset_x + scale_x * u;
  y_px = offset_y + scale_y * v;
}

}  // namespace ff
