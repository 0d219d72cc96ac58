// The tissue's cavity moved onto the needle it holds, edges rounded.
//
// Why: the scene mesher carves the cavity from the needle's CAD, whose edges are sharp, while the
// needle in contact has its edges rounded with the physical radius ρ (needle.edge_radius_um,
// physics/contact/needle_obstacle.hpp). Left sharp, the tissue keeps a re-entrant edge along each
// needle edge: the continuum field there is singular, so its point values and the volume above a
// limit grow with every refinement (docs/accuracy.md §8), and the rounded needle starts up to
// ρ(1/sin(θ/2) - 1) away from the tissue at an edge of dihedral angle θ. OpenCASCADE's 3-D
// fillet of the tip's edges fails on these curves (docs/study.md, "Edge radius and mesh
// grading"), so the rounding is done on the mesh instead:
//   1. every node of the tissue's "cavity" faces (vertices and, for TET10, edge nodes) moves to
//      its closest point on the needle's surface, x_a = X_a - g(X_a) n(X_a) (the needle's signed
//      distance g and normal n at t = 0);
//   2. the move fades into the tissue over a few element layers: free vertices there take the
//      mean of their neighbours' moves weighted by 1/distance² (a discrete harmonic extension,
//      Jacobi sweeps), vertices on other boundary groups stay; TET10 edge nodes off the cavity
//      move by the mean of their edge's two vertices, so interior edges stay as straight (or as
//      curved) as the mesher made them;
//   3. the rounding moves an edge's nodes by up to ρ(1/sin(θ/2) - 1), about an edge element's size
//      on the coarsest meshes, and can squeeze a tet there: each free vertex of a tet whose
//      scaled Jacobian falls below 0.2 moves to the best of a few candidate places (towards its
//      neighbours' centroid, or with the cavity vertex next to it) by the worst straight-sided
//      shape around it, if that improves; a cavity edge node of a tet still that poor moves with its
//      edge's two vertices instead (the mean of their moves, keeping the mesher's curve), and
//      where the tet stays poor, to their midpoint (a straight edge). Such an edge is off the
//      rounded surface by up to its sagitta; reference_gap_offset in
//      physics/contact/penalty_contact.hpp takes those gaps as the start;
//   4. a tet all that leaves inverted or nearly so (scaled Jacobian below 0.05): each free vertex
//      of it moves by a compass search on the worst straight-sided shape around it.
//   5. a TET10 tet still inverted has every edge made straight (the curvature of its interior
//      edges, from gmsh's high-order optimiser, is then what inverts it).
// The moves point into the needle (the rounded needle lies inside the sharp one), so the tissue
// tets at the edges mostly grow; the caller checks every tet's Jacobian afterwards
// (mesh_quality.hpp).
// The needle region, meshed conforming on the cavity for the deformable-needle check, keeps the
// sharp shape: its cavity nodes are split off as copies at their old places (TetMesh::split_nodes),
// and its surface groups ("needle_...") refer to the copies.
#pragma once

#include <cstddef>
#include <functional>

#include <nlohmann/json_fwd.hpp>

#include "model/tet_mesh.hpp"

namespace needlefem {

struct CavityRounding {
  std::size_t moved_nodes = 0;  // cavity nodes (and interior edge nodes) that moved
  double largest_move_m = 0.0;
  std::size_t split_nodes = 0;  // needle-region copies made
  int smoothing_rounds = 0;     // rounds that moved the free vertices of poor tets
  std::size_t relaxed_edges = 0;       // cavity edges of poor tets left with the mesher's curve
  std::size_t straightened_edges = 0;  // ... and of those still poor, made straight
  std::size_t untangled_vertices = 0;  // free vertices of tets still (nearly) inverted, searched further
  std::size_t straightened_tets = 0;   // TET10 tets still inverted, every edge of them made straight
  double tissue_volume_gained_m3 = 0.0;  // where the needle's edges were rounded off (set by the caller)
};

// Moves the "cavity" of `mesh` onto the surface whose closest point to X is closest_point(X).
// A mesh without a "cavity" group is left as it is.
CavityRounding round_cavity(TetMesh& mesh, const std::function<Point3(const Point3&)>& closest_point);

// {"moved_nodes", "largest_move_mm", ..., "tissue_volume_gained_mm3"} for the mesh reports.
nlohmann::json to_json(const CavityRounding& rounding);

}  // namespace needlefem
