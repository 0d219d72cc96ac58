// Which scene a case sets up (scene.kind): it decides which of the other specs apply.
#pragma once

#include <string>

namespace needlefem {

class Case;

enum class SceneKind { brain_tip, block, mesh };

SceneKind parse_scene_kind(const Case& c);

// The kind's scene.kind value, for messages and the mesh cache's key.
std::string scene_kind_name(SceneKind kind);

}  // namespace needlefem
