#pragma once
// The 1-euro filter (Casiez et al.) at a fixed rate, as thesis appendix G
// tunes it. Two ways to take the derivative: from the previous filtered
// value (the thesis and the authors' current reference; default) or from the
// previous raw value (their older code and most ports).
#include <cstdint>

namespace ff {

enum class DerivativeFrom : uint8_t { PreviousFiltered, PreviousRaw };

struct OneEuroConfig {
  float rate_hz = 2000.0f;
  float min_cutoff_hz = 20.0f;
  float beta = 0.0004f;
  float derivative_cutoff_hz = 25.0f;
  DerivativeFrom derivative_from = DerivativeFrom::PreviousFiltered;
};

class OneEuroFilter {
 public:
  void configure(const OneEuroConfig& config);
  void reset() { initialised_ = false; }
  // Filters one value; the first after reset passes through, derivative 0.
  float filter(float x);
  float value() const { return x_hat_; }
  float derivative() const { return dx_hat_; }  // units per second
  bool initialised() const { return initialised_; }

  // alpha(fc) = 1 / (1 + f_r / (2 pi fc)).
  static float alpha(float cutoff_hz, float rate_hz);

 private:
  OneEuroConfig config_;
  float alpha_derivative_ = 0.0f;
  float x_hat_ = 0.0f;
  float x_prev_raw_ = 0.0f;
  float dx_hat_ = 0.0f;
  bool initialised_ = false;
};

}  // namespace ff
