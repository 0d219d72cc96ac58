// Mesh-objective measures of a tissue field against a safety limit, from its values at the
// tissue's quadrature points (reference positions X_q, reference volumes w_q = quadrature weight
// times det J of the element map).
//
// Why: the largest value at a quadrature point next to a needle edge is as large as the mesh
// lets it be (shared/DESIGN.md §2b: 11 % log strain, 45 % von Mises between mesh seeds), while
// the limits it is checked against (0.19 log strain, 10 1/s) come from tissue-level
// measurements over finite gauges, not points. What converges under refinement is an integral:
//
//   critical-distance value (Theory of Critical Distances, volume method; Taylor 2007,
//     "The Theory of Critical Distances", Elsevier, ch. 2): the field averaged over the tissue
//     inside a ball of radius ℓ, maximised over the ball's centre,
//         f_ℓ = max_c  ∫_{B(c,ℓ) ∩ tissue} f dV  /  ∫_{B(c,ℓ) ∩ tissue} dV,
//     a ball cut by the tissue's boundary (the cavity, the cube's faces) averaging over the
//     tissue part only. The integrals are the quadrature's own: Σ w_q f_q / Σ w_q over the points
//     inside the ball, so the ball's rim is sampled to the element size and the value converges
//     with the mesh. Centres lie on a lattice fixed in space (spacing s = ℓ/4, a vertex at the
//     origin): the voxel centres that lie in the tissue (in one of its elements' straight
//     tetrahedra through their vertices, which differ from curved boundary elements by O(h²)).
//     A centre is a point of the material, as in Taylor's volume method: a centre just inside the
//     needle would average a thin tissue shell along the needle's surface, a value that tends to
//     the point value, and whether a voxel straddling the surface held a tissue point would
//     depend on the mesh. The maximum of a smooth average sampled at that spacing is within O(s)
//     of the true one at the tissue's surface, O(s²) inside it. Closed forms
//     (homogeneous field: its value; linear field, full ball: the centre's value; quadratic
//     |X - c|²: 3ℓ²/5; a ball cut by a plane face: the truncated ball's mean; no centre outside
//     the tissue) in tests/run/test_safety_metrics.cpp.
//   volume above the limit (the cumulative strain damage measure of head-injury models, CSDM;
//     Takhounts et al. 2003, Stapp Car Crash J. 47), and its fraction of a stated region: the
//     volume where the field the points represent exceeds the limit. In each element that field
//     is the linear one through its points' values (TET10: the 4 points determine it; the
//     displacement gradient of a straight quadratic element is linear, so this is the element's
//     own field to first order in the strain's nonlinearity), and the part of the element above
//     the limit is cut off by a plane, exactly: V = Σ_e V_e |{λ : Σ_i λ_i c_i > limit}| / |T|,
//     c_i the field extrapolated to the vertices, V_e = Σ_q w_q. A sum of the points' volumes
//     with f_q > limit would instead jump by a whole w_q as a point crosses the limit, an error
//     at the limit's surface whose sign changes from mesh to mesh; the cut is exact for a linear
//     field on any mesh and O(h²) for a smooth one (docs/accuracy.md §12).
//     TET4 has one point, a constant field per element: the element counts whole or not at all;
//   percentile over a region: the smallest value v whose volume above (as just defined) is at
//     most (1 - P/100) V_region, i.e. the value the hottest (100 - P) % of the region's volume
//     reaches.
// Regions are given as a per-point mask (run/: tissue within a distance of the needle's cavity).
//
// Speed: voxels wholly inside a ball enter by their sums, only voxels on its rim point by point;
// the maximisation visits few centres: voxels are grouped in blocks of 4³ (edge ℓ), a ball's
// average is at most the largest point value in the 27 blocks around its centre's block, so
// blocks are visited in descending order of that bound and the search stops once the bound
// cannot beat the best average found (nor tie it in an earlier slot). Within a visited block, a
// centre's rim is read point by point only where a bound from the voxel sums alone can beat the
// best average: the ball holds its inside voxels whole and a part of volume v of each rim voxel
// (volume V, sum S, values between m and L), whose sum is at most min(v L, S - (V - v) m), so
// the average is at most the largest ratio of those sums over the choices of v, which
// Dinkelbach's iteration finds exactly. On the fine meshes' many points per voxel near the
// needle this skips most rims (docs/speed.md).
#pragma once

#include <cstdint>
#include <span>
#include <unordered_map>
#include <vector>

#include "model/tet_mesh.hpp"

namespace needlefem::fields {

using Tetrahedron = std::array<Point3, 4>;  // vertex positions, metres

struct LocatedValue {
  double value = 0.0;
  Point3 position{};  // reference position, metres
};

class BallAverager {
 public:
  // `positions` and `volumes` per point (both as many), `tissue` the tetrahedra they fill (ball
  // centres lie in them); radius_m > 0.
  BallAverager(std::span<const Point3> positions, std::span<const double> volumes,
               std::span<const Tetrahedron> tissue, double radius_m);

