#include "support/models/sensor_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "support/models/gauss_markov.hpp"

namespace ff::tracegen {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr uint64_t kClockWrap = uint64_t{1} << 32;

// A report before timestamps are made absolute: times relative to motion start.
struct Report {
  int64_t t_rel_us = 0;
  double latency_us = 0.0;
  double x = 0.0, y = 0.0;
  bool touch = false;
  SampleEvent event = SampleEvent::Normal;
};

// What happens to a report; Duplicate cycles through SampleEvent's Duplicate, SameTime, Earlier.
enum class Plan : uint8_t { None, Missing, Late, Jump, Duplicate, NonFinite, OffScreen };

class SensorSimulator {
 public:
  SensorSimulator(const Motion& motion, const Tremor& tremor, const TraceOptions& o)
      : motion_(motion), tremor_(tremor), o_(o), timing_(o.seed, Stream::Timing), noise_(o.seed, Stream::Noise),
        faults_(o.seed, Stream::Faults), latency_rng_(o.seed, Stream::Latency),
        period_rng_(o.seed, Stream::PeriodJitter), correlated_rng_(o.seed, Stream::CorrelatedNoise),
        drift_rng_(o.seed, Stream::Drift), correlated_x_(o.sensor.correlated_noise_px, o.sensor.correlated_noise_tau_s),
        correlated_y_(o.sensor.correlated_noise_px, o.sensor.correlated_noise_tau_s),
        drift_x_(o.sensor.drift_px, o.sensor.drift_tau_s), drift_y_(o.sensor.drift_px, o.sensor.drift_tau_s) {}

  std::vector<Report> run() {
    std::vector<Report> reports = scan();
    plan_faults(reports);
    return apply_faults(reports);
  }
  // The faults of each kind that found a site (FaultOptions' counts).
  const FaultOptions& placed() const { return placed_; }

 private:
  TrueState truth(int64_t t_rel_us) const { return motion_.at(static_cast<double>(t_rel_us) * 1e-6); }

  double quantise(double v) const {
    const double q = o_.sensor.quantum_px;
    return q > 0.0 ? std::round(v / q) * q : v;
  }

  // A report stamped at t_rel_us of the finger as the sensor scanned it
  // r.latency_us earlier. Each effect is added only when on, so that with
  // all of them off the numbers are exactly those of the plain model.
  // False if the finger was not on the screen at the scan (it landed
  // between the scan and the stamp): there is nothing to report, but every
  // random draw is made, so that the other reports stay as they were.
  bool measure(Report& r) {
    const SensorOptions& o = o_.sensor;
    r.latency_us = o.latency_us;
    if (o.latency_spread_us > 0.0) r.latency_us += latency_rng_.uniform(0.0, o.latency_spread_us);
    const double scan_s = (static_cast<double>(r.t_rel_us) - r.latency_us) * 1e-6;
    const TrueState s = motion_.at(scan_s);
    Point seen = s.position;
    if (tremor_.enabled()) {
      const Point shake = tremor_.at(scan_s);
      seen = {seen.x + shake.x, seen.y + shake.y};
    }
    if (o.correlated_noise_px > 0.0) {
      seen.x += correlated_x_.at(scan_s, correlated_rng_);
      seen.y += correlated_y_.at(scan_s, correlated_rng_);
    }
    if (o.drift_px > 0.0) {
      seen.x += drift_x_.at(scan_s, drift_rng_);
      seen.y += drift_y_.at(scan_s, drift_rng_);
    }
    r.x = quantise(seen.x + o.noise_px * noise_.gaussian());
    r.y = quantise(seen.y + o.noise_px * noise_.gaussian());
    return s.touching;  // drawn all the same: the reports after it keep their noise
  }

  // Reports on a jittered grid while the finger is down; one touch = 0 report
  // at each lift and at the end.
  std::vector<Report> scan() {
    std::vector<Report> out;
    const double period_us = 1e6 / o_.sensor.rate_hz;
    const double max_jitter = kJitterClipOfPeriod * period_us;
    const double end_us = motion_.duration_s() * 1e6;
    bool was_touching = false;
    Report last;
    double wandering = 0.0;  // the scan clock with period jitter
    for (int64_t n = 0;; ++n) {
      if (n > 0 && o_.sensor.period_jitter_us > 0.0) {
        wandering += period_us + std::clamp(o_.sensor.period_jitter_us * period_rng_.gaussian(), -max_jitter, max_jitter);
      }
      const double nominal = o_.sensor.period_jitter_us > 0.0 ? wandering : static_cast<double>(n) * period_us;
      if (nominal > end_us) break;
      const double jitter = n == 0 ? 0.0 : std::clamp(o_.sensor.jitter_us * timing_.gaussian(), -max_jitter, max_jitter);
      Report r;
      r.t_rel_us = static_cast<int64_t>(std::llround(nominal + jitter));
      bool touching = truth(r.t_rel_us).touching;
      if (touching) {
        r.touch = true;
        r.event = was_touching ? SampleEvent::Normal : SampleEvent::TouchDown;
        if (measure(r)) {
          out.push_back(r);
          last = r;
        } else {
          touching = was_touching;  // scanned before the finger landed: it lands in a later report
        }
      } else if (was_touching) {
        r.x = last.x;
        r.y = last.y;
        r.event = SampleEvent::LiftReport;
        out.push_back(r);
      }
      was_touching = touching;
    }
    if (was_touching) {
      Report r = last;
      r.t_rel_us = last.t_rel_us + static_cast<int64_t>(std::llround(period_us));
      r.touch = false;
      r.event = SampleEvent::LiftReport;
      out.push_back(r);
    }
    return out;
  }

