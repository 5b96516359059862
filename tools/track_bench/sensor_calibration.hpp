#pragma once
// A SensorProfile estimated from a recording of a resting finger
// (ff-track-bench --calibrate, docs/tracking.md#calibration).
//
// Timing: the report rate from the mean interval and the jitter as the
// interval's 1 sigma, both without intervals outside 0.5-1.5 x the median
// (a missed report, a late stamp and the short interval after it are not
// jitter).
// Noise, per axis, then averaged over x and y: the residual after a centred
// moving mean over 1 s (which takes out where the finger rests and any slow
// drift), its autocovariance C(lag) in lag bins one median interval wide, and
// a least-squares fit of
//   C(0)       = white^2 + corr^2 + tremor^2 / 2 + slow
//   C(lag > 0) = corr^2 exp(-lag / tau) + (tremor^2 / 2) cos(2 pi f lag) + slow
// where `slow` is what varies over more than the fit's lags (drift left over,
// and the moving mean's own small bias). white includes the quantisation
// (q^2 / 12). The tremor's frequency f comes from the strongest peak of the
// residual's spectrum (a plain DFT at the report times) in 6-14 Hz; there is
// tremor only if that peak stands out of its neighbourhood, and correlated
// noise only if the exponential term improves the fit by far more than noise
// would (thresholds below).
#include <cstdint>
#include <string>
#include <vector>

#include "frictionfield/core/sensor_profile.hpp"
#include "frictionfield/host/trace_csv.hpp"

namespace ff::bench {

struct CalibrationOptions {
  double max_interval_factor = 1.5;  // intervals outside (2 - this .. this) x the median are left out
  double detrend_window_s = 1.0;     // centred moving mean taken out of each axis
  double max_lag_s = 0.2;            // the autocovariance is fitted up to this lag
  double max_tau_s = 0.1;            // longest correlation time tried (longer looks like `slow`)
  double tremor_min_hz = 6.0, tremor_max_hz = 14.0, tremor_step_hz = 0.02;
  // Tremor: the spectral peak's power over the median power 0.3-1.5 Hz either
  // side of it. Without tremor (white or correlated noise, 120 generated
  // 10 s recordings at 100 Hz-1 kHz) the strongest peak was 2.4-9.7.
  double tremor_peak_ratio = 30.0;
  // Correlated noise: the fit's squared error falls by more than this many
  // times the residual variance of one lag bin. White noise alone (90
  // generated 10 s recordings) gave 0-24; the correlated-noise class 1457-56287.
  double correlated_improvement = 50.0;
  double max_gap_s = 0.25;       // a longer gap splits the recording (so does a lift)
  double min_duration_s = 1.0;   // refuse shorter recordings ...
  size_t min_reports = 100;      // ... or fewer reports
  double max_range_px = 20.0;    // ... or a finger whose 1 s mean moves more than this per axis
};

struct Calibration {
  SensorProfile profile;            // latency_us: as given (not measurable from a recording)
  size_t reports = 0;               // usable touch reports
  size_t runs = 0;                  // pieces between lifts and gaps
  size_t off_screen = 0;            // touch rows left out: not finite or off the screen
  size_t not_after = 0;             // ... stamped at or before the report before
  size_t glitches = 0;              // reports far from the resting finger: out of the noise, not the timing
  double glitch_threshold_px = 0.0; // how far from the run's median counts as far (0: none found)
  double duration_s = 0.0;          // summed over the runs
  size_t intervals = 0;             // used for rate and jitter
  size_t dropped_intervals = 0;     // outside 0.5-1.5 x the median (max_interval_factor)
  double median_interval_us = 0.0;
  double range_px = 0.0;            // largest range of the 1 s moving mean, x or y
  double total_noise_px = 0.0;      // sqrt C(0)
  double slow_px2 = 0.0;            // the fit's constant term
  double tremor_hz = 0.0;           // 0: no tremor found
  double tremor_peak_ratio = 0.0;   // the strongest peak in the band over its neighbourhood
  double correlated_improvement = 0.0;  // see CalibrationOptions
  size_t lag_bins = 0;
  double fit_rms_px2 = 0.0;         // RMS of the fit's residual over the lag bins
};

// false with a one-line `error` when the recording cannot give a profile
// (too short, too few reports, the finger moves).
bool calibrate_from_rest(const std::vector<host::TraceRow>& rows, const CalibrationOptions& options,
                         uint32_t latency_us, Calibration& out, std::string& error);

}  // namespace ff::bench
