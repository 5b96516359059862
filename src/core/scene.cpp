#include "frictionfield/core/scene.hpp"

namespace ff {

bool SceneDefinition::add(const FieldElement& e) {
  if (element_count >= kMaxSceneElements) return false;
  elements[element_count++] = e;
  return true;
}

}  // namespace ff
