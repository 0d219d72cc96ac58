// The cavity moved onto a given surface (model/cavity_rounding.hpp), on a structured TET10 mesh of
// [0,1]² x [-1,1]: "tissue" above z = 0, "needle" below, the cavity their shared face z = 0. The
// surface z = -a sin(πx) sin(πy) bulges into the needle, so the tissue gains the volume
// a ∫∫ sin(πx) sin(πy) = 4a/π² (closed form), and the needle, which keeps its shape on copies of
// the cavity's nodes, keeps its volume 1.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <utility>

#include "model/cavity_rounding.hpp"
#include "model/mesh_quality.hpp"

namespace needlefem {
namespace {

constexpr double kPi = std::numbers::pi;

// n x n x 2n cubes of edge 1/n, six Kuhn tets each, with edge nodes; faces on z = 0 in "cavity"
// (seen from the tissue) and "needle_surface" (seen from the needle).
TetMesh two_block_mesh(int n) {
  TetMesh mesh;
  mesh.nodes_per_tet = 10;
  mesh.region_names = {"tissue", "needle"};
  const double h = 1.0 / n;
  const auto vertex = [&](int i, int j, int k) { return (k * (n + 1) + j) * (n + 1) + i; };
  for (int k = 0; k <= 2 * n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) mesh.nodes.push_back({i * h, j * h, (k - n) * h});
  std::map<std::pair<int, int>, int> middle;
  const auto edge_node = [&](int a, int b) {
    const auto key = std::minmax(a, b);
    auto [it, added] = middle.try_emplace({key.first, key.second}, static_cast<int>(mesh.nodes.size()));
    if (added) {
      const Point3 &p = mesh.nodes[a], &q = mesh.nodes[b];
      mesh.nodes.push_back({0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1]), 0.5 * (p[2] + q[2])});
    }
    return it->second;
  };
  // Kuhn's six tets of a cube: the paths from corner 0 to corner 7 through the axis permutations.
  constexpr std::array<std::array<int, 3>, 6> kPaths{{{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
  constexpr int kEdges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}};
  for (int k = 0; k < 2 * n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        for (const auto& path : kPaths) {
          std::array<int, 3> at{i, j, k};
          std::array<int, 4> v{};
          v[0] = vertex(at[0], at[1], at[2]);
          for (int s = 0; s < 3; ++s) {
            ++at[path[s]];
            v[s + 1] = vertex(at[0], at[1], at[2]);
          }
          const Point3 &p0 = mesh.nodes[v[0]], &p1 = mesh.nodes[v[1]], &p2 = mesh.nodes[v[2]], &p3 = mesh.nodes[v[3]];
          const double det = (p1[0] - p0[0]) * ((p2[1] - p0[1]) * (p3[2] - p0[2]) - (p2[2] - p0[2]) * (p3[1] - p0[1])) -
                             (p1[1] - p0[1]) * ((p2[0] - p0[0]) * (p3[2] - p0[2]) - (p2[2] - p0[2]) * (p3[0] - p0[0])) +
                             (p1[2] - p0[2]) * ((p2[0] - p0[0]) * (p3[1] - p0[1]) - (p2[1] - p0[1]) * (p3[0] - p0[0]));
          if (det < 0) std::swap(v[1], v[2]);
          for (int a : v) mesh.tet_nodes.push_back(a);
          for (const auto& e : kEdges) mesh.tet_nodes.push_back(edge_node(v[e[0]], v[e[1]]));
          const bool needle = k < n;
          mesh.tet_region.push_back(needle ? 1 : 0);
          std::array<int, 3> face{};
          int on_plane = 0;
          for (int a : v)
            if (std::abs(mesh.nodes[a][2]) < 1e-12 && on_plane < 3) face[on_plane++] = a;
          if (on_plane == 3) {
            auto& group = mesh.surface_faces[needle ? "needle_surface" : "cavity"];
            for (int a : face) group.push_back(a);
            group.push_back(edge_node(face[0], face[1]));
            group.push_back(edge_node(face[1], face[2]));
            group.push_back(edge_node(face[2], face[0]));
          }
        }
  return mesh;
}

double bulge(double a, double x, double y) { return -a * std::sin(kPi * x) * std::sin(kPi * y); }

TEST(CavityRounding, CavityOnTheSurfaceTissueGainsTheClosedFormVolumeNeedleKeepsItsShape) {
  constexpr double a = 0.05;
  TetMesh mesh = two_block_mesh(8);
  const std::size_t nodes_before = mesh.nodes.size();
  const double tissue_before = measure_quality(mesh).regions.at("tissue").volume_m3;
  const CavityRounding report =
      round_cavity(mesh, [&](const Point3& X) { return Point3{X[0], X[1], X[2] + bulge(a, X[0], X[1])}; });

  // Every cavity node on the surface; interior nodes off it moved no more than the bulge's depth.
  for (int node : mesh.surface_faces.at("cavity")) {
    const Point3& x = mesh.nodes[node];
    EXPECT_NEAR(x[2], bulge(a, x[0], x[1]), 1e-14);
  }
  EXPECT_NEAR(report.largest_move_m, a, 1e-12);  // the bulge's deepest point is a vertex at (1/2, 1/2)
  const MeshQuality quality = measure_quality(mesh);
  EXPECT_EQ(quality.inverted(), 0U);
  EXPECT_EQ(report.straightened_edges, 0U);  // a gentle bulge leaves every tet's shape good
  // Tissue: 1 + 4a/π² up to the quadratic faces' interpolation error of the bulge (h = 1/8).
  const double gained = quality.regions.at("tissue").volume_m3 - tissue_before;
  EXPECT_NEAR(gained, 4 * a / (kPi * kPi), 1e-3 * 4 * a / (kPi * kPi));
  EXPECT_NEAR(quality.regions.at("needle").volume_m3, 1.0, 1e-12);
  // The needle's cavity nodes are copies: one per shared node (vertices and edge nodes of z = 0).
  const std::size_t shared = 81 + 2 * 8 * 9 + 64;  // 9x9 vertices, 144 axis edges, 64 diagonals
  EXPECT_EQ(report.split_nodes, shared);
  EXPECT_EQ(mesh.nodes.size(), nodes_before + shared);
  EXPECT_EQ(mesh.split_nodes.size(), shared);
  for (const auto& [tissue, needle] : mesh.split_nodes) {
    EXPECT_NE(tissue, needle);
    EXPECT_NEAR(mesh.nodes[needle][2], 0.0, 1e-15);
  }
  for (int node : mesh.surface_faces.at("needle_surface")) EXPECT_GE(node, static_cast<int>(nodes_before));
}

TEST(CavityRounding, AMeshWithoutCavityIsLeftAlone) {
  TetMesh mesh = two_block_mesh(2);
  mesh.surface_faces.erase("cavity");
  const auto nodes = mesh.nodes;
  const CavityRounding report = round_cavity(mesh, [](const Point3& X) { return Point3{X[0], X[1], X[2] + 1.0}; });
  EXPECT_EQ(report.moved_nodes, 0U);
  EXPECT_EQ(mesh.nodes, nodes);
}

}  // namespace
}  // namespace needlefem
