// The mesh stage's keys, parsed: the scene's kind and the user's mesh or geometry ([scene]),
// [mesh], the brain-tip scene's tip and tissue cube with their element sizes and the needle keys
// its mesher reads, and the block's box: the input of the scene mesher and its cache
// (mesh/scene_mesher.hpp, mesh/mesh_cache.hpp) and of load_scene_model (model/scene_model.hpp).
// Its scene.mesh_file, mesh.refinement_level and needle.edge_radius_um are parsed here only: the
// mechanics, the contact and the needle in contact take them from this spec (run/run_specs.hpp).
// The mesh cache's key holds every key parsed here but the files and the partitions it handles
// otherwise (tests/mesh/check_mesh_cache_keys.py reads this parser's keys).
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "case/specs/needle_tip_spec.hpp"
#include "case/specs/scene_kind.hpp"

namespace needlefem {

class Case;

struct MeshSpec {
  std::string origin;  // the case's, for the CaseErrors naming scene.mesh_file
  SceneKind scene_kind;
  std::filesystem::path scene_mesh_file;  // the user's .msh or .geo, resolved; empty: none
  long order;                             // 1: 4-node tets, 2: 10-node tets
  bool optimize_high_order;
  long seed;              // gmsh's random factor
  long refinement_level;  // L: every refined size times 2^-L
  // n: the edge size at level 0 is max(ρ, core / 4) / n. Not given: the mesher's default for the
  // tip (edge_elements_per_radius in mesh/scene_mesher.hpp).
  std::optional<long> edge_elements_per_radius;
  long partitions;        // METIS element partitions (MPI ranks), of the mesh once meshed
  // The brain-tip scene.
  NeedleTipSpec needle_tip;
  TissueCubeSpec tissue;                     // the cube, its core and their element sizes
  long curvature_elements;                   // tissue.curvature_elements; 0: sizes not from curvature
  double needle_edge_radius_um;              // ρ, which the grading towards the tip's edges follows
  bool needle_mesh_volume;                   // the tip meshed too ("needle", "needle_surface")
  std::filesystem::path needle_export_file;  // the tip's CAD written there while meshing; empty: none
  // The block scene.
  std::array<double, 3> block_size_mm;
  double block_element_mm;
  // The keys only a mesh scene reads that the case gives (in the schema's order): load_scene_model
  // refuses them in another scene.
  std::vector<std::string> mesh_scene_keys_given;
};

MeshSpec parse_mesh_spec(const Case& c);

// True when the mesher builds the brain-tip scene around the tip (scene.kind = "brain-tip" without
// a scene.mesh_file): the scene whose geometric rules a case must keep.
bool generates_brain_tip_scene(const MeshSpec& spec);

}  // namespace needlefem
