#include "frictionfield/core/one_euro_filter.hpp"

#include "frictionfield/core/fastrun.hpp"

#include <cmath>

#include "frictionfield/core/geometry.hpp"

namespace ff {

float OneEuroFilter::alpha(float cutoff_hz, float rate_hz) {
  return 1.0f / (1.0f + rate_hz / (2.0f * kPi * cutoff_hz));
}

void OneEuroFilter::configure(const OneEuroConfig& config) {
  config_ = config;
  alpha_derivative_ = alpha(config.derivative_cutoff_hz, config.rate_hz);
  initialised_ = false;
}

FF_FASTRUN float OneEuroFilter::filter(float x) {
  if (!initialised_) {
    initialised_ = true;
    x_hat_ = x;
    x_prev_raw_ = x;
    dx_hat_ = 0.0f;
    return x;
  }
  const float reference = config_.derivative_from == DerivativeFrom::PreviousFiltered ? x_hat_ : x_prev_raw_;
  const float dx = (x - reference) * config_.rate_hz;
  dx_hat_ = alpha_derivative_ * dx + (1.0f - alpha_derivative_) * dx_hat_;
  const float cutoff = config_.min_cutoff_hz + config_.beta * std::fabs(dx_hat_);
  const float a = alpha(cutoff, config_.rate_hz);
  x_hat_ = a * x + (1.0f - a) * x_hat_;
  x_prev_raw_ = x;
  return x_hat_;
}

}  // namespace ff
