// Which scene a case sets up (scene.kind): it decides which of the other specs apply.
#pragma once

namespace needlefem {

class Case;

enum class SceneKind { brain_tip, block, mesh };

SceneKind parse_scene_kind(const Case& c);

}  // namespace needlefem
