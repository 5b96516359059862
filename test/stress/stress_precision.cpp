#include "stress_precision.hpp"

#include <cmath>
#include <cstdio>
#include <memory>

#include "frictionfield/core/scene_plan.hpp"
#include "frictionfield/core/scenes.hpp"
#include "frictionfield/host/scene_file.hpp"
#include "support/reference/reference_amplitude.hpp"
#include "support/reference/reference_scene.hpp"
#include "support/reference/reference_tracker.hpp"
#include "stress_random.hpp"
#include "stress_run.hpp"
#include "stress_scenes.hpp"
#include "stress_traces.hpp"

namespace ff::stress {

RenderingPrecision rendering_precision(uint64_t seed, int scenes_n, int points) {
  Rng rng(seed ^ 0x9e11);
  auto plan = std::make_unique<ScenePlan>();
  RenderingPrecision r;
  for (int i = 0; i < scenes_n; ++i) {
    const bool builtin = i % 2 != 0;
    const SceneDefinition s = builtin ? random_builtin_scene(rng) : random_general_scene(rng, false);
    if (plan->prepare(s, nullptr, 0) != PrepareStatus::Ok) continue;
    ++r.scenes;
    reference::ReferenceScene ref(s);
    if (s.rendering == Rendering::Directional && ref.max_gradient() > 0.0) {
      const double core_max = plan->stats().max_gradient;
      const double rel = std::fabs(core_max - ref.max_gradient()) / ref.max_gradient();
      double& worst = builtin ? r.worst_max_builtin : r.worst_max_general;
      if (!builtin && rel > worst) {
        char buf[96];
        std::snprintf(buf, sizeof buf, "core %.7g, double %.7g:\n", core_max, ref.max_gradient());
        r.worst_max_scene = buf + host::format_scene_text(s);
      }
      worst = std::fmax(worst, rel);
      ref.use_max_gradient(core_max);  // the float32 evaluation apart from the search
    }
    for (int k = 0; k < points; ++k) {
      const Vec2 p{static_cast<float>(rng.uniform(0.0, 799.0)), static_cast<float>(rng.uniform(0.0, 479.0))};
      const double angle = rng.uniform(0.0, 6.283185307179586);
      const Vec2 d{static_cast<float>(std::cos(angle)), static_cast<float>(std::sin(angle))};
      const double a = plan->amplitude(p, d);
      r.worst_amplitude = std::fmax(r.worst_amplitude, std::fabs(a - ref.raw_amplitude(p.x, p.y, d.x, d.y)));
      ++r.evaluations;
    }
  }
  return r;
}

ChainPrecision thesis_chain_precision(uint64_t seed, int traces) {
  Rng rng(seed ^ 0x7e515);
  ChainPrecision r;
  for (int c = 0; c < traces; ++c) {
    const Target targets[] = {Target::Top, Target::Middle, Target::Bottom};
    const SceneDefinition scene = scenes::heightmap(rng.pick(targets));
    const uint64_t start = rng.next() & 0xffffffffu;
    Motion m(start, {rng.uniform(100.0, 700.0), rng.uniform(100.0, 380.0)});
    while (m.end() < start + 3000000) {
      const reference::DVec to{rng.uniform(60.0, 740.0), rng.uniform(60.0, 420.0)};
      m.stroke(to, rng.uniform(0.3, 1.0));
      if (rng.chance(0.2)) m.rest(rng.uniform(0.02, 0.2));
    }
    SensorStyle style = random_sensor(rng);
    style.noise_px = std::fmin(style.noise_px, 1.0);  // stays on screen: no clamping to compare
    const std::vector<Report> reports = sense(m, style, rng);
    RunConfig config;
    config.tracker = TrackerConfig::thesis();
    config.condition.scene = scene;
    const RunResult run = run_pipeline(config, reports, regular_ticks(start, m.end()));
    const reference::ReferenceScene ref(scene);
    reference::ReferenceThesisTracker tracker;
    size_t next = 0;
    ++r.traces;
    for (const Tick& t : run.ticks) {
      while (next < reports.size() && reports[next].at <= t.at) tracker.on_sample(reports[next++].s);
      if (!tracker.present()) continue;  // the filter starts with the first report
      reference::DVec p, d;
      tracker.on_tick(p, d);
      ++r.ticks;
      r.worst_position = std::fmax(r.worst_position, std::hypot(p.x - static_cast<double>(t.out.position.x),
                                                               p.y - static_cast<double>(t.out.position.y)));
      // dxhat / |dxhat| is ill-conditioned near rest: amplitudes are compared
      // while the filtered speed is at least 50 px/s.
      if (tracker.filtered_speed() < 50.0) continue;
      ++r.moving_ticks;
      const reference::DVec g = ref.field(p.x, p.y);
      const double a = std::fmin(1.0, std::fmax(0.0, 0.5 - 0.5 * (d.x * g.x + d.y * g.y) / ref.max_gradient()));
      r.worst_amplitude = std::fmax(r.worst_amplitude, std::fabs(a - static_cast<double>(t.out.amplitude)));
    }
  }
  return r;
}

}  // namespace ff::stress
