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

// For a file from outside (scene.mesh_file): gmsh's reader trusts the counts and tags a .msh
// gives, and a damaged $Nodes or $Elements section can make it crash (SIGSEGV) or ask for
// terabytes (std::bad_alloc). So gmsh first reads the file in a child process; a crash, an
// exception or an error there becomes std::runtime_error "FILE: reason", and this process,
// with whatever it has written, goes on to report it.
void require_readable_msh(const std::filesystem::path& file);

}  // namespace needlefem
