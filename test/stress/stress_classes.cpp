#include "stress_classes.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <memory>

#include "frictionfield/core/scenes.hpp"
#include "stress_random.hpp"
#include "stress_run.hpp"
#include "stress_scenes.hpp"
#include "stress_traces.hpp"

namespace ff::stress {

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

uint64_t name_hash(const char* s) {
  uint64_t h = 1469598103934665603ull;
  for (; *s != '\0'; ++s) h = (h ^ static_cast<unsigned char>(*s)) * 1099511628211ull;
  return h;
}

// One case: the condition, the timeline with bad input (dirty) and without
// (clean), and what to compare.
struct Case {
  RunConfig config;
  std::vector<Report> dirty, clean;
  std::vector<TickTime> dirty_ticks, clean_ticks;
  uint64_t episode_end = 0;    // bad input stops here (real time)
  bool compare_clean = true;   // recovery against the clean run
  double rendering_bound = kRenderingBound;
  // Class-specific check: a failure message or empty; may set `measure`.
  std::function<std::string(const RunResult& dirty, const RunResult& clean, double& measure)> extra;
};

// A random clean trace: about `seconds` of motion starting at a random point
// of the 32-bit clock (so some wrap), ticks over its whole length.
struct Base {
  Motion motion{0, {}};
  std::vector<Report> reports;
  std::vector<TickTime> ticks;
  uint64_t start = 0;
  SensorStyle style;
};

Base base_trace(Rng& rng, double seconds, bool lifts) {
  Base b;
  b.start = (rng.next() & 0xffffffffu) + 1000000u;
  b.motion = random_motion(rng, b.start, seconds, lifts);
  b.style = random_sensor(rng);
  b.reports = sense(b.motion, b.style, rng);
  b.ticks = regular_ticks(b.start, b.motion.end() + 300000);  // time-outs play out
  return b;
}

Case clean_case(Rng& rng, double seconds, bool lifts, RunConfig config) {
  Base b = base_trace(rng, seconds, lifts);
  Case c;
  c.config = config;
  c.clean = b.reports;
  c.dirty = b.reports;
  c.clean_ticks = b.ticks;
  c.dirty_ticks = b.ticks;
  return c;
}

// Garbage in [w0, w1): after each clean report, with probability p, a bad one
// made by `make` from it; with probability `replace` the clean one itself.
template <typename Make>
void corrupt(Case& c, Rng& rng, uint64_t w0, uint64_t w1, double p, double replace, Make make) {
  std::vector<Report> out;
  for (const Report& r : c.clean) {
    if (r.at < w0 || r.at >= w1) {
      out.push_back(r);
      continue;
    }
    if (rng.chance(replace)) {
      Report bad = make(rng, r);
      bad.at = r.at;
      out.push_back(bad);
    } else {
      out.push_back(r);
    }
    if (rng.chance(p)) {
      Report bad = make(rng, r);
      bad.at = r.at + static_cast<uint64_t>(rng.integer(0, 4000));
      out.push_back(bad);
    }
  }
  std::stable_sort(out.begin(), out.end(), [](const Report& a, const Report& b) { return a.at < b.at; });
  c.dirty = out;
  c.episode_end = w1 + 5000;
}

// The usual shape: 1 s clean, an episode of bad input, >= 2.5 s clean.
struct Episode {
  uint64_t w0, w1;
};
Case episode_case(Rng& rng, double episode_s, Episode& e, bool lifts = true) {
  Case c = clean_case(rng, 1.0 + episode_s + 2.5, lifts, random_config(rng));
  e.w0 = c.clean_ticks.front().at + 1000000;
  e.w1 = e.w0 + static_cast<uint64_t>(episode_s * 1e6);
  return c;
}

float pick_float(Rng& rng, std::initializer_list<float> values) {
  return *(values.begin() + rng.integer(0, static_cast<int>(values.size()) - 1));
}

// Runs `cases` cases of one class: invariants at every tick, the same input
// twice bit for bit, recovery against the clean run, the class's own check.
ClassResult run_cases(const char* name, uint64_t base, int cases, Case (*make)(Rng&), const char* measure_label = nullptr,
                      int64_t recovery_bound = kRecoveryBoundTicks) {
  ClassResult res;
  res.name = name;
  double measure_max = 0.0;
  for (int i = 0; i < cases; ++i) {
    const uint64_t seed = base + static_cast<uint64_t>(i);
    Rng rng(seed ^ name_hash(name));
    Case c = make(rng);
    std::string failure;
    InvariantChecker check(c.config, c.rendering_bound);
    const RunResult a = run_pipeline(c.config, c.dirty, c.dirty_ticks, &check);
    res.ticks += check.ticks;
    res.worst_rendering = std::max(res.worst_rendering, check.worst_rendering);
    res.worst_table = std::max(res.worst_table, check.worst_table);
    res.worst_max_gradient_error = std::max(res.worst_max_gradient_error, check.max_gradient_error);
    if (a.status != PrepareStatus::Ok) failure = std::string("set_condition refused: ") + to_string(a.status);
    if (failure.empty() && check.violations > 0) failure = check.first_violation;
    if (failure.empty()) {
      const RunResult again = run_pipeline(c.config, c.dirty, c.dirty_ticks);
      const std::string diff = bitwise_difference(a.ticks, again.ticks);
      if (!diff.empty()) failure = "the same input gave a different output: " + diff;
    }
    RunResult b;
    if (c.compare_clean) {
      b = run_pipeline(c.config, c.clean, c.clean_ticks);
      if (failure.empty()) {
        std::string last;
        const Estimator e = c.config.tracker.estimator;  // the fade is the Kalman estimators'
        const bool fades = c.config.tracker.moving_sigmas > 0.0f && (e == Estimator::Kalman || e == Estimator::SplitKalman);
        // Judged on the tracker's filters, stroke ends not predicted: a bad
        // report may move a later predicted end by a refinement or drop one
        // (the predictor remembers a stroke; it resynchronises at the next
        // rest, stroke_end_predictor_test), which differs from the clean run
        // for a few ms there but harms nothing.
        RunConfig filters_only = c.config;
        filters_only.tracker.stroke_end_widening = 1.0f;
        const RunResult dirty = run_pipeline(filters_only, c.dirty, c.dirty_ticks);
        const RunResult clean = run_pipeline(filters_only, c.clean, c.clean_ticks);
        const int64_t rec =
            recovery_ticks(dirty.ticks, clean.ticks, c.episode_end, 0.5, kRecoveryAmplitudeTolerance, &last, fades);
        if (rec < 0 || rec > recovery_bound) {
          failure = (rec < 0 ? "did not recover: output still differs from the clean run at the end"
                             : "recovered only after " + std::to_string(rec) + " ticks") + std::string("; last difference ") + last;
        }
        if (rec > res.worst_recovery) res.worst_recovery = rec;
        if (rec < 0) res.worst_recovery = std::numeric_limits<int64_t>::max();
      }
    }
    if (failure.empty() && c.extra) {
      double m = 0.0;
      failure = c.extra(a, b, m);
      measure_max = std::max(measure_max, m);
    }
    ++res.cases;
    if (!failure.empty()) {
      if (res.failures++ == 0) {
        char what[96];
        std::snprintf(what, sizeof what, " (tracker %s, rendering %d, evaluation %d, %d terms, strength %g)",
                      to_string(c.config.tracker.estimator), static_cast<int>(c.config.condition.scene.rendering),
                      static_cast<int>(c.config.condition.scene.evaluation), c.config.condition.scene.element_count,
                      static_cast<double>(c.config.condition.amplitude.strength));
        res.first_failure = reproduce_hint(seed, name) + ": " + failure + what;
      }
    }
  }
  if (measure_label != nullptr) {
    char buf[120];
    std::snprintf(buf, sizeof buf, "%s %.6g", measure_label, measure_max);
    res.note = buf;
  }
  return res;
}

// ---------------------------------------------------------------------------
// The classes.

// Arguments that draw from the generator are drawn one statement at a time:
// their order inside one call is unspecified.
Case make_random(Rng& rng) {
  const double seconds = rng.uniform(1.0, 4.0);
  return clean_case(rng, seconds, true, random_config(rng));
}

Case make_nonfinite(Rng& rng) {
  Episode e;
  Case c = episode_case(rng, rng.uniform(0.05, 1.0), e);
  corrupt(c, rng, e.w0, e.w1, 0.5, 0.3, [](Rng& g, Report r) {
    const float bad = pick_float(g, {kNaN, -kNaN, kInf, -kInf});
    const int which = g.integer(0, 2);
    if (which != 1) r.s.x = bad;
    if (which != 0) r.s.y = pick_float(g, {kNaN, kInf, -kInf, bad});
    r.s.touch = true;
    return r;
  });
  return c;
}

// The report, touching, with the value as its x, its y or both (drawn).
Report touching_at(Rng& rng, Report r, float value) {
  const int which = rng.integer(0, 2);
  if (which != 1) r.s.x = value;
  if (which != 0) r.s.y = value;
  r.s.touch = true;
  return r;
}

Case make_subnormal(Rng& rng) {
  Episode e;
  Case c = episode_case(rng, rng.uniform(0.02, 0.3), e);
  corrupt(c, rng, e.w0, e.w1, 0.3, 0.1, [](Rng& g, Report r) {
    const float tiny = pick_float(g, {1e-40f, -1e-40f, FLT_TRUE_MIN, -FLT_TRUE_MIN, -0.0f, FLT_MIN, 1e-30f});
    return touching_at(g, r, tiny);
  });
  return c;
}

Case make_huge(Rng& rng) {
  Episode e;
  Case c = episode_case(rng, rng.uniform(0.05, 1.0), e);
  corrupt(c, rng, e.w0, e.w1, 0.5, 0.3, [](Rng& g, Report r) {
    const float big = pick_float(g, {1e6f, -1e6f, 1e30f, -1e30f, FLT_MAX, -FLT_MAX, 65535.0f, -841.0f});
    return touching_at(g, r, big);
  });
  return c;
}

Case make_time_steps(Rng& rng) {
  Episode e;
  Case c = episode_case(rng, rng.uniform(0.05, 1.0), e);
  uint32_t last = 0;
  corrupt(c, rng, e.w0, e.w1, 0.5, 0.2, [&last](Rng& g, Report r) {
    switch (g.integer(0, 4)) {
      case 0: break;                                                        // duplicate stamp
      case 1: r.s.t_us -= static_cast<uint32_t>(g.integer(1, 400)); break;   // slightly earlier
      case 2: r.s.t_us -= static_cast<uint32_t>(g.integer(1000, 2000000000)); break;  // far earlier
      case 3: r.s.t_us = last; break;                                        // an old stamp again
      default: r.s.t_us += static_cast<uint32_t>(g.integer(1, 10000)); break;  // up to 10 ms early
    }
    r.s.x += static_cast<float>(g.uniform(-3.0, 3.0));
    last = r.s.t_us;
    return r;
  });
  return c;
}

Case make_future_stamps(Rng& rng) {
  Episode e;
  Case c = episode_case(rng, 0.0, e, false);
  corrupt(c, rng, e.w0, e.w0 + 6000, 1.0, 0.0, [](Rng& g, Report r) {
    const uint32_t ahead[] = {100000u, 1000000u, 10000000u, 1000000000u, 0x7fffffffu};
    r.s.t_us += g.pick(ahead);
    return r;
  });
  return c;
}

Case make_clock_wrap(Rng& rng) {
  // The same motion twice: once crossing 2^32 mid-stroke, once far from it.
  RunConfig config = random_config(rng);
  const double seconds = rng.uniform(2.0, 4.0);
  const uint64_t wrap_start = (uint64_t{1} << 32) - static_cast<uint64_t>(rng.uniform(0.2, seconds - 0.2) * 1e6);
  const uint64_t plain_start = 1000000u + (wrap_start & 0xfffu);
  Motion m = random_motion(rng, wrap_start, seconds, rng.chance(0.3));
  const SensorStyle style = random_sensor(rng);
  Case c;
  c.config = config;
  c.dirty = sense(m, style, rng);
  c.dirty_ticks = regular_ticks(wrap_start, m.end() + 300000);
  c.clean = c.dirty;
  c.clean_ticks = c.dirty_ticks;
  for (Report& r : c.clean) {
    r.at = r.at - wrap_start + plain_start;
    r.s.t_us = static_cast<uint32_t>(r.at);
  }
  for (TickTime& t : c.clean_ticks) {
    t.at = t.at - wrap_start + plain_start;
    t.now = static_cast<uint32_t>(t.at);
  }
  c.compare_clean = false;
  c.extra = [c](const RunResult& a, const RunResult&, double&) {
    const RunResult plain = run_pipeline(c.config, c.clean, c.clean_ticks);
    const std::string diff = bitwise_difference(a.ticks, plain.ticks, true);
    return diff.empty() ? diff : "wrapping clock changed the output: " + diff;
  };
  return c;
}

Case make_mailbox(Rng& rng) {
  Episode e;
  Case c = episode_case(rng, rng.uniform(0.05, 0.5), e);
  // A backlog: 9..64 reports delivered at once between two ticks, stamps
  // increasing by 1..200 us, positions on the finger's track.
  c.dirty = c.clean;
  for (uint64_t at = e.w0; at < e.w1; at += static_cast<uint64_t>(rng.integer(2000, 50000))) {
    const int n = rng.integer(9, 64);
    const Report* near = &c.clean.front();
    for (const Report& r : c.clean) {
      if (r.at <= at && r.s.touch) near = &r;
    }
    Report r = *near;
    for (int k = 0; k < n; ++k) {
      r.at = at;
      r.s.t_us += static_cast<uint32_t>(rng.integer(1, 200));
      insert_report(c.dirty, r);
    }
  }
  c.episode_end = e.w1 + 5000;
  // Expected refusals, counted from the timeline: a post finds 8 reports
  // waiting, and each tick takes one.
  uint64_t expected = 0;
  size_t next = 0;
  uint64_t waiting = 0;
  for (const TickTime& t : c.dirty_ticks) {
    for (; next < c.dirty.size() && c.dirty[next].at <= t.at; ++next) {
      if (waiting == 8) ++expected;
      else ++waiting;
    }
    if (waiting > 0) --waiting;
  }
  c.extra = [expected](const RunResult& a, const RunResult&, double& measure) {
    measure = static_cast<double>(a.failed_posts);
    if (a.failed_posts != expected) return std::string("refused posts ") + std::to_string(a.failed_posts) + ", expected " + std::to_string(expected);
    if (a.faults[Fault::MailboxOverflow] != expected) return std::string("MailboxOverflow counted ") + std::to_string(a.faults[Fault::MailboxOverflow]) + ", expected " + std::to_string(expected);
    return std::string();
  };
  return c;
}

Case make_silence(Rng& rng) {
  Episode e;
  const double gap = rng.uniform(0.3, 5.0);
  Case c = episode_case(rng, gap, e, false);
  c.dirty.clear();
  for (const Report& r : c.clean) {
    if (r.at < e.w0 || r.at >= e.w1) c.dirty.push_back(r);
  }
  c.episode_end = e.w1;
  uint64_t last_before = c.clean.front().at;
  for (const Report& r : c.dirty) {
    if (r.at < e.w0) last_before = r.at;
  }
  const uint32_t timeout = c.config.tracker.stale_timeout_us;
  c.extra = [last_before, e, timeout](const RunResult& a, const RunResult&, double&) {
    // One tick after the stale timeout the finger is gone: the plate idles.
    for (const Tick& t : a.ticks) {
      if (t.at > last_before + timeout + 500 && t.at < e.w1 && t.out.present) {
        return "finger still present " + std::to_string(t.at - last_before) + " us after the last report";
      }
    }
    return std::string();
  };
  return c;
}

Case make_long_rest(Rng& rng) {
  // Resting for 1..3 minutes without noise, then a 300 px/s stroke.
  RunConfig config = random_config(rng, [](Rng& g) { return scenes::heightmap(g.chance(0.5) ? Target::Top : Target::Bottom); });
  const uint64_t start = rng.next() & 0xffffffffu;
  const reference::DVec p{rng.uniform(200.0, 600.0), rng.uniform(150.0, 330.0)};
  Motion m(start, p);
  const double rest_s = rng.uniform(60.0, 180.0);
  m.rest(rest_s);
  const double angle = rng.uniform(0.0, 6.283185307179586);
  const reference::DVec dir{std::cos(angle), std::sin(angle)};
  m.stroke({p.x + 150.0 * dir.x, p.y + 150.0 * dir.y}, 0.75);
  SensorStyle style;
  style.noise_px = 0.0;
  style.jitter_us = rng.uniform(0.0, 300.0);
  Case c;
  c.config = config;
  c.dirty = sense(m, style, rng);
  c.dirty_ticks = regular_ticks(start, m.end());
  c.compare_clean = false;
  const uint64_t move_at = start + static_cast<uint64_t>(rest_s * 1e6);
  // When the true speed first reaches 100 px/s (minimum-jerk start is slow).
  uint64_t fast_at = move_at;
  while (fast_at < m.end()) {
    const reference::DVec a = m.position(fast_at), b = m.position(fast_at + 1000);
    if (std::hypot(b.x - a.x, b.y - a.y) * 1000.0 >= 100.0) break;
    fast_at += 1000;
  }
  const uint64_t stroke_end = m.end();
  c.extra = [p, dir, move_at, fast_at, stroke_end](const RunResult& a, const RunResult&, double& measure) {
    // At the end of the rest the filter sits on the sensor's position.
    const Tick* before = nullptr;
    for (const Tick& t : a.ticks) {
      if (t.at < move_at) before = &t;
    }
    const double off = std::hypot(static_cast<double>(before->out.position.x) - static_cast<double>(static_cast<float>(p.x)),
                                  static_cast<double>(before->out.position.y) - static_cast<double>(static_cast<float>(p.y)));
    if (!(off <= 0.1)) return "after the rest the position is " + std::to_string(off) + " px from the sensor's";
    // Once the finger moves at 100 px/s, the direction follows it (within
    // 25 degrees) after at most 100 ticks and stays with it.
    int64_t late = -1, k = 0;
    for (const Tick& t : a.ticks) {
      if (t.at < fast_at || t.at + 100000 > stroke_end) continue;  // the stroke's slow end fades by design
      const double along = static_cast<double>(t.out.direction.x) * dir.x + static_cast<double>(t.out.direction.y) * dir.y;
      if (!(along > 0.9)) late = k;
      ++k;
    }
    measure = static_cast<double>(late + 1);
    if (late + 1 > 100) return "direction followed the motion only after " + std::to_string(late + 1) + " ticks";
    return std::string();
  };
  return c;
}

Case make_strength(Rng& rng) {
  const double seconds = rng.uniform(1.0, 3.0);
  Case c = clean_case(rng, seconds, true, random_config(rng));
  AmplitudeSettings& a = c.config.condition.amplitude;
  a.strength = pick_float(rng, {0.0f, -0.0f, -1.0f, -1e-30f, 1e-30f, 1.0000001f, 1.5f, 1e30f, kNaN, kInf, -kInf, 1.0f});
  if (rng.chance(0.5)) a.idle_amplitude = pick_float(rng, {-1.0f, 2.0f, kNaN, kInf, 0.25f});
  if (rng.chance(0.5)) a.s_curve = pick_float(rng, {-1.0f, 2.0f, kNaN, -kInf, 0.5f});
  if (rng.chance(0.5)) {
    a.calibration.count = static_cast<uint8_t>(rng.integer(0, 20));
    a.calibration.code[1] = pick_float(rng, {kNaN, 5000.0f, -1.0f, 0.0f, 4095.0f});
  }
  c.config.calibration_valid = a.calibration.valid();
  const float s = a.strength;
  const bool bad_strength = !(s > 0.0f && s <= 1.0f);
  const bool bad_calibration = !c.config.calibration_valid;
  c.compare_clean = false;
  c.extra = [bad_strength, bad_calibration](const RunResult& r, const RunResult&, double&) {
    if ((r.faults[Fault::BadStrength] == 1) != bad_strength) return std::string("BadStrength not counted once");
    if ((r.faults[Fault::BadCalibration] == 1) != bad_calibration) return std::string("BadCalibration not counted once");
    return std::string();
  };
  return c;
}

Case make_flat(Rng& rng) {
  SceneDefinition s;
  s.rendering = Rendering::Directional;
  const Vec2 c0{static_cast<float>(rng.uniform(0.0, 800.0)), static_cast<float>(rng.uniform(0.0, 480.0))};
  const float w = static_cast<float>(rng.log_uniform(1e-3, 1e3));
  switch (rng.integer(0, 4)) {
    case 0: break;  // no elements at all
    case 1: s.add(FieldElement::point_sink(c0, 0.0f)); s.add(FieldElement::vortex(c0, 0.0f)); break;
    case 2: s.add(FieldElement::sine_texture(100.0f, 50.0f, 0.0f, w)); break;
    case 3: s.add(FieldElement::point_sink(c0, w)); s.add(FieldElement::point_sink(c0, -w)); break;  // cancel exactly
    default: s.add(FieldElement::vortex(c0, w)); s.add(FieldElement::vortex(c0, -w)); break;
  }
  if (rng.chance(0.3)) {
    s.evaluation = Evaluation::Table;
    s.table.spacing_px = 8.0f;
  }
  RunConfig config;
  config.tracker = random_tracker(rng);
  config.condition.scene = s;
  config.condition.amplitude = random_settings(rng);
  config.calibration_valid = config.condition.amplitude.calibration.valid();
  const double seconds = rng.uniform(1.0, 3.0);
  Case c = clean_case(rng, seconds, true, config);
  c.compare_clean = false;
  c.extra = [](const RunResult& r, const RunResult&, double&) {
    for (const Tick& t : r.ticks) {
      if (t.out.present && t.out.amplitude != 0.5f) return "a flat field rendered " + std::to_string(t.out.amplitude) + ", not 0.5";
    }
    return std::string();
  };
  return c;
}

Case make_singular(Rng& rng) {
  // The finger stops exactly on a singular point, rests, and leaves through it.
  const float px = static_cast<float>(rng.integer(50, 750));
  const float half = rng.chance(0.5) ? 0.0f : 0.5f;
  const Vec2 p{px + half, static_cast<float>(rng.integer(50, 430))};
  SceneDefinition s;
  s.rendering = Rendering::Directional;
  switch (rng.integer(0, 4)) {
    case 0: s.add(FieldElement::point_sink(p)); break;
    case 1: s.add(FieldElement::vortex(p)); break;
    case 2: s.add(FieldElement::saddle(p)); break;
    case 3: s.add(FieldElement::point_sink(p)); s.add(FieldElement::vortex(p, 0.01f)); s.add(FieldElement::saddle(p, 0.01f)); break;
    default: s.add(FieldElement::path_sink(PathCurve::cubic(0.0f, 0.0f, p.y, 800.0f), 0.2f)); break;  // on u = 0
  }
  RunConfig config;
  config.tracker = random_tracker(rng);
  config.condition.scene = s;
  const uint64_t start = rng.next() & 0xffffffffu;
  const reference::DVec P{p.x, p.y};
  Motion m(start, {P.x - 100.0, P.y + rng.uniform(-40.0, 40.0)});
  m.stroke(P, rng.uniform(0.2, 0.6));
  m.rest(rng.uniform(0.2, 1.5));
  const reference::DVec away{P.x + 100.0, P.y + rng.uniform(-40.0, 40.0)};
  m.stroke(away, rng.uniform(0.2, 0.6));
  SensorStyle style;
  style.noise_px = 0.0;
  style.jitter_us = rng.uniform(0.0, 300.0);
  Case c;
  c.config = config;
  c.dirty = sense(m, style, rng);
  c.dirty_ticks = regular_ticks(start, m.end() + 100000);
  c.compare_clean = false;
  c.extra = [p, s](const RunResult& r, const RunResult&, double&) {
    // Exactly on the point of a cone, vortex or saddle there is no gradient: 0.5.
    if (s.elements[0].kind == ElementKind::PathSink) return std::string();
    for (const Tick& t : r.ticks) {
      if (t.out.present && t.out.position.x == p.x && t.out.position.y == p.y && t.out.amplitude != 0.5f) {
        return "on the singular point the amplitude is " + std::to_string(t.out.amplitude);
      }
    }
    return std::string();
  };
  return c;
}

float extreme_factor(Rng& rng) { return pick_float(rng, {1e-30f, 1e-25f, 1e-20f, 1e-10f, 1e10f, 1e20f, 1e25f, 1e30f}); }

Case make_extreme_weights(Rng& rng) {
  const double seconds = rng.uniform(1.0, 3.0);
  Case c = clean_case(rng, seconds, true, random_config(rng, [](Rng& g) { return random_general_scene(g, false); }));
  SceneDefinition& s = c.config.condition.scene;
  const bool mixed = rng.chance(0.5);
  const float common = extreme_factor(rng);
  for (int i = 0; i < s.element_count; ++i) s.elements[i].weight *= mixed ? extreme_factor(rng) : common;
  c.rendering_bound = std::numeric_limits<double>::infinity();  // safety only: see the scale-invariance class
  c.compare_clean = false;
  return c;
}

Case make_scale_invariance(Rng& rng) {
  // Multiplying every weight by k must not change a directional scene:
  // G / (2 max|G|) is scale-free.
  const double seconds = rng.uniform(1.0, 2.0);
  Case c = clean_case(rng, seconds, false, random_config(rng, [](Rng& g) {
    SceneDefinition s = g.chance(0.5) ? random_builtin_scene(g) : random_general_scene(g, false);
    if (s.rendering != Rendering::Directional) s = scenes::heightmap(Target::Top);
    return s;
  }));
  const float k = extreme_factor(rng);
  RunConfig unscaled = c.config;
  for (int i = 0; i < c.config.condition.scene.element_count; ++i) c.config.condition.scene.elements[i].weight *= k;
  c.rendering_bound = std::numeric_limits<double>::infinity();
  c.compare_clean = false;
  const std::vector<Report> reports = c.dirty;
  const std::vector<TickTime> ticks = c.dirty_ticks;
  c.extra = [unscaled, reports, ticks, k](const RunResult& a, const RunResult&, double& measure) {
    const RunResult b = run_pipeline(unscaled, reports, ticks);
    for (size_t i = 0; i < a.ticks.size(); ++i) {
      const double d = std::fabs(static_cast<double>(a.ticks[i].out.amplitude) - static_cast<double>(b.ticks[i].out.amplitude));
      measure = std::max(measure, d);
    }
    if (measure > 1e-3) {
      char buf[120];
      std::snprintf(buf, sizeof buf, "weights x %g change the amplitude by up to %.3g", static_cast<double>(k), measure);
      return std::string(buf);
    }
    return std::string();
  };
  return c;
}

Case make_general(Rng& rng) {
  const double seconds = rng.uniform(1.0, 3.0);
  return clean_case(rng, seconds, true, random_config(rng, [](Rng& g) { return random_general_scene(g, true); }));
}

Case make_tick_timing(Rng& rng) {
  Episode e;
  Case c = episode_case(rng, rng.uniform(0.05, 1.0), e);
  std::vector<TickTime> out;
  for (size_t i = 0; i < c.clean_ticks.size(); ++i) {
    TickTime t = c.clean_ticks[i];
    if (t.at < e.w0 || t.at >= e.w1) {
      out.push_back(t);
      continue;
    }
    const double r = rng.uniform();
    if (r < 0.15) {  // the interrupt fires twice with the same time (a stall)
      out.push_back(t);
      for (int k = rng.integer(1, 10); k > 0; --k) out.push_back(t);
    } else if (r < 0.3) {  // told a time up to 400 us early
      t.now -= static_cast<uint32_t>(rng.integer(1, 400));
      out.push_back(t);
    } else if (r < 0.35) {  // ticks missed for 1 ms .. 1 s
      const uint64_t skip_to = t.at + static_cast<uint64_t>(rng.log_uniform(1000.0, 1e6));
      while (i + 1 < c.clean_ticks.size() && c.clean_ticks[i + 1].at < skip_to) ++i;
    } else {
      out.push_back(t);
    }
  }
  c.dirty_ticks = out;
  c.episode_end = e.w1;
  return c;
}

Case make_tick_glitch(Rng& rng) {
  // One tick told a time far ahead (a corrupted timer read), then normal again.
  Episode e;
  Case c = episode_case(rng, 0.0, e, false);
  for (TickTime& t : c.dirty_ticks) {
    if (t.at >= e.w0) {
      t.now += static_cast<uint32_t>(rng.integer(1 << 30, 0x7fffffff));
      break;
    }
  }
  c.episode_end = e.w0 + 500;
  return c;
}

Case make_clock_reset(Rng& rng) {
  // The whole time base steps back by 10 ms .. 100 s mid-stroke (samples and
  // ticks alike), as after a timer re-initialisation.
  Episode e;
  Case c = episode_case(rng, 0.0, e, false);
  const uint32_t back = static_cast<uint32_t>(rng.log_uniform(1e4, 1e8));
  for (Report& r : c.dirty) {
    if (r.at >= e.w0) r.s.t_us -= back;
  }
  for (TickTime& t : c.dirty_ticks) {
    if (t.at >= e.w0) t.now -= back;
  }
  c.episode_end = e.w0;
  return c;
}

Case make_second_finger(Rng& rng) {
  Episode e;
  Case c = episode_case(rng, rng.uniform(0.05, 1.0), e);
  corrupt(c, rng, e.w0, e.w1, 0.4, 0.2, [](Rng& g, Report r) {
    if (g.chance(0.4)) {
      r.s.touch = false;  // touch flapping
    } else {
      r.s.x = static_cast<float>(g.uniform(0.0, 799.0));  // a second finger or a glitch
      r.s.y = static_cast<float>(g.uniform(0.0, 479.0));
      r.s.touch = true;
    }
    return r;
  });
  return c;
}

Case make_direction_length(Rng& rng) {
  // The thesis tracker renders v_hat = dxhat / |dxhat| at any speed; at rest
  // dxhat decays through the subnormal range, where |dxhat|^2 loses precision.
  RunConfig config = random_config(rng, [](Rng& g) { return scenes::heightmap(g.chance(0.5) ? Target::Top : Target::Middle); });
  config.tracker = TrackerConfig::thesis();
  // Derivative from the previous raw value: exactly 0 at rest, so dxhat
  // decays geometrically through every subnormal.
  config.tracker.one_euro.derivative_from = DerivativeFrom::PreviousRaw;
  const uint64_t start = rng.next() & 0xffffffffu;
  Motion m(start, {rng.uniform(200.0, 600.0), rng.uniform(150.0, 330.0)});
  for (int i = 0; i < 4; ++i) {
    const reference::DVec to{rng.uniform(100.0, 700.0), rng.uniform(50.0, 430.0)};
    m.stroke(to, rng.uniform(0.2, 0.8));
    m.rest(rng.uniform(0.5, 2.0));
  }
  SensorStyle style;
  style.noise_px = 0.0;
  Case c;
  c.config = config;
  c.dirty = sense(m, style, rng);
  c.dirty_ticks = regular_ticks(start, m.end());
  c.compare_clean = false;
  c.extra = [](const RunResult& a, const RunResult&, double& measure) {
    for (const Tick& t : a.ticks) measure = std::max(measure, static_cast<double>(length(t.out.direction)));
    if (measure > 1.0 + 1e-5) return "direction of length " + std::to_string(measure);
    return std::string();
  };
  return c;
}

Case make_max_search(Rng& rng) {
  // A short stroke over a random general directional scene; the check is the
  // core's max|G| against the double scan (4 px grid + refinement).
  const double seconds = rng.uniform(0.2, 0.5);
  Case c = clean_case(rng, seconds, false, random_config(rng, [](Rng& g) {
    SceneDefinition s = random_general_scene(g, false);
    s.rendering = Rendering::Directional;
    return s;
  }));
  c.compare_clean = false;
  const SceneDefinition scene = c.config.condition.scene;
  c.extra = [scene](const RunResult&, const RunResult&, double& measure) {
    auto plan = std::make_unique<ScenePlan>();
    // A scene too costly to prepare (a fine texture among many elements) is
    // refused: no max|G| to compare.
    if (plan->prepare(scene, nullptr, 0) == PrepareStatus::TooCostlyToPrepare) return std::string();
    const reference::ReferenceScene ref(scene);
    if (!(ref.max_gradient() > 0.0)) return std::string();
    measure = std::fabs(static_cast<double>(plan->stats().max_gradient) - ref.max_gradient()) / ref.max_gradient();
    if (measure > kMaxGradientBound) {
      char buf[120];
      std::snprintf(buf, sizeof buf, "core max|G| %.6g, double scan %.6g", static_cast<double>(plan->stats().max_gradient), ref.max_gradient());
      return std::string(buf);
    }
    return std::string();
  };
  return c;
}

#define FF_CLASS(fn, make, ...) \
  ClassResult fn(uint64_t seed, int cases) { return run_cases(#fn, seed, cases, make, ##__VA_ARGS__); }

FF_CLASS(random_scenes_and_traces, make_random)
FF_CLASS(nonfinite_coordinates, make_nonfinite)
FF_CLASS(subnormal_coordinates, make_subnormal)
FF_CLASS(huge_coordinates, make_huge)
FF_CLASS(bad_time_steps, make_time_steps)
FF_CLASS(stamps_far_ahead, make_future_stamps)
FF_CLASS(clock_wrap, make_clock_wrap)
FF_CLASS(mailbox_overflow, make_mailbox, "most refused posts in a case:")
FF_CLASS(sensor_silence, make_silence)
FF_CLASS(long_rest_then_move, make_long_rest, "most ticks from 100 px/s until the direction follows:")
FF_CLASS(bad_strength_and_settings, make_strength)
FF_CLASS(flat_fields, make_flat)
FF_CLASS(singular_points, make_singular)
FF_CLASS(extreme_weights_safety, make_extreme_weights)
FF_CLASS(extreme_weights_scale_invariance, make_scale_invariance, "largest amplitude change:")
FF_CLASS(general_scenes, make_general)
FF_CLASS(tick_stalls_and_skips, make_tick_timing)
FF_CLASS(tick_time_glitch_ahead, make_tick_glitch)
FF_CLASS(clock_set_back, make_clock_reset)
FF_CLASS(second_finger_and_flapping, make_second_finger)
FF_CLASS(direction_unit_length, make_direction_length, "longest direction:")
FF_CLASS(max_gradient_search, make_max_search, "largest relative max|G| error:")

}  // namespace

std::string reproduce_hint(uint64_t seed, const char* class_name) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "[%s seed %llu: FF_STRESS_SEED=%llu FF_STRESS_CASES=1]", class_name,
                static_cast<unsigned long long>(seed), static_cast<unsigned long long>(seed));
  return buf;
}