  // Picks `count` sites, each a run of 1..max_run ordinary reports with 8
  // ordinary reports on either side that no other site uses, so that each
  // fault is seen on its own, away from touch-downs and lifts.
  // Returns how many found a site.
  int pick(const std::vector<Report>& reports, int count, Plan plan, int max_run) {
    const int n = static_cast<int>(reports.size());
    int placed = 0;
    for (int attempts = 0; placed < count && attempts < 1000 * (count + 1); ++attempts) {
      const int run = faults_.integer(1, max_run);
      const int i = faults_.integer(0, std::max(0, n - 1));
      const int lo = i - 8, hi = i + run + 8;
      if (lo < 0 || hi >= n) continue;
      bool free = true;
      for (int k = lo; k <= hi && free; ++k) {
        const Report& r = reports[static_cast<size_t>(k)];
        free = !taken_[static_cast<size_t>(k)] && r.touch && r.event == SampleEvent::Normal;
      }
      if (!free) continue;
      for (int k = lo; k <= hi; ++k) taken_[static_cast<size_t>(k)] = true;
      for (int k = i; k < i + run; ++k) plans_[static_cast<size_t>(k)] = plan;
      ++placed;
    }
    return placed;
  }

  void plan_faults(const std::vector<Report>& reports) {
    plans_.assign(reports.size(), Plan::None);
    taken_.assign(reports.size(), false);
    const FaultOptions& f = o_.faults;
    placed_ = f;
    placed_.missing = pick(reports, f.missing, Plan::Missing, 6);
    placed_.late = pick(reports, f.late, Plan::Late, 1);
    placed_.jumps = pick(reports, f.jumps, Plan::Jump, 3);
    placed_.duplicates = pick(reports, f.duplicates, Plan::Duplicate, 1);
    placed_.non_finite = pick(reports, f.non_finite, Plan::NonFinite, 1);
    placed_.off_screen = pick(reports, f.off_screen, Plan::OffScreen, 1);
  }

  std::vector<Report> apply_faults(const std::vector<Report>& in) {
    std::vector<Report> out;
    out.reserve(in.size() + static_cast<size_t>(o_.faults.duplicates));
    int duplicate_kind = 0, non_finite_kind = 0, off_screen_kind = 0;
    bool after_gap = false;
    int64_t overwritten_until = std::numeric_limits<int64_t>::min();
    Point second_finger;
    bool in_jump = false;
    for (size_t i = 0; i < in.size(); ++i) {
      Report r = in[i];
      const Plan plan = plans_[i];
      if (plan != Plan::Jump) in_jump = false;
      if (plan == Plan::Missing) {
        after_gap = true;
        continue;
      }
      if (r.t_rel_us <= overwritten_until) continue;  // superseded by a late read
      if (after_gap && r.event == SampleEvent::Normal) r.event = SampleEvent::AfterGap;
      after_gap = false;
      switch (plan) {
        case Plan::None:
        case Plan::Missing:
          break;
        case Plan::Late: {
          // Read late: the position is from the scan, the stamp from the read.
          const int late_us = faults_.integer(1000, 12000);
          r.t_rel_us += late_us;
          r.latency_us += late_us;
          r.event = SampleEvent::Late;
          overwritten_until = r.t_rel_us + 300;
          break;
        }
        case Plan::Jump: {
          if (!in_jump) {
            const TrueState s = truth(r.t_rel_us);
            do {
              second_finger = {faults_.uniform(20.0, 780.0), faults_.uniform(20.0, 460.0)};
            } while (std::hypot(second_finger.x - s.position.x, second_finger.y - s.position.y) < 150.0);
            in_jump = true;
          }
          r.x = quantise(second_finger.x + o_.sensor.noise_px * noise_.gaussian());
          r.y = quantise(second_finger.y + o_.sensor.noise_px * noise_.gaussian());
          r.event = SampleEvent::Jump;
          break;
        }
        case Plan::NonFinite: {
          static constexpr int kKinds = 5;
          switch (non_finite_kind++ % kKinds) {
            case 0: r.x = kNaN; r.event = SampleEvent::NaN; break;
            case 1: r.y = kNaN; r.event = SampleEvent::NaN; break;
            case 2: r.x = r.y = kNaN; r.event = SampleEvent::NaN; break;
            case 3: r.x = kInf; r.event = SampleEvent::Infinite; break;
            default: r.y = -kInf; r.event = SampleEvent::Infinite; break;
          }
          break;
        }
        case Plan::OffScreen: {
          switch (off_screen_kind++ % 4) {
            case 0: r.x = -300.0; break;
            case 1: r.y = 900.0; break;
            case 2: r.x = r.y = 65535.0; break;  // a 16-bit "no value"
            default: r.x = 880.0; break;         // beyond the screen plus any sane margin
          }
          r.event = SampleEvent::OffScreen;
          break;
        }
        case Plan::Duplicate:
          break;
      }
      out.push_back(r);
      if (plan == Plan::Duplicate) {
        Report extra = r;
        switch (duplicate_kind++ % 3) {
          case 0: extra.event = SampleEvent::Duplicate; break;
          case 1: extra.event = SampleEvent::SameTime; measure(extra); break;
          default:
            extra.event = SampleEvent::Earlier;
            extra.t_rel_us = r.t_rel_us - faults_.integer(500, 3000);
            measure(extra);
            break;
        }
        out.push_back(extra);
      }
    }
    return out;
  }

