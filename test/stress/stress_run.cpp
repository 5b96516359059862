#include "stress_run.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace ff::stress {

RunResult run_pipeline(const RunConfig& config, const std::vector<Report>& reports,
                       const std::vector<TickTime>& ticks, TickObserver* observe, bool keep_ticks) {
  RunResult r;
  auto pipeline = std::make_unique<HapticPipeline>(config.tracker);
  r.status = pipeline->set_condition(config.condition);
  if (keep_ticks) r.ticks.reserve(ticks.size());
  size_t next = 0;
  for (const TickTime& t : ticks) {
    while (next < reports.size() && reports[next].at <= t.at) {
      if (!pipeline->post_sample(reports[next].s)) ++r.failed_posts;
      ++next;
    }
    Tick tick{t.at, pipeline->tick(t.now)};
    if (observe != nullptr) observe->on_tick(*pipeline, tick);
    if (keep_ticks) r.ticks.push_back(tick);
  }
  r.faults = pipeline->faults();
  return r;
}

InvariantChecker::InvariantChecker(const RunConfig& config, double rendering_bound)
    : scene_(config.condition.scene),
      amplitude_(config.condition.amplitude, config.calibration_valid),
      rendering_bound_(rendering_bound),
      closed_form_(config.condition.scene.evaluation == Evaluation::ClosedForm &&
                       config.condition.scene.sampled.heights == nullptr) {}

void InvariantChecker::fail(const Tick& t, const std::string& what) {
  if (violations++ == 0) {
    char head[160];
    std::snprintf(head, sizeof head, "tick at %llu us (present %d, pos %.9g,%.9g, dir %.9g,%.9g, A %.9g, dac %u): ",
                  static_cast<unsigned long long>(t.at), t.out.present ? 1 : 0,
                  static_cast<double>(t.out.position.x), static_cast<double>(t.out.position.y),
                  static_cast<double>(t.out.direction.x), static_cast<double>(t.out.direction.y),
                  static_cast<double>(t.out.amplitude), static_cast<unsigned>(t.out.dac));
    first_violation = head + what;
  }
}

void InvariantChecker::on_tick(const HapticPipeline& pipeline, const Tick& t) {
  if (first_tick_) {
    // The amplitude is compared with the core's own max|G|; how far that is
    // from the true maximum is measured here, once.
    first_tick_ = false;
    const double core_max = pipeline.plan().stats().max_gradient;
    if (closed_form_ && pipeline.plan().needs() == Needs::PositionAndDirection && scene_.max_gradient() > 0.0) {
      max_gradient_error = std::fabs(core_max - scene_.max_gradient()) / scene_.max_gradient();
      scene_.use_max_gradient(core_max);
    }
  }
  ++ticks;
  const TickOutput& o = t.out;
  const double a = o.amplitude;
  if (!std::isfinite(a)) return fail(t, "amplitude is not finite");
  if (o.dac > kDacMax) return fail(t, "DAC code above 4095");
  bool tie = false;
  const int expected_dac = amplitude_.dac(a, &tie);
  if (tie) ++dac_ties;
  if (tie ? std::abs(static_cast<int>(o.dac) - expected_dac) > 1 : o.dac != expected_dac) {
    return fail(t, "DAC code " + std::to_string(o.dac) + " is not the calibration of the amplitude (" +
                       std::to_string(expected_dac) + ")");
  }
  if (!o.present) {
    if (a != amplitude_.idle()) return fail(t, "no finger but not the idle amplitude " + std::to_string(amplitude_.idle()));
    return;
  }
  const double s = amplitude_.strength();
  if (a < 0.5 - 0.5 * s - 1e-7 || a > 0.5 + 0.5 * s + 1e-7) {
    return fail(t, "amplitude outside the strength range (s = " + std::to_string(s) + ")");
  }
  if (!is_finite(o.position) || o.position.x < 0.0f || o.position.x > kScreenMaxX || o.position.y < 0.0f ||
      o.position.y > kScreenMaxY) {
    return fail(t, "position not finite or off screen");
  }
  // Unit length while moving, shorter while fading (docs/spec.md#replay-output). Here only a
  // sanity bound: the amplitude's own range is checked above, and the exact
  // unit length has its own class (direction_unit_length: the core misses it
  // by up to 27 % at subnormal speeds).
  if (!is_finite(o.direction) || length(o.direction) > 2.0f) return fail(t, "direction not finite or longer than 2");
  if (std::isinf(rendering_bound_)) return;  // no meaningful reference for this class
  const double ref = amplitude_.scale(scene_.raw_amplitude(o.position.x, o.position.y, o.direction.x, o.direction.y));
  const double dev = std::fabs(a - ref);
  if (!closed_form_) {
    if (dev > worst_table) worst_table = dev;
  } else {
    if (dev > worst_rendering) worst_rendering = dev;
    if (dev > rendering_bound_) {
      char buf[96];
      std::snprintf(buf, sizeof buf, "float32 amplitude deviates from the double reference %.9g by %.3g", ref, dev);
      return fail(t, buf);
    }
  }
}

