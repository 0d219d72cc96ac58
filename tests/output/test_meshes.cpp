#include "test_meshes.hpp"

#include <algorithm>
#include <map>
#include <stdexcept>
#include <utility>

namespace needlefem::output::testing {
namespace {

// gmsh TET10 edges, local node 4 + k on edge k.
constexpr int kGmshEdges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}};

std::pair<int, int> key(int a, int b) { return {std::min(a, b), std::max(a, b)}; }

}  // namespace

TetMesh kuhn_cube(double edge, bool quadratic) {
  TetMesh mesh;
  mesh.nodes_per_tet = quadratic ? 10 : 4;
  // Cube vertex v has coordinates (v & 1, (v >> 1) & 1, (v >> 2) & 1) * edge.
  for (int v = 0; v < 8; ++v) mesh.nodes.push_back({(v & 1) * edge, ((v >> 1) & 1) * edge, ((v >> 2) & 1) * edge});
  // Kuhn tets: 0 -> 0 + e_a -> 0 + e_a + e_b -> 7 for every order (a, b, c) of the axes.
  const int axis_bit[3] = {1, 2, 4};
  const int orders[6][2] = {{0, 1}, {1, 0}, {0, 2}, {2, 0}, {1, 2}, {2, 1}};
  std::map<std::pair<int, int>, int> edge_nodes;
  for (int t = 0; t < 6; ++t) {
    const int a = axis_bit[orders[t][0]], b = axis_bit[orders[t][1]];
    int corner[4] = {0, a, a | b, 7};
    // Positive orientation: (x1-x0, x2-x0, x3-x0) right-handed.
    const bool odd = (orders[t][0] + 1) % 3 != orders[t][1];
    if (odd) std::swap(corner[1], corner[2]);
    mesh.tet_nodes.insert(mesh.tet_nodes.end(), corner, corner + 4);
    if (quadratic) {
      for (const auto& [i, j] : kGmshEdges) {
        auto [it, added] = edge_nodes.try_emplace(key(corner[i], corner[j]), static_cast<int>(mesh.nodes.size()));
        if (added) {
          const Point3& p = mesh.nodes[corner[i]];
          const Point3& q = mesh.nodes[corner[j]];
          mesh.nodes.push_back({(p[0] + q[0]) / 2, (p[1] + q[1]) / 2, (p[2] + q[2]) / 2});
        }
        mesh.tet_nodes.push_back(it->second);
      }
    }
    mesh.tet_region.push_back(t < 3 ? 0 : 1);
  }
  mesh.region_names = {"tissue", "needle"};
  if (quadratic) {
    // z = 0 holds vertices 0 1 2 3 (diagonal 0-3); z = edge holds 4 5 6 7 (diagonal 4-7).
    // TRI6 faces: vertices, then edge nodes (0,1) (1,2) (2,0); outward normals.
    auto face = [&](int p, int q, int r) {
      return std::vector<int>{p, q, r, edge_nodes.at(key(p, q)), edge_nodes.at(key(q, r)), edge_nodes.at(key(r, p))};
    };
    std::vector<int> bottom = face(0, 3, 1), bottom2 = face(0, 2, 3);
    bottom.insert(bottom.end(), bottom2.begin(), bottom2.end());
    std::vector<int> top = face(4, 5, 7), top2 = face(4, 7, 6);
    top.insert(top.end(), top2.begin(), top2.end());
    mesh.surface_faces["bottom"] = bottom;
    mesh.surface_faces["top"] = top;
  }
  return mesh;
}

int edge_node(const TetMesh& mesh, int a, int b) {
  for (std::size_t e = 0; e < mesh.tet_count(); ++e) {
    const int* tet = mesh.tet(e);
    for (int k = 0; k < 6; ++k) {
      const int i = tet[kGmshEdges[k][0]], j = tet[kGmshEdges[k][1]];
      if (key(i, j) == key(a, b)) return tet[4 + k];
    }
  }
  throw std::invalid_argument("no such edge");
}

}  // namespace needlefem::output::testing
