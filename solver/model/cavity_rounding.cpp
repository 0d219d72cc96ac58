#include "model/cavity_rounding.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <unordered_map>
#include <vector>

#include <nlohmann/json.hpp>

#include "model/mesh_quality.hpp"

namespace needlefem {

namespace {

constexpr double kMovedM = 1e-9;  // a move below a nanometre is the projection's round-off
constexpr int kLayers = 8;        // element layers over which the cavity's move fades
constexpr int kSweeps = 150;      // Jacobi sweeps of the extension (converged for 8 layers)
constexpr int kSmoothingRounds = 20;  // rounds of moving poor tets' free vertices (at most)
constexpr double kPoorScaledJacobian = 0.2;  // the gmsh meshes' smallest is about 0.4
constexpr double kLeastScaledJacobian = 0.05;  // below it a tet's free vertices search further
constexpr int kCompassHalvings = 8;            // the compass search's last step: 1/512 of its first
// TET10 edge nodes 4..9 sit on the edges (0,1) (1,2) (2,0) (3,0) (3,2) (3,1) (tet_mesh.hpp).
constexpr int kEdgeEnds[6][2] = {{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}};

double squared_distance(const Point3& a, const Point3& b) {
  return (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]);
}

// 6√2 V / l³ of the tet's vertices (l the root mean square of its six edge lengths): 1 for the
// regular tet, 0 for a flat one, negative for an inverted one.
double straight_tet_quality(const TetMesh& mesh, std::size_t e) {
  const int* tet = mesh.tet(e);
  const Point3 &a = mesh.nodes[tet[0]], &b = mesh.nodes[tet[1]], &c = mesh.nodes[tet[2]], &d = mesh.nodes[tet[3]];
  const Point3 u{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v{c[0] - a[0], c[1] - a[1], c[2] - a[2]},
      w{d[0] - a[0], d[1] - a[1], d[2] - a[2]};
  const double volume = (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
                         u[2] * (v[0] * w[1] - v[1] * w[0])) / 6.0;
  const double lengths = squared_distance(a, b) + squared_distance(a, c) + squared_distance(a, d) +
                         squared_distance(b, c) + squared_distance(b, d) + squared_distance(c, d);
  return 6.0 * std::sqrt(2.0) * volume / std::pow(lengths / 6.0, 1.5);
}

bool needle_group(const std::string& name) { return name.rfind("needle", 0) == 0; }

// The needle region's nodes on the cavity become copies at the same place; the needle's tets and
// surface groups use the copies.
std::size_t split_needle_nodes(TetMesh& mesh, const std::vector<char>& on_cavity) {
  const int needle = mesh.region_index("needle");
  if (needle < 0) return 0;
  std::unordered_map<int, int> copy_of;
  const auto copy = [&](int node) {
    if (!on_cavity[node]) return node;
    auto [it, added] = copy_of.try_emplace(node, static_cast<int>(mesh.nodes.size()));
    if (added) {
      mesh.nodes.push_back(mesh.nodes[node]);
      mesh.split_nodes.push_back({node, it->second});
    }
    return it->second;
  };
  for (std::size_t e = 0; e < mesh.tet_count(); ++e)
    if (mesh.tet_region[e] == needle)
      for (int a = 0; a < mesh.nodes_per_tet; ++a) {
        int& node = mesh.tet_nodes[e * mesh.nodes_per_tet + a];
        node = copy(node);
      }
  for (auto& [name, faces] : mesh.surface_faces)
    if (needle_group(name))
      for (int& node : faces) node = copy(node);
  return copy_of.size();
}

}  // namespace

CavityRounding round_cavity(TetMesh& mesh, const std::function<Point3(const Point3&)>& closest_point) {
  CavityRounding report;
  const auto cavity = mesh.surface_faces.find("cavity");
  if (cavity == mesh.surface_faces.end()) return report;
  std::vector<char> on_cavity(mesh.nodes.size(), 0);
  for (int node : cavity->second) on_cavity[node] = 1;
  report.split_nodes = split_needle_nodes(mesh, on_cavity);

  const std::size_t nodes = on_cavity.size();
  const int needle = mesh.region_index("needle");
  const int vertices = mesh.nodes_per_tet == 10 ? 4 : mesh.nodes_per_tet;
  // Fixed nodes: the cavity's (moved onto the needle) and every other boundary node (not moved).
  std::vector<char> fixed(on_cavity);
  for (const auto& [name, faces] : mesh.surface_faces)
    if (!needle_group(name))
      for (int node : faces) fixed[node] = 1;
  std::vector<Point3> move(nodes, Point3{});
  for (std::size_t node = 0; node < nodes; ++node) {
    if (!on_cavity[node]) continue;
    const Point3& X = mesh.nodes[node];
    const Point3 x = closest_point(X);
    move[node] = {x[0] - X[0], x[1] - X[1], x[2] - X[2]};
  }
  // The tissue's vertex graph within kLayers edges of the cavity: free vertices there take the
  // mean move of their neighbours (a discrete harmonic extension, by Jacobi sweeps), so the
  // cavity's move fades over several element layers instead of deforming the first one alone.
  std::vector<std::vector<int>> neighbours(nodes);
  for (std::size_t e = 0; e < mesh.tet_count(); ++e) {
    if (mesh.tet_region[e] == needle) continue;
    const int* tet = mesh.tet(e);
    for (int a = 0; a < vertices; ++a)
      for (int b = 0; b < vertices; ++b)
        if (a != b) neighbours[tet[a]].push_back(tet[b]);
  }
  std::vector<int> layer(nodes, -1), free_vertices;
  std::vector<int> front;
  for (std::size_t node = 0; node < nodes; ++node)
    if (on_cavity[node] && !neighbours[node].empty()) {
      layer[node] = 0;
      front.push_back(static_cast<int>(node));
    }
  for (int depth = 1; depth <= kLayers; ++depth) {
    std::vector<int> next;
    for (int node : front)
      for (int other : neighbours[node])
        if (layer[other] < 0) {
          layer[other] = depth;
          next.push_back(other);
          if (!fixed[other] && depth < kLayers) free_vertices.push_back(other);
        }
    front.swap(next);
  }
  // The weights 1/distance² of each free vertex's neighbours, fixed over the sweeps.
  std::vector<std::vector<double>> weight(free_vertices.size());
  for (std::size_t i = 0; i < free_vertices.size(); ++i)
    for (int other : neighbours[free_vertices[i]])
      weight[i].push_back(1.0 / squared_distance(mesh.nodes[free_vertices[i]], mesh.nodes[other]));
  for (int sweep = 0; sweep < kSweeps; ++sweep) {
    std::vector<Point3> updated(free_vertices.size());
    for (std::size_t i = 0; i < free_vertices.size(); ++i) {
      const auto& around = neighbours[free_vertices[i]];
      Point3 sum{};
      double weights = 0.0;
      for (std::size_t j = 0; j < around.size(); ++j) {
        weights += weight[i][j];
        for (int c = 0; c < 3; ++c) sum[c] += weight[i][j] * move[around[j]][c];
      }
      for (int c = 0; c < 3; ++c) updated[i][c] = sum[c] / weights;
    }
    for (std::size_t i = 0; i < free_vertices.size(); ++i) move[free_vertices[i]] = updated[i];
  }
  const std::vector<Point3> reference(mesh.nodes.begin(), mesh.nodes.begin() + static_cast<long>(nodes));
  // TET10 edge nodes off the cavity: the mean move of their edge's two vertices.
  const auto place = [&] {
    if (mesh.nodes_per_tet == 10)
      for (std::size_t e = 0; e < mesh.tet_count(); ++e) {
        if (mesh.tet_region[e] == needle) continue;
        const int* tet = mesh.tet(e);
        for (int k = 0; k < 6; ++k) {
          const int middle = tet[4 + k], a = tet[kEdgeEnds[k][0]], b = tet[kEdgeEnds[k][1]];
          if (!on_cavity[middle])
            for (int c = 0; c < 3; ++c) move[middle][c] = 0.5 * (move[a][c] + move[b][c]);
        }
      }
    for (std::size_t node = 0; node < nodes; ++node)
      for (int c = 0; c < 3; ++c) mesh.nodes[node][c] = reference[node][c] + move[node][c];
  };
  place();
  // Where a tet next to a sharp edge is squeezed (the edge's nodes move by up to ρ(1/sin(θ/2) - 1),
  // about an edge element's size on the coarsest meshes), each free vertex of it moves to the
  // best of a few candidate places (towards the centroid of its neighbours, or along with the
  // cavity vertex next to it that moved most) by the worst shape (straight_tet_quality) of the
  // tets around it, and only if that improves, until every tissue tet's scaled Jacobian is at least
  // kPoorScaledJacobian or a round finds nothing better.
  std::vector<char> is_free(nodes, 0);
  for (int node : free_vertices) is_free[node] = 1;
  std::vector<std::vector<int>> tets_at(nodes);
  for (std::size_t e = 0; e < mesh.tet_count(); ++e)
    if (mesh.tet_region[e] != needle)
      for (int a = 0; a < vertices; ++a) tets_at[mesh.tet(e)[a]].push_back(static_cast<int>(e));
  const auto worst_around = [&](int node) {
    double worst = 1.0;
    for (int e : tets_at[node]) worst = std::min(worst, straight_tet_quality(mesh, static_cast<std::size_t>(e)));
    return worst;
  };
  // The free vertices of the tissue tets whose scaled Jacobian is below `least` (with repeats).
  const auto free_vertices_of_tets_below = [&](double least) {
    const MeshQuality quality = measure_quality(mesh);
    std::vector<int> found;
    for (std::size_t e = 0; e < mesh.tet_count(); ++e)
      if (mesh.tet_region[e] != needle && quality.tet_scaled_jacobian[e] < least)
        for (int a = 0; a < vertices; ++a)
          if (is_free[mesh.tet(e)[a]]) found.push_back(mesh.tet(e)[a]);
    return found;
  };
  for (int round = 0; round < kSmoothingRounds; ++round) {
    const std::vector<int> poor = free_vertices_of_tets_below(kPoorScaledJacobian);
    bool improved = false;
    for (int node : poor) {
      Point3 centroid{}, follow{};
      double largest = 0.0;
      for (int other : neighbours[node]) {
        for (int c = 0; c < 3; ++c) centroid[c] += mesh.nodes[other][c] / static_cast<double>(neighbours[node].size());
        const double size = squared_distance(move[other], Point3{});
        if (on_cavity[other] && size > largest) {
          largest = size;
          follow = move[other];
        }
      }
      const Point3 start = mesh.nodes[node];
      std::vector<Point3> candidates;
      for (double s : {0.25, 0.5, 0.75, 1.0})
        candidates.push_back({start[0] + s * (centroid[0] - start[0]), start[1] + s * (centroid[1] - start[1]),
                              start[2] + s * (centroid[2] - start[2])});
      for (double s : {0.5, 1.0})
        candidates.push_back({reference[node][0] + s * follow[0], reference[node][1] + s * follow[1],
                              reference[node][2] + s * follow[2]});
      double best = worst_around(node);
      Point3 best_place = start;
      for (const Point3& candidate : candidates) {
        mesh.nodes[node] = candidate;
        if (const double q = worst_around(node); q > best) {
          best = q;
          best_place = candidate;
        }
      }
      mesh.nodes[node] = best_place;
      if (best_place != start) improved = true;
      for (int c = 0; c < 3; ++c) move[node][c] = best_place[c] - reference[node][c];
    }
    if (!improved) break;
    ++report.smoothing_rounds;
    place();
  }
  // A cavity edge node still bends a poor tet's edge out of shape: it first moves with its edge's
  // two vertices instead (the mean of their moves, keeping the mesher's curve of the sharp
  // surface), and where the tet stays poor, sits at their midpoint (a straight edge).
  if (mesh.nodes_per_tet == 10)
    for (const bool straight : {false, true}) {
      const MeshQuality quality = measure_quality(mesh);
      for (std::size_t e = 0; e < mesh.tet_count(); ++e) {
        if (mesh.tet_region[e] == needle || quality.tet_scaled_jacobian[e] >= kPoorScaledJacobian) continue;
        const int* tet = mesh.tet(e);
        for (int k = 0; k < 6; ++k) {
          const int middle = tet[4 + k], a = tet[kEdgeEnds[k][0]], b = tet[kEdgeEnds[k][1]];
          if (!on_cavity[middle]) continue;
          for (int c = 0; c < 3; ++c) {
            move[middle][c] = 0.5 * (move[a][c] + move[b][c]);
            if (straight) move[middle][c] += 0.5 * (reference[a][c] + reference[b][c]) - reference[middle][c];
            mesh.nodes[middle][c] = reference[middle][c] + move[middle][c];
          }
          ++(straight ? report.straightened_edges : report.relaxed_edges);
        }
      }
    }
  // Where none of that untangles a tet (its scaled Jacobian still below kLeastScaledJacobian,
  // inverted or nearly so: seen on the r = 1.25 mm, 20°, 0.15 mm tip, whose fillet moves edge nodes
  // by 0.2 mm), each free vertex of it searches for a better place: a compass search on the worst
  // straight-sided shape around it, steps along ±x, ±y, ±z from a quarter of its mean edge length,
  // halved when no step improves.
  std::vector<int> tangled = free_vertices_of_tets_below(kLeastScaledJacobian);
  std::sort(tangled.begin(), tangled.end());
  tangled.erase(std::unique(tangled.begin(), tangled.end()), tangled.end());  // each vertex searched once
  for (int node : tangled) {
    double step = 0.0;
    for (int other : neighbours[node]) step += std::sqrt(squared_distance(mesh.nodes[node], mesh.nodes[other]));
    step *= 0.25 / static_cast<double>(neighbours[node].size());
    double best = worst_around(node);
    for (int halving = 0; halving < kCompassHalvings; ++halving) {
      bool moved = true;
      while (moved) {
        moved = false;
        for (int direction = 0; direction < 6; ++direction) {
          const Point3 start = mesh.nodes[node];
          mesh.nodes[node][direction / 2] += direction % 2 ? -step : step;
          if (const double q = worst_around(node); q > best) {
            best = q;
            moved = true;
          } else {
            mesh.nodes[node] = start;
          }
        }
      }
      step *= 0.5;
    }
    for (int c = 0; c < 3; ++c) move[node][c] = mesh.nodes[node][c] - reference[node][c];
    ++report.untangled_vertices;
  }
  if (!tangled.empty()) place();
  for (std::size_t node = 0; node < nodes; ++node) {
    const Point3& d = move[node];
    const double size = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (size > kMovedM) ++report.moved_nodes;
    report.largest_move_m = std::max(report.largest_move_m, size);
  }
  return report;
}

nlohmann::json to_json(const CavityRounding& rounding) {
  return {{"moved_nodes", rounding.moved_nodes},
          {"largest_move_mm", rounding.largest_move_m * 1e3},
          {"split_needle_nodes", rounding.split_nodes},
          {"smoothing_rounds", rounding.smoothing_rounds},
          {"relaxed_edges", rounding.relaxed_edges},
          {"straightened_edges", rounding.straightened_edges},
          {"untangled_vertices", rounding.untangled_vertices},
          {"tissue_volume_gained_mm3", rounding.tissue_volume_gained_m3 * 1e9}};
}

}  // namespace needlefem