int64_t recovery_ticks(const std::vector<Tick>& a, const std::vector<Tick>& b, uint64_t from_at, double pos_tol,
                       double amp_tol, std::string* last_difference, bool amplitude_at_rest) {
  // Walk both by real time; remember the last disagreement after from_at.
  size_t i = 0, j = 0;
  int64_t counted = 0, last_bad = -1;
  bool any = false;
  while (i < a.size() && j < b.size()) {
    if (a[i].at < b[j].at) { ++i; continue; }
    if (b[j].at < a[i].at) { ++j; continue; }
    if (a[i].at >= from_at) {
      const TickOutput& x = a[i].out;
      const TickOutput& y = b[j].out;
      bool compare_amplitude = amplitude_at_rest || !y.present;
      if (!compare_amplitude && j >= 20 && b[j - 20].out.present) {
        const Vec2 moved = y.position - b[j - 20].out.position;
        compare_amplitude = length(moved) > 0.5f;
      }
      const bool same = x.present == y.present &&
                        (!x.present || (std::fabs(static_cast<double>(x.position.x) - static_cast<double>(y.position.x)) <= pos_tol &&
                                        std::fabs(static_cast<double>(x.position.y) - static_cast<double>(y.position.y)) <= pos_tol)) &&
                        (!compare_amplitude || std::fabs(static_cast<double>(x.amplitude) - static_cast<double>(y.amplitude)) <= amp_tol);
      if (!same) {
        last_bad = counted;
        if (last_difference != nullptr) {
          char buf[320];
          std::snprintf(buf, sizeof buf, "at %llu us (%lld us after the episode): %s %.3f,%.3f dir %.3f,%.3f A %.4f vs clean %s %.3f,%.3f dir %.3f,%.3f A %.4f",
                        static_cast<unsigned long long>(a[i].at), static_cast<long long>(a[i].at - from_at),
                        x.present ? "finger" : "none", static_cast<double>(x.position.x), static_cast<double>(x.position.y),
                        static_cast<double>(x.direction.x), static_cast<double>(x.direction.y), static_cast<double>(x.amplitude),
                        y.present ? "finger" : "none", static_cast<double>(y.position.x), static_cast<double>(y.position.y),
                        static_cast<double>(y.direction.x), static_cast<double>(y.direction.y), static_cast<double>(y.amplitude));
          *last_difference = buf;
        }
      }
      ++counted;
      any = true;
    }
    ++i;
    ++j;
  }
  if (!any) return 0;
  if (last_bad == counted - 1) return -1;  // still apart at the end
  return last_bad + 1;
}

std::string bitwise_difference(const std::vector<Tick>& a, const std::vector<Tick>& b, bool ignore_time) {
  if (a.size() != b.size()) return "different tick counts";
  auto bits = [](float f) {
    uint32_t u;
    std::memcpy(&u, &f, sizeof u);
    return u;
  };
  for (size_t i = 0; i < a.size(); ++i) {
    const TickOutput& x = a[i].out;
    const TickOutput& y = b[i].out;
    if ((!ignore_time && a[i].at != b[i].at) || x.present != y.present || x.dac != y.dac || bits(x.amplitude) != bits(y.amplitude) ||
        bits(x.position.x) != bits(y.position.x) || bits(x.position.y) != bits(y.position.y) ||
        bits(x.direction.x) != bits(y.direction.x) || bits(x.direction.y) != bits(y.direction.y)) {
      return "tick " + std::to_string(i) + " differs";
    }
  }
  return {};
}

}  // namespace ff::stress
