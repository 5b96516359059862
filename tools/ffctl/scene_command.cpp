#include "scene_command.hpp"

#include <memory>

#include "frictionfield/core/haptic_pipeline.hpp"

namespace ff::ffctl {

bool condition_message(const host::SceneSpec& spec, protocol::ConditionMessage& out, std::string& error) {
  Condition c;
  if (!host::make_condition(spec, c, error)) return false;
  protocol::ConditionMessage m;
  m.strength = c.amplitude.strength;
  m.idle_amplitude = c.amplitude.idle_amplitude;
  m.s_curve = c.amplitude.s_curve;
  m.calibration = c.amplitude.calibration;
  // make_condition accepted the target word, so it is one of these three.
  m.target = spec.target == "top" ? Target::Top : spec.target == "bottom" ? Target::Bottom : Target::Middle;
  // A table-evaluated heightmap is a different rendering: it goes whole.
  const bool closed_form = spec.evaluation == "closed";
  // A scene file is whatever make_condition made of it (--scene-file implies
  // the file scene there): it travels whole, whatever --scene says.
  if (!spec.scene_file.empty()) {
    m.kind = protocol::ConditionKind::General;
    m.scene = c.scene;
  } else if (closed_form && spec.scene == "heightmap") {
    m.kind = protocol::ConditionKind::Heightmap;
  } else if (closed_form && spec.scene == "frictionmap") {
    m.kind = protocol::ConditionKind::Frictionmap;
  } else if (spec.scene == "neutral") {
    m.kind = protocol::ConditionKind::Neutral;
  } else {
    m.kind = protocol::ConditionKind::General;
    m.scene = c.scene;
  }
  // The device prepares the condition with this same core: one it would
  // refuse (too costly to prepare within its watchdog, a table over its slot)
  // is refused here, before anything is sent.
  auto pipeline = std::make_unique<HapticPipeline>();
  const PrepareStatus status = pipeline->set_condition(m.to_condition());
  if (status != PrepareStatus::Ok) {
    error = std::string("the device would refuse the scene: ") + to_string(status);
    return false;
  }
  out = m;
  return true;
}

}  // namespace ff::ffctl