const std::vector<StressClass>& stress_classes() {
  static const std::vector<StressClass> classes = {
      {"random_scenes_and_traces", "random scenes, settings, trackers and finger traces (strokes, rests, lifts, noise, jitter)", false, random_scenes_and_traces},
      {"nonfinite_coordinates", "NaN and +-inf in x, y or both, added and replacing reports", false, nonfinite_coordinates},
      {"subnormal_coordinates", "subnormal, -0 and FLT_MIN coordinates", false, subnormal_coordinates},
      {"huge_coordinates", "coordinates of +-1e6, +-1e30, +-FLT_MAX, 65535", false, huge_coordinates},
      {"bad_time_steps", "duplicate, earlier (up to 2e9 us), repeated and up to 10 ms early stamps", false, bad_time_steps},
      {"stamps_far_ahead", "one report stamped 0.1 s .. 2^31 us ahead of the clock", false, stamps_far_ahead},
      {"clock_wrap", "the 32-bit us clock wraps mid-trace: bit-identical to the same trace far from the wrap", false, clock_wrap},
      {"mailbox_overflow", "backlogs of 9..64 reports between two ticks", false, mailbox_overflow},
      {"sensor_silence", "no reports for 0.3..5 s with the finger down", false, sensor_silence},
      {"long_rest_then_move", "finger resting 1..3 min (no noise), then a 300 px/s stroke", false, long_rest_then_move},
      {"bad_strength_and_settings", "strength 0, -0, negative, above 1, NaN, +-inf; bad idle amplitude, S-curve, calibration", false, bad_strength_and_settings},
      {"flat_fields", "directional scenes with max|G| = 0 (no terms, zero weights, terms that cancel)", false, flat_fields},
      {"singular_points", "finger stopping exactly on a cone apex, vortex or saddle centre, a valley's centre line", false, singular_points},
      {"extreme_weights_safety", "weights scaled by 1e-30 .. 1e30, common or per element", false, extreme_weights_safety},
      {"extreme_weights_scale_invariance", "weights x 1e-30 .. 1e30 render like weight 1 (G / 2 max|G| is scale-free)", false, extreme_weights_scale_invariance},
      {"general_scenes", "1..8 terms of every kind, either sign, closed form and tables (int16/float, gradient/height)", false, general_scenes},
      {"tick_stalls_and_skips", "tick time repeated (stall), up to 400 us early, ticks skipped for 1 ms .. 1 s", false, tick_stalls_and_skips},
      {"tick_time_glitch_ahead", "one tick told a time 2^30 .. 2^31 us ahead, then normal", false, tick_time_glitch_ahead},
      {"clock_set_back", "the time base steps back 10 ms .. 100 s mid-stroke (reports and ticks)", false, clock_set_back},
      {"second_finger_and_flapping", "reports from a second finger anywhere on screen, touch flapping 1/0", false, second_finger_and_flapping},
      {"max_gradient_search", "max|G| of random general scenes (steep narrow polyline segments, textures) against a double scan", false, max_gradient_search},
      {"direction_unit_length", "thesis tracker (raw derivative) resting without noise: |v_hat| = 1 as dxhat decays through subnormals", false, direction_unit_length},
  };
  return classes;
}

const StressClass* find_class(const std::string& name) {
  for (const StressClass& c : stress_classes()) {
    if (name == c.name) return &c;
  }
  return nullptr;
}

}  // namespace ff::stress
