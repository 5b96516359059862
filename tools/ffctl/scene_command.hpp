#pragma once
// The scene words (--scene, --target, --strength, ...; shared with ff-replay)
// turned into the SetCondition message ffctl sends.
#include <string>

#include "frictionfield/host/scene_spec.hpp"
#include "frictionfield/protocol/messages.hpp"

namespace ff::ffctl {

// The thesis conditions (heightmap, frictionmap with closed-form evaluation;
// neutral) travel as kind + target + strength so the firmware builds them
// itself; anything else travels whole as a General scene. false with a
// readable `error` if the words do not make a condition or the core refuses to
// prepare it (host::make_condition prepares it as the device would: nothing is sent).
bool condition_message(const host::SceneSpec& spec, protocol::ConditionMessage& out, std::string& error);

}  // namespace ff::ffctl
