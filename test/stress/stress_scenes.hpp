#pragma once
// Random conditions for the stress set: the thesis' scenes, general scenes
// mixing every element kind, table evaluation, amplitude settings and
// tracker configurations.
#include "frictionfield/core/haptic_pipeline.hpp"
#include "stress_random.hpp"
#include "stress_run.hpp"

namespace ff::stress {

SceneDefinition random_builtin_scene(Rng& rng);
// 1..8 elements of every kind, weights log-uniform in [1e-2, 1e2] with
// either sign, directional or position-only; `tables` allows table evaluation.
SceneDefinition random_general_scene(Rng& rng, bool tables);
SceneDefinition random_scene(Rng& rng);  // either of the above, closed form or table

// Strength, S-curve, idle amplitude and calibration within their valid ranges.
AmplitudeSettings random_settings(Rng& rng);
TrackerConfig random_tracker(Rng& rng);

// A condition the core accepts (retries the scene until prepare() says Ok).
RunConfig random_config(Rng& rng, SceneDefinition (*scene)(Rng&) = random_scene);

}  // namespace ff::stress
