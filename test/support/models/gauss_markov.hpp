#pragma once
// A first-order Gauss-Markov process (a continuous-time AR(1)): a stationary
// Gaussian wander with standard deviation sigma and correlation time tau,
// E[e(t) e(t + dt)] = sigma^2 exp(-dt / tau). Sampled at any, irregular,
// times with the exact discretisation, so that one process serves every
// report rate: the sensor's correlated noise and its slow drift.
#include <algorithm>
#include <cmath>

#include "support/random.hpp"

namespace ff::tracegen {

class GaussMarkov {
 public:
  GaussMarkov(double sigma, double tau_s) : sigma_(sigma), tau_s_(tau_s) {}

  // The value at time t_s (non-decreasing between calls); the first call
  // draws from the stationary distribution N(0, sigma^2).
  double at(double t_s, support::Random& rng) {
    if (!started_) {
      value_ = sigma_ * rng.gaussian();
      started_ = true;
    } else {
      const double rho = std::exp(-std::max(0.0, t_s - t_s_) / tau_s_);
      value_ = rho * value_ + sigma_ * std::sqrt(1.0 - rho * rho) * rng.gaussian();
    }
    t_s_ = t_s;
    return value_;
  }

 private:
  double sigma_, tau_s_;
  double value_ = 0.0, t_s_ = 0.0;
  bool started_ = false;
};

}  // namespace ff::tracegen