  const Motion& motion_;
  const Tremor& tremor_;
  const TraceOptions& o_;
  Random timing_, noise_, faults_;
  Random latency_rng_, period_rng_, correlated_rng_, drift_rng_;
  GaussMarkov correlated_x_, correlated_y_, drift_x_, drift_y_;
  std::vector<Plan> plans_;
  std::vector<bool> taken_;
  FaultOptions placed_;
};

// Motion time (s) at which the 32-bit clock should wrap: between two reports
// while the finger moves fast (so both touch: a stroke ends at rest before a
// lift), as near the middle as possible.
int64_t wrap_point_us(const Motion& motion, const std::vector<Report>& reports) {
  const size_t n = reports.size();
  for (size_t step = 0; step < n; ++step) {
    for (int sign : {1, -1}) {
      const int64_t i = static_cast<int64_t>(n / 2) + sign * static_cast<int64_t>(step);
      if (i < 0 || i + 1 >= static_cast<int64_t>(n)) continue;
      const Report& a = reports[static_cast<size_t>(i)];
      const Report& b = reports[static_cast<size_t>(i) + 1];
      const int64_t mid = (a.t_rel_us + b.t_rel_us) / 2;
      const TrueState s = motion.at(static_cast<double>(mid) * 1e-6);
      if (std::hypot(s.velocity.x, s.velocity.y) > 200.0) return mid;
    }
  }
  return n > 0 ? reports[n / 2].t_rel_us : 0;
}

}  // namespace

const char* to_string(SampleEvent e) {
  switch (e) {
    case SampleEvent::Normal: return "-";
    case SampleEvent::TouchDown: return "touch-down";
    case SampleEvent::LiftReport: return "lift-off";
    case SampleEvent::AfterGap: return "after-gap";
    case SampleEvent::Late: return "late";
    case SampleEvent::Jump: return "jump";
    case SampleEvent::Duplicate: return "duplicate";
    case SampleEvent::SameTime: return "same-time";
    case SampleEvent::Earlier: return "earlier";
    case SampleEvent::NaN: return "nan";
    case SampleEvent::Infinite: return "infinite";
    case SampleEvent::OffScreen: return "off-screen";
    case SampleEvent::kCount: break;
  }
  return "?";
}

TrueState GeneratedTrace::truth_at(uint64_t t_us) const {
  const double rel = static_cast<double>(static_cast<int64_t>(t_us - start_us));
  return motion.at(rel * 1e-6);
}

Point GeneratedTrace::tremor_at(uint64_t t_us) const {
  const double rel = static_cast<double>(static_cast<int64_t>(t_us - start_us));
  return tremor.at(rel * 1e-6);
}

GeneratedTrace generate_trace(const TraceOptions& options) {
  GeneratedTrace trace;
  trace.motion = plan_motion(options.motion, options.seed);
  if (options.tremor.amplitude_px > 0.0) {
    Random tremor_rng(options.seed, Stream::Tremor);
    trace.tremor = Tremor(options.tremor, tremor_rng);
  }
  SensorSimulator sensor(trace.motion, trace.tremor, options);
  const std::vector<Report> reports = sensor.run();
  trace.faults_placed = sensor.placed();

  trace.start_us = options.faults.start_us;
  if (options.faults.wrap) trace.start_us = kClockWrap - static_cast<uint64_t>(wrap_point_us(trace.motion, reports));

  trace.samples.reserve(reports.size());
  for (const Report& r : reports) {
    TraceSample s;
    s.t_us = trace.start_us + static_cast<uint64_t>(r.t_rel_us);
    s.x = r.x;
    s.y = r.y;
    s.touch = r.touch;
    s.event = r.event;
    s.latency_us = r.latency_us;
    const TrueState truth = trace.motion.at(static_cast<double>(r.t_rel_us) * 1e-6);
    // A touch = 0 report has no finger to be true about (the last one comes
    // after the motion ends).
    const bool down = truth.touching && s.touch;
    s.x_true = down ? truth.position.x : kNaN;
    s.y_true = down ? truth.position.y : kNaN;
    trace.samples.push_back(s);
    ++trace.events[static_cast<int>(s.event)];
  }
  return trace;
}

}  // namespace ff::tracegen
