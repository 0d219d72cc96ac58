// Builds the scene geometry of a case with the gmsh C++ API (OpenCASCADE kernel), meshes it
// with second- (or first-) order tetrahedra and writes a .msh (millimetres).
//
// Physical names written (the contract with model/read_msh and user-supplied meshes):
//   volumes  "tissue_core", "tissue_outer" (brain-tip) or "tissue" (block); "needle" (optional)
//   surfaces brain-tip: "entry" (z = 0 face of the tissue), "x_min" "x_max" "y_min" "y_max"
//            "z_max" (the five skull-fixed faces), "fixed" (their union), "cavity" (tissue
//            faces touching the needle tip), "needle_rear" (rear face of the tip, z = 0),
//            "needle_surface" (the whole boundary of the meshed tip, when needle.mesh_volume)
//            block: "x_min" ... "z_max"
//   mesh scene: those of the user's .geo (scene.mesh_file), which needs a volume "tissue"
#pragma once

#include <cstddef>
#include <cstdio>
#include <filesystem>
#include <string>

namespace needlefem {

struct CompliantTip;
struct MeshSpec;
struct NeedleTip;
struct NeedleTipSpec;
struct TissueCubeSpec;

// Sizes of the tissue elements next to the needle, each the mean edge length of a tet
// (corner nodes), over the tissue tets with a corner on the given entities (millimetres).
struct ElementSizeStats {
  std::size_t tets = 0;
  double min = 0, median = 0, max = 0;
};

// The mesh sizes near the needle that the scene mesher aimed at, and what it got.
struct NeedleGrading {
  int refinement_level = 0;
  double edge_radius_mm = 0;           // ρ = min(τ, needle.edge_radius_um); 0 without sharp edges
  double edge_target_mm = 0;           // element size aimed at on the sharp edges
  long edge_elements_per_radius = 1;   // n (edge_elements_per_radius above)
  double surface_target_mm = 0;        // ... on the cavity surface
  double core_mm = 0;                  // ... where the grading meets the core size
  double grading_distance_mm = 0;      // distance over which the sizes grow to the core size
  int edge_curves = 0;                 // sharp edges of the cavity that the edge grading uses
  ElementSizeStats edge_elements;      // tissue tets touching those edges
  ElementSizeStats cavity_elements;    // tissue tets touching the cavity surface
};

// n of the edge grading (mesh/size_field.cpp): mesh.edge_elements_per_radius when given, otherwise
// by the tip: 2 on bevels sharper than 15° that have edges, whose volume above the strain limit
// converges only with the rounding resolved from level 0 (docs/accuracy.md §14); 1 on every
// other tip.
long edge_elements_per_radius(const MeshSpec& spec, const NeedleTip& tip);

struct SceneMeshInfo {
  std::string needle_description;  // empty for the block scene
  double needle_cad_volume_m3 = 0;       // from the OpenCASCADE model
  double needle_analytic_volume_m3 = 0;  // from geometry/needle_tip (independent)
  double domain_volume_m3 = 0;           // cube or block without the cavity: the bounding solid
  double seconds = 0;
  std::string high_order_optimisation;  // which gmsh optimisation passes ran, and misses
  NeedleGrading grading;                // brain-tip scene only (block: refinement level only)
  // Where the mesh came from (mesh/mesh_cache.hpp): "hit" (read from the cache), "miss" (meshed
  // and published by this run, then read from the cache), "off" (the cache could not be used:
  // meshed into msh_file directly, `cache_note` says why) or "bypassed" (scene.mesh_file,
  // needle.export_file).
  std::string cache;
  std::string cache_key;    // empty when bypassed
  std::string cache_file;   // the entry read; empty when off or bypassed
  std::string cache_note;   // why the cache was off or bypassed
};

// The cache entry point (mesh/mesh_cache.cpp): writes the scene mesh of the case's mesh spec to msh_file, from
// the mesh cache when it holds the scene, else meshed with generate_scene_mesh and published
// there first. Throws CaseError for impossible geometry (naming the violated rule) and
// std::runtime_error when gmsh fails. On `progress` (nullptr: none), a line when gmsh starts and
// one when the mesh is written: fine levels mesh for long with nothing else to show.
SceneMeshInfo build_scene_mesh(const MeshSpec& spec, const std::filesystem::path& msh_file, std::FILE* progress);

// Meshes the case's scene with gmsh and writes it to msh_file (the mesher itself, without the
// cache); on `progress` the line when gmsh starts.
SceneMeshInfo generate_scene_mesh(const MeshSpec& spec, const std::filesystem::path& msh_file, std::FILE* progress);

// Building blocks for other meshers of the needle alone (prbm_check/), inside a GmshSession:
// adds paper 000's compliant tip (millimetres, axis +z, rear face z = 0) to the current model as
// one OpenCASCADE solid and returns its volume tag (call occ::synchronize() after);
int add_compliant_tip(const CompliantTip& tip);
// adds the case's needle tip `tip` (needle_tip_from_spec(spec)) of any kind (a CAD tip checked
// against `tissue`: mesh/cad_tip.hpp), synchronised;
int add_needle_tip(const NeedleTip& tip, const NeedleTipSpec& spec, const TissueCubeSpec& tissue);
// curves a generated second-order mesh without inverting it; returns the passes that ran.
std::string optimise_high_order();
// makes the edges of every second-order tet still inverted straight; returns how many.
std::size_t straighten_inverted_tets();

}  // namespace needlefem
