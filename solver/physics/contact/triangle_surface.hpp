// Closest points on a triangulated surface, through a bounding-volume hierarchy.
//
// Closest point on one triangle: Ericson, Real-Time Collision Detection (2005), §5.1.5 (Voronoi
// regions of the vertices, edges and face), which also says which feature the point lies on.
// Sign: the angle-weighted pseudo-normal of that feature (Bærentzen & Aanæs, IEEE TVCG 11(3),
// 2005): the face normal on a face, the sum of the two face normals on an edge, Σ θ_f n_f at a
// vertex (θ_f the face's angle there); (x - p)·N > 0 outside for a closed, outward-oriented
// surface.
// Index: a binary tree of axis-aligned boxes over the triangles (split at the median centroid
// along the box's longest axis, leaves of at most kLeafSize triangles). A query descends the
// nearer child first and skips every box farther than the best distance so far, so it tests the
// triangles whose boxes come within that distance: for a point at distance d from a surface of
// facets s, a patch of radius about sqrt(2 d s) (the contact needle's queries sit at d ≈ ρ from
// its core, cad_needle.hpp). A leaf is also skipped when the slab around its triangles (their mean
// normal, the range of their vertices along it) is farther than the best distance: on a face
// tilted to the axes the boxes alone let in every leaf within about sqrt(2 d w), w a leaf's width. Why not a uniform grid (the first version): with cells of two
// facets a query at d = ρ = 100 µm walks ~3000 cells of 16 µm (docs/speed.md records the cost). Queries are const (thread-safe).
#pragma once

#include <array>
#include <vector>

#include "model/tet_mesh.hpp"

namespace needlefem::contact {

struct TriangleSoup {
  std::vector<Point3> vertices;
  std::vector<std::array<int, 3>> triangles;
};

class TriangleSurface {
 public:
  enum class Feature { Face, Edge, Vertex };
  struct Closest {
    Point3 point{};
    double distance = 0.0;
    int triangle = -1;
    Feature feature = Feature::Face;
    Point3 edge_direction{};  // unit tangent of the edge (Feature::Edge)
    Point3 pseudo_normal{};   // unit
  };

  explicit TriangleSurface(TriangleSoup soup);

  Closest closest(const Point3& x) const;              // through the tree
  Closest closest_brute_force(const Point3& x) const;  // every triangle (tests)
  // Distance, negative where the pseudo-normal says inside.
  double signed_distance(const Point3& x) const;
  const TriangleSoup& soup() const { return soup_; }
  const Point3& face_normal(int t) const { return face_normals_[t]; }

 private:
  void test_triangle(int t, const Point3& x, Closest& best) const;

  TriangleSoup soup_;
  std::vector<Point3> face_normals_, vertex_normals_;
  std::vector<std::array<Point3, 3>> edge_normals_;  // per triangle: edges (0,1), (1,2), (2,0)
  struct Node {
    Point3 lo, hi;
    int first = 0, count = 0;  // leaf: triangles order_[first, first + count)
    int left = -1, right = -1;  // inner node: children
    // Leaf: the slab {y : slab_lo <= slab_normal·y <= slab_hi} that holds its triangles, normal
    // their mean. A box around a patch tilted to the axes is as thick as the patch is wide; the
    // slab is as thin as the patch is curved, so it prunes the leaves beside a query's foot.
    Point3 slab_normal{};
    double slab_lo = 0.0, slab_hi = 0.0;
  };
  int build(int first, int count);
  std::vector<Node> nodes_;
  std::vector<int> order_;
};

// Orients a closed triangulation consistently (neighbours traverse a shared edge in opposite
// directions) and outward (positive enclosed volume). Returns the number of edges not shared by
// exactly two triangles (0 for a closed manifold surface; then the orientation is reliable).
std::size_t orient_outward(TriangleSoup& soup);
// Volume enclosed by a closed, outward-oriented triangulation (divergence theorem).
double enclosed_volume(const TriangleSoup& soup);

}  // namespace needlefem::contact
