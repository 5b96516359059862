#include "stress_scenes.hpp"

#include <memory>

#include "frictionfield/core/scenes.hpp"

namespace ff::stress {

namespace {

float f(double v) { return static_cast<float>(v); }

PathCurve random_curve(Rng& rng) {
  // One draw per statement: the order of a call's arguments is unspecified.
  const int kind = rng.integer(0, 2);
  if (kind == 0) {
    const float rise = f(rng.uniform(-300.0, 300.0));
    const float x0 = f(rng.uniform(0.0, 400.0));
    const float y0 = f(rng.uniform(0.0, 480.0));
    const float length = f(rng.uniform(50.0, 800.0));
    return PathCurve::cubic(rise, x0, y0, length);
  }
  if (kind == 1) {
    const float y0 = f(rng.uniform(0.0, 480.0));
    const float amplitude = f(rng.uniform(0.0, 150.0));
    const float wavelength = f(rng.uniform(40.0, 800.0));
    const float x0 = f(rng.uniform(-400.0, 400.0));
    return PathCurve::sine(y0, amplitude, wavelength, x0);
  }
  Vec2 pts[kMaxPolylinePoints];
  const int n = rng.integer(2, kMaxPolylinePoints);
  float x = f(rng.uniform(-50.0, 300.0));
  for (int i = 0; i < n; ++i) {
    pts[i] = {x, f(rng.uniform(0.0, 480.0))};
    x += f(rng.uniform(5.0, 120.0));
  }
  return PathCurve::polyline(pts, n);
}

FieldElement random_element(Rng& rng, bool allow_vortex) {
  const double sign = rng.chance(0.3) ? -1.0 : 1.0;
  const float w = f(sign * rng.log_uniform(1e-2, 1e2));
  const Vec2 c{f(rng.uniform(-100.0, 900.0)), f(rng.uniform(-100.0, 580.0))};
  switch (rng.integer(0, allow_vortex ? 5 : 4)) {
    case 0: {
      FieldElement e = FieldElement::point_sink(c, w);
      e.point.radius = f(rng.uniform(0.0, 60.0));
      e.point.feather = f(rng.uniform(1.0, 60.0));
      return e;
    }
    case 1: {
      const PathCurve curve = random_curve(rng);
      FieldElement e = FieldElement::path_sink(curve, f(rng.log_uniform(0.02, 2.0)), w);
      e.valley.band_half_width = f(rng.uniform(0.0, 40.0));
      e.valley.band_feather = f(rng.uniform(1.0, 40.0));
      return e;
    }
    case 2: {
      TunnelParams t;
      t.x_start = f(rng.uniform(0.0, 400.0));
      t.length = f(rng.uniform(50.0, 600.0));
      t.width_start = f(rng.uniform(5.0, 100.0));
      t.width_end = f(rng.uniform(5.0, 100.0));
      t.scale = f(rng.log_uniform(0.5, 10.0));
      t.y_centre = f(rng.uniform(100.0, 380.0));
      return FieldElement::tunnel_valley(t, w);
    }
    case 3:
      return FieldElement::saddle(c, w * 0.01f);  // |G| grows with distance: keep it comparable
    case 4:
    {
      const float lx = f(rng.uniform(20.0, 400.0));
      const float ly = f(rng.uniform(20.0, 400.0));
      return FieldElement::sine_texture(lx, ly, f(rng.uniform(-30.0, 30.0)), w);
    }
    default:
      return FieldElement::vortex(c, w * 0.01f);
  }
}

}  // namespace

SceneDefinition random_builtin_scene(Rng& rng) {
  const Target targets[] = {Target::Top, Target::Middle, Target::Bottom};
  const Target t = rng.pick(targets);
  TunnelParams tunnel;
  tunnel.width_start = f(rng.uniform(20.0, 80.0));
  tunnel.width_end = f(rng.uniform(10.0, 40.0));
  tunnel.scale = rng.chance(0.5) ? 1.0f : 10.0f;
  switch (rng.integer(0, 9)) {
    case 0: return scenes::heightmap(t);
    case 1: return scenes::frictionmap(t);
    case 2: return scenes::neutral();
    case 3: return scenes::steering_tunnel(tunnel, scenes::TunnelMode::Converging);
    case 4: return scenes::steering_tunnel(tunnel, scenes::TunnelMode::Diverging);
    case 5: return scenes::pilot_c_valley(t);
    case 6: return scenes::familiarisation_path();
    case 7: return scenes::bump_map();
    case 8: return scenes::vortex();
    default: return scenes::heightmap(t);
  }
}

SceneDefinition random_general_scene(Rng& rng, bool tables) {
  SceneDefinition s;
  s.rendering = rng.chance(0.75) ? Rendering::Directional : Rendering::PositionOnly;
  s.bias = s.rendering == Rendering::PositionOnly ? f(rng.uniform(-0.5, 0.5)) : 0.0f;
  bool table_heights = false;
  if (tables && rng.chance(0.5)) {
    s.evaluation = Evaluation::Table;
    s.table.storage = rng.chance(0.5) ? TableStorage::Int16 : TableStorage::Float32;
    s.table.source = rng.chance(0.5) ? TableSource::TabulatedGradient : TableSource::HeightCentralDifferences;
    s.table.spacing_px = f(rng.uniform(6.0, 16.0));  // fits the 96 KB slot in every layout
    table_heights = s.rendering == Rendering::Directional && s.table.source == TableSource::HeightCentralDifferences;
  }
  const int n = rng.integer(1, kMaxSceneElements);
  for (int i = 0; i < n; ++i) {
    FieldElement e = random_element(rng, !table_heights);
    if (s.rendering == Rendering::PositionOnly) e.weight = f(rng.uniform(-1.0, 1.0));  // profiles add in [0, 1]
    s.add(e);
  }
  return s;
}

SceneDefinition random_scene(Rng& rng) {
  return rng.chance(0.5) ? random_builtin_scene(rng) : random_general_scene(rng, true);
}

AmplitudeSettings random_settings(Rng& rng) {
  AmplitudeSettings a;
  const float strengths[] = {1.0f, 0.66f, 0.33f, f(rng.uniform(0.01, 1.0))};
  a.strength = rng.pick(strengths);
  a.s_curve = rng.chance(0.7) ? 0.0f : f(rng.uniform(0.0, 1.0));
  a.idle_amplitude = rng.chance(0.7) ? 0.0f : f(rng.uniform(0.0, 1.0));
  switch (rng.integer(0, 3)) {
    case 0:
    case 1: a.calibration = DacCalibration::linear(); break;
    case 2: a.calibration = DacCalibration::inverted(); break;
    default: {
      // A measured, monotonic curve of 3..16 points.
      const int n = rng.integer(3, kMaxCalibrationPoints);
      float amps[kMaxCalibrationPoints], codes[kMaxCalibrationPoints];
      const bool up = rng.chance(0.5);
      for (int i = 0; i < n; ++i) {
        amps[i] = i == 0 ? 0.0f : (i == n - 1 ? 1.0f : f((i + rng.uniform(-0.3, 0.3)) / (n - 1)));
        const double c = (i + rng.uniform(-0.3, 0.3)) / (n - 1) * 4095.0;
        const float code = f(i == 0 ? rng.uniform(0.0, 200.0) : (i == n - 1 ? rng.uniform(3895.0, 4095.0) : c));
        codes[up ? i : n - 1 - i] = code;
      }
      DacCalibration::from_points(amps, codes, n, a.calibration);
      break;
    }
  }
  return a;
}

TrackerConfig random_tracker(Rng& rng) {
  TrackerConfig c = TrackerConfig::recommended();
  switch (rng.integer(0, 9)) {
    case 0:
    case 1: c = TrackerConfig::thesis(); break;
    case 2: c = TrackerConfig::thesis(); c.one_euro.derivative_from = DerivativeFrom::PreviousRaw; break;
    case 3: c.estimator = Estimator::TimedExtrapolation; break;
    case 4: c.estimator = Estimator::ThesisTicks; break;
    default: break;
  }
  return c;
}

RunConfig random_config(Rng& rng, SceneDefinition (*scene)(Rng&)) {
  RunConfig r;
  r.tracker = random_tracker(rng);
  r.condition.amplitude = random_settings(rng);
  r.calibration_valid = r.condition.amplitude.calibration.valid();
  auto probe = std::make_unique<ScenePlan>();
  auto memory = std::make_unique<unsigned char[]>(kTableSlotBytes);
  for (int attempt = 0; attempt < 20; ++attempt) {
    r.condition.scene = scene(rng);
    if (probe->prepare(r.condition.scene, memory.get(), kTableSlotBytes) == PrepareStatus::Ok) return r;
  }
  r.condition.scene = scenes::heightmap(Target::Middle);
  return r;
}

}  // namespace ff::stress
