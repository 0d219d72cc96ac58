// The mesh stage as the rest of the solver sees it: the case's scene meshed (or the user's
// .msh taken), read into a TetMesh and checked. Every command that needs a mesh calls this.
#pragma once

#include <cstdio>
#include <filesystem>

#include "mesh/scene_mesher.hpp"
#include "model/cavity_rounding.hpp"
#include "model/mesh_quality.hpp"
#include "model/tet_mesh.hpp"

namespace needlefem {

struct MeshSceneGroupsSpec;
struct MeshSpec;
struct ObstacleSpec;
struct PressureSpec;

struct SceneModel {
  TetMesh mesh;
  SceneMeshInfo info;      // CAD facts (zero for a user-supplied mesh or geometry)
  MeshQuality quality;
  std::filesystem::path msh_file;
  bool user_mesh = false;
  CavityRounding cavity_rounding;  // what moved the cavity onto the needle (run/run_case.hpp)
};

// Meshes the scene of the case's mesh spec `spec` (parse_mesh_spec) into out_dir/mesh.msh (or
// reads scene.mesh_file; a .geo of the mesh scene is meshed there too), saying so on `progress`
// (build_scene_mesh; nullptr: silent). Throws CaseError for bad input (also: a group the mesh
// scene's keys name that is not a surface group of the mesh, and mesh-scene keys given in another
// scene) and std::runtime_error for meshing failures; inverted elements are reported in
// `quality`, and require_valid_elements() turns them into an error.
// The groups the mesh scene's keys name: groups.fixed, .roller and .displaced in `groups`
// (parse_boundary_spec), groups.pressure in `pressure` (parse_pressure_spec), obstacle.group in
// `obstacle` (parse_obstacle_spec).
SceneModel load_scene_model(const MeshSpec& spec, const MeshSceneGroupsSpec& groups, const PressureSpec& pressure,
                            const ObstacleSpec& obstacle, const std::filesystem::path& out_dir, std::FILE* progress);
void require_valid_elements(const SceneModel& scene);

}  // namespace needlefem
