// Reads a gmsh .msh (millimetres; TET10 or TET4; the physical names listed in
// mesh/scene_mesher.hpp) into a TetMesh in metres. Surface faces are oriented outward of the
// tissue (or, for faces touching no tissue, of the needle).
#pragma once

#include <filesystem>

#include "model/tet_mesh.hpp"

namespace needlefem {

// Throws std::runtime_error "FILE: reason" for unreadable files, mixed or unsupported element
// types and meshes without a physical volume whose name starts with "tissue".
TetMesh read_msh(const std::filesystem::path& file);

}  // namespace needlefem
