#include "bench_cases.hpp"

#include "frictionfield/core/scenes.hpp"

namespace ff::bench {

namespace {

constexpr float kSpacings[] = {1.0f, 2.0f, 4.0f, 8.0f, 16.0f};
constexpr int kSpacingCount = 5;
constexpr TableStorage kStorages[] = {TableStorage::Float32, TableStorage::Int16};

bool has_height(SceneId s) { return s != SceneId::Vortex && s != SceneId::General6; }

// Table strategies per scene: spacing x storage x source.
int sources_of(SceneId s) {
  const Rendering r = scene_definition(s).rendering;
  if (r == Rendering::Constant) return 0;
  if (r == Rendering::PositionOnly) return 1;
  return has_height(s) ? 2 : 1;
}

int strategies_of(SceneId s) { return 1 + kSpacingCount * 2 * sources_of(s); }

void append(char* out, size_t capacity, size_t& used, const char* text) {
  while (*text != '\0' && used + 1 < capacity) out[used++] = *text++;
  if (capacity > 0) out[used < capacity ? used : capacity - 1] = '\0';
}

void append_int(char* out, size_t capacity, size_t& used, int v) {
  char digits[12];
  int n = 0;
  do {
    digits[n++] = static_cast<char>('0' + v % 10);
    v /= 10;
  } while (v > 0 && n < 11);
  char text[12];
  for (int i = 0; i < n; ++i) text[i] = digits[n - 1 - i];
  text[n] = '\0';
  append(out, capacity, used, text);
}

SceneDefinition general(int elements) {
  // A weighted sum exercising every element kind, weights chosen so that no
  // term dominates the screen: cost against element count.
  SceneDefinition s;
  s.rendering = Rendering::Directional;
  s.add(FieldElement::path_sink(PathCurve::cubic(-200.0f), 0.2f, 1.0f));
  if (elements >= 3) {
    s.add(FieldElement::point_sink({700.0f, 40.0f}, 0.5f));
    s.add(FieldElement::saddle({400.0f, 240.0f}, 0.002f));
  }
  if (elements >= 6) {
    s.add(FieldElement::tunnel_valley(TunnelParams{}, 0.5f));
    s.add(FieldElement::sine_texture(160.0f, 160.0f, 20.0f, 0.3f));
    s.add(FieldElement::vortex({400.0f, 240.0f}, 0.002f));
  }
  return s;
}

}  // namespace

const char* scene_name(SceneId scene) {
  switch (scene) {
    case SceneId::Neutral: return "neutral";
    case SceneId::FrictionmapTop: return "frictionmap-top";
    case SceneId::HeightmapTop: return "heightmap-top";
    case SceneId::HeightmapMiddle: return "heightmap-middle";
    case SceneId::HeightmapBottom: return "heightmap-bottom";
    case SceneId::TunnelPilotA: return "tunnel-pilot-a";
    case SceneId::TunnelPilotB: return "tunnel-pilot-b";
    case SceneId::PilotCTop: return "pilot-c-top";
    case SceneId::BumpMap: return "bump-map";
    case SceneId::Vortex: return "vortex";
    case SceneId::FamiliarisationPath: return "familiarisation-path";
    case SceneId::General1: return "general-1";
    case SceneId::General3: return "general-3";
    case SceneId::General6: return "general-6";
    case SceneId::kCount: break;
  }
  return "?";
}

bool is_builtin(SceneId scene) {
  return scene != SceneId::General1 && scene != SceneId::General3 && scene != SceneId::General6;
}

TunnelParams tunnel_params(SceneId scene) {
  TunnelParams t;  // x 100..500, width 60 -> 20, centre y 240
  t.scale = scene == SceneId::TunnelPilotB ? 10.0f : 1.0f;
  return t;
}

SceneDefinition scene_definition(SceneId scene) {
  switch (scene) {
    case SceneId::Neutral: return scenes::neutral();
    case SceneId::FrictionmapTop: return scenes::frictionmap(Target::Top);
    case SceneId::HeightmapTop: return scenes::heightmap(Target::Top);
    case SceneId::HeightmapMiddle: return scenes::heightmap(Target::Middle);
    case SceneId::HeightmapBottom: return scenes::heightmap(Target::Bottom);
    case SceneId::TunnelPilotA:
    case SceneId::TunnelPilotB:
      return scenes::steering_tunnel(tunnel_params(scene), scenes::TunnelMode::Converging);
    case SceneId::PilotCTop: return scenes::pilot_c_valley(Target::Top);
    case SceneId::BumpMap: return scenes::bump_map();
    case SceneId::Vortex: return scenes::vortex();
    case SceneId::FamiliarisationPath: return scenes::familiarisation_path();
    case SceneId::General1: return general(1);
    case SceneId::General3: return general(3);
    case SceneId::General6: return general(6);
    case SceneId::kCount: break;
  }
  return scenes::neutral();
}

int case_count() {
  int n = 0;
  for (int s = 0; s < kSceneCount; ++s) n += strategies_of(static_cast<SceneId>(s));
  return n;
}

BenchCase case_at(int index) {
  BenchCase c;
  for (int s = 0; s < kSceneCount; ++s) {
    const SceneId scene = static_cast<SceneId>(s);
    const int n = strategies_of(scene);
    if (index >= n) {
      index -= n;
      continue;
    }
    c.scene = scene;
    if (index == 0) {
      c.strategy.evaluation = Evaluation::ClosedForm;
      return c;
    }
    const int t = index - 1;  // spacing-major, then storage, then source
    const int sources = sources_of(scene);
    c.strategy.evaluation = Evaluation::Table;
    c.strategy.table.spacing_px = kSpacings[t / (2 * sources)];
    c.strategy.table.storage = kStorages[(t / sources) % 2];
    c.strategy.table.source =
        t % sources == 0 ? TableSource::TabulatedGradient : TableSource::HeightCentralDifferences;
    return c;
  }
  return c;
}

SceneDefinition case_definition(const BenchCase& c) {
  SceneDefinition d = scene_definition(c.scene);
  d.evaluation = c.strategy.evaluation;
  d.table = c.strategy.table;
  return d;
}

bool is_default(const BenchCase& c) {
  const SceneDefinition d = scene_definition(c.scene);
  if (d.evaluation != c.strategy.evaluation) return false;
  if (d.evaluation == Evaluation::ClosedForm) return true;
  return d.table.spacing_px == c.strategy.table.spacing_px &&
         d.table.storage == c.strategy.table.storage && d.table.source == c.strategy.table.source;
}

void strategy_label(const Strategy& s, Rendering rendering, char* out, size_t capacity) {
  size_t used = 0;
  if (capacity > 0) out[0] = '\0';
  if (s.evaluation == Evaluation::ClosedForm) {
    append(out, capacity, used, "closed-form");
    return;
  }
  append(out, capacity, used, "table-");
  append_int(out, capacity, used, static_cast<int>(s.table.spacing_px));
  append(out, capacity, used, s.table.storage == TableStorage::Int16 ? "px-int16" : "px-float");
  if (rendering != Rendering::Directional) {
    append(out, capacity, used, "-profile");  // a position-only table holds the profile
  } else {
    append(out, capacity, used,
           s.table.source == TableSource::TabulatedGradient ? "-gradient" : "-height-cd");
  }
}

void case_id(const BenchCase& c, char* out, size_t capacity) {
  size_t used = 0;
  if (capacity > 0) out[0] = '\0';
  append(out, capacity, used, scene_name(c.scene));
  append(out, capacity, used, "/");
  char label[48];
  strategy_label(c.strategy, scene_definition(c.scene).rendering, label, sizeof(label));
  append(out, capacity, used, label);
}

const char* tracker_config_name(int index) {
  switch (index) {
    case 0: return "thesis()";
    case 1: return "recommended()";
    case 2: return "recommended()+thesis-ticks";
    case 3: return "recommended()+timed-extrapolation";
    case 4: return "recommended()+kalman";
    case 5: return "recommended(realistic profile)";
  }
  return "?";
}

SensorProfile realistic_sensor_profile() {
  SensorProfile p;
  p.white_noise_px = 0.52041650f;  // 0.5 px white and the 0.5 px quantum's q/sqrt(12)
  p.correlated_noise_px = 1.5f;
  p.correlation_time_ms = 30.0f;
  p.tremor_px = 1.0f;
  p.report_rate_hz = 200.0f;
  p.jitter_us = 234.52079f;  // 150 us on each stamp (twice) and 2 % period jitter (100 us)
  p.latency_us = 2000;       // 1-3 ms after the scan
  return p;
}

TrackerConfig tracker_config(int index) {
  if (index == 0) return TrackerConfig::thesis();
  // Every filter carries the wander and the tremor.
  if (index == 5) return TrackerConfig::recommended(realistic_sensor_profile());
  TrackerConfig c = TrackerConfig::recommended();
  if (index == 2) c.estimator = Estimator::ThesisTicks;
  if (index == 3) c.estimator = Estimator::TimedExtrapolation;
  if (index == 4) c.estimator = Estimator::Kalman;
  return c;
}

}  // namespace ff::bench
