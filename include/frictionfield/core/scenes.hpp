#pragma once
// The built-in scenes: the experiment conditions, the pilots, familiarisation.
// Each is an instance of the general weighted-sum SceneDefinition.
#include "frictionfield/core/scene.hpp"

namespace ff::scenes {

// Experiment conditions (docs/spec.md#scenes).
SceneDefinition heightmap(Target target);    // 1/2 valley (a = 1/5) + 1/2 cone
SceneDefinition frictionmap(Target target);  // 20 px slippery path, 20 px feather
SceneDefinition neutral();                   // A = 0.5

// Pilots (thesis appendix I).
enum class TunnelMode : uint8_t { Converging, Diverging, Neutral };
SceneDefinition steering_tunnel(const TunnelParams& tunnel, TunnelMode mode);
SceneDefinition pilot_c_valley(Target target);  // width 20, s = 10: |2 atan(u/2) - u|

// Familiarisation.
SceneDefinition familiarisation_path();  // low-friction winding sine path
SceneDefinition bump_map();              // sinusoidal bumps, rendered as a heightmap

// A vortex around the screen centre: a field no potential can produce.
SceneDefinition vortex();

}  // namespace ff::scenes
