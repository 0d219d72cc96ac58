#include "case/specs/scene_kind.hpp"

#include <array>
#include <utility>

#include "case/specs/choice.hpp"

namespace needlefem {

SceneKind parse_scene_kind(const Case& c) {
  return parse_choice(c, "scene.kind",
                      std::array{std::pair{"brain-tip", SceneKind::brain_tip}, std::pair{"block", SceneKind::block},
                                 std::pair{"mesh", SceneKind::mesh}});
}

}  // namespace needlefem
