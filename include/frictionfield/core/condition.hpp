#pragma once
// One experiment condition: the scene and how its output becomes a DAC code.
// Plain data on its own, so that the protocol (messages.hpp) and host tools
// can name it without the pipeline and its two table slots.
#include "frictionfield/core/amplitude_map.hpp"
#include "frictionfield/core/scene.hpp"

namespace ff {

// Everything needed to render one experiment condition.
struct Condition {
  SceneDefinition scene;
  AmplitudeSettings amplitude;
};

}  // namespace ff
