#pragma once
// The built-in scenes as docs/spec.md#scenes and #pilots define them, written
// out field by field from the spec's numbers (not through the core's
// ff::scenes builders or its factory defaults): the reference side of every
// "the core builds the spec's scene" check.
#include "frictionfield/core/scene.hpp"

namespace ff::reference::spec {

// rise T: the path's target at (700, 240 + T); -200 top, 0 middle, 200 bottom.
SceneDefinition heightmap(double rise);    // Z = 1/2 |5 atan(u/5) - u| + 1/2 |p - target|
SceneDefinition frictionmap(double rise);  // A = S5((30 - |u|) / 20)
SceneDefinition pilot_c(double rise);      // H = |2 atan(u/2) - u|
SceneDefinition steering_tunnel(double scale);  // x 100..500, width 60 -> 20, centre 240; s = 1 (A), 10 (B)
SceneDefinition bump_map();                // 20 px sin(2 pi x/160) sin(2 pi y/160)
SceneDefinition vortex();                  // G = (-(y - 240), x - 400)
SceneDefinition familiarisation_path();    // a slippery band along 240 + 120 sin(2 pi x / 400)
SceneDefinition neutral();                 // 0.5 everywhere

}  // namespace ff::reference::spec
