// The mesh cache: a case's scene is meshed once and every later run of the same scene reads that
// mesh, so that runs repeat bit for bit (gmsh's high-order optimiser works in the order of memory
// addresses, so two meshings of one scene differ in the last digits of their curved nodes, and
// frictional contact turns that into other step sequences and maxima).
//
// An entry is one .msh named by the key, a hash of
//   - the canonical text (key = value) of every case key the scene mesher reads, from its mesh
//     spec (case/specs/mesh_spec.hpp; mesh_cache_key_text in mesh_cache.cpp; the bytes of
//     needle.cad_file too),
//   - gmsh's version,
//   - the bytes of the running executable (/proc/self/exe): a rebuild invalidates every entry.
// The entry holds the mesh as gmsh wrote it and, in a section gmsh skips ($NeedlefemMeshInfo),
// the SceneMeshInfo of that meshing.
//
// Directory: $NEEDLEFEM_MESH_CACHE, else $XDG_CACHE_HOME/needlefem/meshes, else
// ~/.cache/needlefem/meshes. Entries are never changed once written; delete the directory freely.
//
// A miss meshes into a temporary file in the directory and publishes it with link(), which fails
// when the name exists: the first writer wins, a concurrent one drops its own and reads the
// winner's (a temporary left by a writer that was killed is removed by a miss a day later). Hit
// or miss, the run reads the published entry, so the first run and every later one
// use the same bytes. A directory that cannot be written (read-only, full) does not fail the run:
// it meshes into the output directory as without a cache and says so in one line. The user's mesh
// or geometry (scene.mesh_file) and a case that exports the needle (needle.export_file, written
// while meshing) bypass the cache.
#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "mesh/scene_mesher.hpp"

namespace needlefem {

struct MeshSpec;

// The directory the cache uses in this environment (not created).
std::filesystem::path mesh_cache_directory();

// The key of the mesh spec's scene mesh: 16 hexadecimal digits, the hash of a canonical text (the
// mesher's case keys, gmsh's version and the executable's hash, one "name = value" line each).
std::string mesh_cache_key(const MeshSpec& spec);

// Where the scene mesh came from, for run summaries and mesh reports: {"source": "hit" | "miss" |
// "off" | "bypassed", "key", "file", "note"} (SceneMeshInfo::cache).
nlohmann::json mesh_cache_json(const SceneMeshInfo& info);

// The sizes aimed at near the needle and those measured on the mesh, as the mesh report and the
// cache entry hold them; and back.
nlohmann::json to_json(const NeedleGrading& grading);
NeedleGrading grading_from_json(const nlohmann::json& json);

}  // namespace needlefem
