#pragma once
// What the benchmarks measure, shared by the host tool (ff-bench) and the
// Cortex-M4F harness (ff-m4bench) so that their rows match by id: the scenes,
// the evaluation strategies of each, and the tracker configurations.
// Portable: single precision, no allocation, no host library.
#include <cstddef>
#include <cstdint>

#include "frictionfield/core/scene.hpp"
#include "frictionfield/core/tracker.hpp"

namespace ff::bench {

enum class SceneId : uint8_t {
  Neutral,
  FrictionmapTop,
  HeightmapTop,
  HeightmapMiddle,
  HeightmapBottom,
  TunnelPilotA,         // steering tunnel, converging, s = 1
  TunnelPilotB,         // steering tunnel, converging, s = 10
  PilotCTop,            // valley only, |2 atan(u/2) - u|
  BumpMap,
  Vortex,
  FamiliarisationPath,
  General1,             // general weighted sum with 1, 3 and 6 elements
  General3,
  General6,
  kCount
};
constexpr int kSceneCount = static_cast<int>(SceneId::kCount);

const char* scene_name(SceneId scene);
bool is_builtin(SceneId scene);         // an ff::scenes:: scene (not a general one)
SceneDefinition scene_definition(SceneId scene);  // as built in: its default evaluation
// The geometry the tunnel scenes use (TunnelParams defaults, scale s).
TunnelParams tunnel_params(SceneId scene);

struct Strategy {
  Evaluation evaluation = Evaluation::ClosedForm;
  TableConfig table;
};

struct BenchCase {
  SceneId scene = SceneId::Neutral;
  Strategy strategy;
};

// Every (scene, strategy) pair: the scene's closed form, then tables at
// 1, 2, 4, 8, 16 px, float and int16, tabulated gradient and (for fields that
// have a height) height + central differences. Position-only scenes tabulate
// the profile; the constant scene has only its closed form.
int case_count();
BenchCase case_at(int index);
SceneDefinition case_definition(const BenchCase& c);
bool is_default(const BenchCase& c);  // the scene's built-in evaluation

// "closed-form", "table-4px-int16-gradient", "table-4px-float-height-cd",
// "table-8px-int16-profile" (position-only scenes tabulate the profile).
void strategy_label(const Strategy& s, Rendering rendering, char* out, size_t capacity);
// "heightmap-top/table-4px-int16-gradient"
void case_id(const BenchCase& c, char* out, size_t capacity);

// Tracker configurations whose per-update cost is measured: thesis(),
// recommended(), recommended() with each Estimator, and recommended() for a
// sensor with every modelled effect (names without commas).
constexpr int kTrackerConfigCount = 6;
const char* tracker_config_name(int index);
TrackerConfig tracker_config(int index);
// The profile of a sensor with every modelled effect: what a perfect
// calibration measures on the realistic-200hz trace class (bench_reference_test
// checks it against the trace generator's nominal profile).
SensorProfile realistic_sensor_profile();

}  // namespace ff::bench
