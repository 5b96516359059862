#pragma once
// The minimum-jerk profile (Flash & Hogan 1985): a point-to-point movement
// that starts and stops at rest covers the fraction s(tau) = 10 tau^3 -
// 15 tau^4 + 6 tau^5 of its way at tau = (t - start) / duration, 0 before
// it, 1 after. A finger's strokes are close to it; the trace generator's
// are exactly it. Float on the device, double in the generator: one formula.

namespace ff {

// Within the movement, 0 <= tau <= 1.
template <class T>
constexpr T min_jerk_within(T tau) {
  return tau * tau * tau * (T(10) + tau * (T(-15) + T(6) * tau));
}

template <class T>
constexpr T min_jerk(T tau) {
  return min_jerk_within(tau < T(0) ? T(0) : (tau > T(1) ? T(1) : tau));
}

}  // namespace ff
