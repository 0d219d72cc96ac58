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

std::string scene_kind_name(SceneKind kind) { return choice_name(kSceneKinds, kind); }

}  // namespace needlefem
