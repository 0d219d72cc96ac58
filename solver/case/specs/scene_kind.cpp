#include "case/specs/scene_kind.hpp"

#include <array>
#include <utility>

#include "case/specs/choice.hpp"

namespace needlefem {

namespace {

// scene.kind's choices (schema.cpp) with their enumerators.
const std::array kSceneKinds{std::pair{"brain-tip", SceneKind::brain_tip}, std::pair{"block", SceneKind::block},
                             std::pair{"mesh", SceneKind::mesh}};

}  // namespace

SceneKind parse_scene_kind(const Case& c) { return parse_choice(c, "scene.kind", kSceneKinds); }

std::string scene_kind_name(SceneKind kind) {
  for (const auto& [name, enumerator] : kSceneKinds)
    if (enumerator == kind) return name;
  throw std::logic_error("scene kind without a name");
}

}  // namespace needlefem
