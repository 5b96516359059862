#pragma once
// Physiological tremor: an involuntary 8-12 Hz oscillation of the finger,
// ~0.1-0.5 mm (0.5-2.5 px) in amplitude, on top of the voluntary motion. It is
// part of what the sensor sees but not of the truth the trackers are judged
// on (they should render the voluntary stroke), so it is kept apart.
#include "support/models/motion.hpp"
#include "support/random.hpp"

namespace ff::tracegen {

struct TremorOptions {
  double amplitude_px = 0.0;  // peak displacement per axis; 0: no tremor
  double min_hz = 8.0;        // the frequency is drawn once per trace in [min_hz, max_hz]
  double max_hz = 12.0;
};

class Tremor {
 public:
  Tremor() = default;
  Tremor(const TremorOptions& options, support::Random& rng);

  bool enabled() const { return amplitude_px_ > 0.0; }
  double frequency_hz() const { return frequency_hz_; }
  // The displacement at motion time t_s: an ellipse traced at frequency_hz,
  // each axis a sinusoid of amplitude_px with its own phase.
  Point at(double t_s) const;

 private:
  double amplitude_px_ = 0.0;
  double frequency_hz_ = 0.0;
  double phase_x_ = 0.0, phase_y_ = 0.0;
};

}  // namespace ff::tracegen
