#include "rest_chatter.hpp"

#include <algorithm>
#include <cmath>

#include "support/statistics.hpp"

namespace ff::bench {

void RestChatter::resting(uint64_t t_us, double deviation) {
  if (!in_rest_) {
    in_rest_ = true;
    settled_ = false;
    in_band_ = false;
    rest_start_us_ = t_us;
  }
  const double squared = deviation * deviation;
  ++ticks_;
  sum_squared_ += squared;
  if (t_us - rest_start_us_ >= kStopTransientUs) {
    ++steady_ticks_;
    steady_sum_squared_ += squared;
  }
  if (settled_) return;
  if (std::fabs(deviation) > kSettledBand) {
    in_band_ = false;
    return;
  }
  if (!in_band_) {
    in_band_ = true;
    band_since_us_ = t_us;
  }
  if (t_us - band_since_us_ >= kSettledHoldUs) {
    settled_ = true;
    settle_us_.push_back(band_since_us_ - rest_start_us_);
  }
}

void RestChatter::not_resting() {
  if (!in_rest_) return;
  in_rest_ = false;
  if (settled_) return;
  if (in_band_) {
    settle_us_.push_back(band_since_us_ - rest_start_us_);  // in the band until the rest ended
  } else {
    ++unsettled_;
  }
}

double RestChatter::rms() const { return ticks_ > 0 ? std::sqrt(sum_squared_ / static_cast<double>(ticks_)) : 0.0; }

double RestChatter::steady_rms() const {
  return steady_ticks_ > 0 ? std::sqrt(steady_sum_squared_ / static_cast<double>(steady_ticks_)) : 0.0;
}

double RestChatter::transient_share() const {
  return sum_squared_ > 0.0 ? (sum_squared_ - steady_sum_squared_) / sum_squared_ : 0.0;
}

double RestChatter::settle_median_ms() const {
  return support::percentile(std::vector<double>(settle_us_.begin(), settle_us_.end()), 50.0) * 1e-3;
}

double RestChatter::settle_max_ms() const {
  return settle_us_.empty() ? 0.0 : static_cast<double>(*std::max_element(settle_us_.begin(), settle_us_.end())) * 1e-3;
}

}  // namespace ff::bench