  double radius() const { return radius_; }
  // The largest ball average of `field` (one value per point), at a voxel centre in the tissue.
  LocatedValue maximum(std::span<const double> field) const;
  // The ball average around the centre of the voxel that contains `x`, and that centre.
  LocatedValue average_around(const Point3& x, std::span<const double> field) const;

 private:
  static constexpr int kBlock = 4;  // voxels per block edge: a block's edge is ℓ
  static constexpr int kBlockVoxels = kBlock * kBlock * kBlock;
  struct Block {
    std::array<long long, 3> index;
    // The block's points, voxel by voxel: voxel l's are slots first[l]..first[l + 1]-1 of the
    // point arrays in block order (below).
    std::array<int, kBlockVoxels + 1> first{};
    std::array<int, 27> neighbours{};           // block indices of the 27 blocks around, -1 if none
    std::uint64_t centres_in_tissue = 0;        // bit l: voxel l's centre lies in the tissue
  };
  struct Sums {
    std::vector<double> weighted, volume, largest, smallest;  // per block and voxel
    std::vector<double> field;                      // per point in block order
  };
  // The voxels of one neighbour block that a ball centred in a given voxel reaches (bit l: voxel
  // l), wholly inside the ball or cut by its rim.
  struct Reach {
    std::uint64_t inside = 0, rim = 0;
  };
  void mark_centres_in_tissue(std::span<const Tetrahedron> tissue, const std::unordered_map<long long, int>& block_at);
  std::array<long long, 3> voxel_of(const Point3& x) const;
  Point3 centre_of(const std::array<long long, 3>& voxel) const;
  Sums accumulate(std::span<const double> field) const;
  double average(const Sums& sums, int block, int voxel) const;
  // At least average(sums, block, voxel), from the voxel sums alone (the header comment).
  double average_bound(const Sums& sums, int block, int voxel) const;
  void plan_reach();  // fills reach_

  double radius_, spacing_;
  // The points in block order: the point each slot holds, its position and volume. The averages
  // read them in this order, so that a ball's rim reads contiguous memory.
  std::vector<int> point_of_slot_;
  std::vector<Point3> positions_;
  std::vector<double> volumes_;
  std::vector<Block> blocks_;
  std::vector<std::uint64_t> occupied_;  // per block, bit l: voxel l holds points
  // Per centre voxel, per neighbour (Block::neighbours' order).
  std::array<std::array<Reach, 27>, kBlockVoxels> reach_;
};

// The tissue's elements as the volume measures see them: element k holds points [k p, (k + 1) p)
// of the point arrays, p = point_barycentric.size() (1 or 4), at those barycentric coordinates
// of its straight tetrahedron (the same for every element: the quadrature rule's). The spans
// must outlive it.
class TissueElements {
 public:
  TissueElements(std::span<const Tetrahedron> tetrahedra, std::span<const std::array<double, 4>> point_barycentric);

  std::span<const Tetrahedron> tetrahedra() const { return tetrahedra_; }
  // Per element, the volume of its points that the mask (per point) selects; all with no mask.
  std::vector<double> selected_volumes(std::span<const double> point_volumes, std::span<const char> mask = {}) const;
  // Per element, the vertex values of its field: the linear field through its 4 points' values
  // (all four the point's value for one point).
  std::vector<std::array<double, 4>> vertex_values(std::span<const double> field) const;

 private:
  std::span<const Tetrahedron> tetrahedra_;
  std::size_t points_;
  std::array<std::array<double, 4>, 4> vertex_from_points_{};  // c = Λ⁻¹ f, Λ_qi = λ_i(point q)
};

// The part of the tetrahedron where the linear field with vertex values `vertex_value` exceeds
// `limit`: its share of the tetrahedron's volume and its centroid (barycentric coordinates).
struct TetrahedronPart {
  double fraction = 0.0;
  std::array<double, 4> centroid{};
};
TetrahedronPart part_above(const std::array<double, 4>& vertex_value, double limit);

// The volume where the elements' field (TissueElements::vertex_values) exceeds `limit`, with its
// centroid; each element counts by its volume in `element_volumes` (TissueElements::
// selected_volumes: a mask's share of it).
struct VolumeAbove {
  double volume = 0.0;  // m³
  Point3 centroid{};    // reference position, metres (zeros when the volume is empty)
};
VolumeAbove volume_above(const TissueElements& elements, std::span<const std::array<double, 4>> vertex_values,
                         std::span<const double> element_volumes, double limit);

// The volume-weighted percentile (0 < percent < 100) of the elements' field over the elements'
// volumes (as volume_above counts them), as defined above: the smallest v whose volume above is
// at most (1 - percent/100) of their sum.
double volume_percentile(std::span<const std::array<double, 4>> vertex_values, std::span<const double> element_volumes,
                         double percent);

}  // namespace needlefem::fields
