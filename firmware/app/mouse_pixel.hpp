#pragma once
// The filtered position as a mouse pixel: rounded, and on the screen whatever
// the float is (NaN and infinities too), so Mouse.moveTo never gets a pixel
// off the screen even if a position ever escaped the tracker's clamp.

namespace ff::firmware {

inline int mouse_pixel(float v, float max) {
  if (!(v > 0.0f)) return 0;  // NaN too
  if (v >= max) return static_cast<int>(max);
  return static_cast<int>(v + 0.5f);
}

}  // namespace ff::firmware
