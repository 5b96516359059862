#include "support/models/tremor.hpp"

#include <cmath>

namespace ff::tracegen {

namespace {
constexpr double kTwoPi = 6.283185307179586476925;
}

Tremor::Tremor(const TremorOptions& options, support::Random& rng)
    : amplitude_px_(options.amplitude_px),
      frequency_hz_(rng.uniform(options.min_hz, options.max_hz)),
      phase_x_(rng.uniform(0.0, kTwoPi)),
      phase_y_(rng.uniform(0.0, kTwoPi)) {}

Point Tremor::at(double t_s) const {
  if (!enabled()) return {};
  const double w = kTwoPi * frequency_hz_ * t_s;
  return {amplitude_px_ * std::sin(w + phase_x_), amplitude_px_ * std::sin(w + phase_y_)};
}

}  // namespace ff::tracegen
