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

// The steps of round_cavity (cavity_rounding.hpp) over the state they share: every node's move
// from its reference place, the tissue's vertex graph, and which vertices may move freely.
class CavityRounder {
 public:
  CavityRounder(TetMesh& mesh, const std::vector<char>& on_cavity)
      : mesh_(mesh), on_cavity_(on_cavity), nodes_(on_cavity.size()), needle_(mesh.region_index("needle")),
        vertices_(mesh.nodes_per_tet == 10 ? 4 : mesh.nodes_per_tet), move_(nodes_, Point3{}), neighbours_(nodes_),
        tets_at_(nodes_), is_free_(nodes_, 0) {
    for (std::size_t e = 0; e < mesh_.tet_count(); ++e) {
      if (mesh_.tet_region[e] == needle_) continue;
      const int* tet = mesh_.tet(e);
      for (int a = 0; a < vertices_; ++a)
        for (int b = 0; b < vertices_; ++b)
          if (a != b) neighbours_[tet[a]].push_back(tet[b]);
    }
  }

  // Step 1: every cavity node's move onto the surface.
  void project_cavity(const std::function<Point3(const Point3&)>& closest_point) {
    for (std::size_t node = 0; node < nodes_; ++node) {
      if (!on_cavity_[node]) continue;
      const Point3& X = mesh_.nodes[node];
      const Point3 x = closest_point(X);
      move_[node] = {x[0] - X[0], x[1] - X[1], x[2] - X[2]};
    }
  }

  // Step 2: the free vertices within kLayers edges of the cavity take the mean move of their
  // neighbours (a discrete harmonic extension, by Jacobi sweeps), so the cavity's move fades over
  // several element layers instead of deforming the first one alone. Then every node is placed.
  void extend_moves() {
    // Fixed nodes: the cavity's (moved onto the needle) and every other boundary node (not moved).
    std::vector<char> fixed(on_cavity_);
    for (const auto& [name, faces] : mesh_.surface_faces)
      if (!needle_group(name))
        for (int node : faces) fixed[node] = 1;
    std::vector<int> layer(nodes_, -1), front;
    for (std::size_t node = 0; node < nodes_; ++node)
      if (on_cavity_[node] && !neighbours_[node].empty()) {
        layer[node] = 0;
        front.push_back(static_cast<int>(node));
      }
    for (int depth = 1; depth <= kLayers; ++depth) {
      std::vector<int> next;
      for (int node : front)
        for (int other : neighbours_[node])
          if (layer[other] < 0) {
            layer[other] = depth;
            next.push_back(other);
            if (!fixed[other] && depth < kLayers) free_vertices_.push_back(other);
          }
      front.swap(next);
    }
    // The weights 1/distance² of each free vertex's neighbours, fixed over the sweeps.
    std::vector<std::vector<double>> weight(free_vertices_.size());
    for (std::size_t i = 0; i < free_vertices_.size(); ++i)
      for (int other : neighbours_[free_vertices_[i]])
        weight[i].push_back(1.0 / squared_distance(mesh_.nodes[free_vertices_[i]], mesh_.nodes[other]));
    for (int sweep = 0; sweep < kSweeps; ++sweep) {
      std::vector<Point3> updated(free_vertices_.size());
      for (std::size_t i = 0; i < free_vertices_.size(); ++i) {
        const auto& around = neighbours_[free_vertices_[i]];
        Point3 sum{};
        double weights = 0.0;
        for (std::size_t j = 0; j < around.size(); ++j) {
          weights += weight[i][j];
          for (int c = 0; c < 3; ++c) sum[c] += weight[i][j] * move_[around[j]][c];
        }
        for (int c = 0; c < 3; ++c) updated[i][c] = sum[c] / weights;
      }
      for (std::size_t i = 0; i < free_vertices_.size(); ++i) move_[free_vertices_[i]] = updated[i];
    }
    reference_.assign(mesh_.nodes.begin(), mesh_.nodes.begin() + static_cast<long>(nodes_));
    place();
    for (int node : free_vertices_) is_free_[node] = 1;
    for (std::size_t e = 0; e < mesh_.tet_count(); ++e)
      if (mesh_.tet_region[e] != needle_)
        for (int a = 0; a < vertices_; ++a) tets_at_[mesh_.tet(e)[a]].push_back(static_cast<int>(e));
  }

  // Step 3, first part: where a tet next to a sharp edge is squeezed (the edge's nodes move by up
  // to ρ(1/sin(θ/2) - 1), about an edge element's size on the coarsest meshes), each free vertex of
  // it moves to the best of a few candidate places (towards the centroid of its neighbours, or
  // along with the cavity vertex next to it that moved most) by the worst shape
  // (straight_tet_quality) of the tets around it, and only if that improves, until every tissue
  // tet's scaled Jacobian is at least kPoorScaledJacobian or a round finds nothing better.
  // Returns the rounds that moved a vertex.
  int smooth_poor_tets() {
    int rounds = 0;
    for (int round = 0; round < kSmoothingRounds; ++round) {
      bool improved = false;
      for (int node : free_vertices_of_tets_below(kPoorScaledJacobian)) improved |= move_to_best_candidate(node);
      if (!improved) break;
      ++rounds;
      place();
    }
    return rounds;
  }

  // Step 3, second part: a cavity edge node still bends a poor tet's edge out of shape: it first
  // moves with its edge's two vertices instead (the mean of their moves, keeping the mesher's curve
  // of the sharp surface), and where the tet stays poor, sits at their midpoint (a straight edge).
  void relax_cavity_edges(CavityRounding& report) {
    if (mesh_.nodes_per_tet != 10) return;
    for (const bool straight : {false, true}) {
      const MeshQuality quality = measure_quality(mesh_);
      for (std::size_t e = 0; e < mesh_.tet_count(); ++e) {
        if (mesh_.tet_region[e] == needle_ || quality.tet_scaled_jacobian[e] >= kPoorScaledJacobian) continue;
        const int* tet = mesh_.tet(e);
        for (int k = 0; k < 6; ++k) {
          const int middle = tet[4 + k], a = tet[kEdgeEnds[k][0]], b = tet[kEdgeEnds[k][1]];
          if (!on_cavity_[middle]) continue;
          if (straight) {
            straighten_edge(middle, a, b);
          } else {
            for (int c = 0; c < 3; ++c) {
              move_[middle][c] = 0.5 * (move_[a][c] + move_[b][c]);
              mesh_.nodes[middle][c] = reference_[middle][c] + move_[middle][c];
            }
          }
          ++(straight ? report.straightened_edges : report.relaxed_edges);
        }
      }
    }
  }

  // Step 4: where none of that untangles a tet (its scaled Jacobian still below
  // kLeastScaledJacobian, inverted or nearly so: seen on the r = 1.25 mm, 20°, 0.15 mm tip, whose
  // fillet moves edge nodes by 0.2 mm), each free vertex of it searches for a better place: a
  // compass search on the worst straight-sided shape around it, steps along ±x, ±y, ±z from a
  // quarter of its mean edge length, halved when no step improves. Returns the vertices searched.
  std::size_t untangle() {
    std::vector<int> tangled = free_vertices_of_tets_below(kLeastScaledJacobian);
    std::sort(tangled.begin(), tangled.end());
    tangled.erase(std::unique(tangled.begin(), tangled.end()), tangled.end());  // each vertex searched once
    for (int node : tangled) compass_search(node);
    if (!tangled.empty()) place();
    return tangled.size();
  }

  // Step 5: a TET10 tissue tet still inverted (det J <= 0 somewhere) has all its edges made
  // straight, each mid-edge node at the midpoint of its end vertices. Its straight-sided shape then
  // decides: the curvature gmsh's high-order optimiser gave its interior edges (up to a fifth of
  // their length next to a curved cavity), added to the cavity's move, is what inverted it (seen at
  // the lancet point of the Quincke tip, cases/tips/quincke.toml). A cavity edge made straight
  // leaves the rounded surface by its sagitta, as in step 3. Straight edges are shared, so the
  // neighbours are measured again, a few rounds at most. Returns the tets straightened.
  std::size_t straighten_inverted_tets() {
    constexpr int kRounds = 4;
    std::size_t straightened = 0;
    if (mesh_.nodes_per_tet != 10) return straightened;
    for (int round = 0; round < kRounds; ++round) {
      const MeshQuality quality = measure_quality(mesh_);
      std::size_t this_round = 0;
      for (std::size_t e = 0; e < mesh_.tet_count(); ++e) {
        if (mesh_.tet_region[e] == needle_ || quality.tet_scaled_jacobian[e] > 0.0) continue;
        if (!(straight_tet_quality(mesh_, e) > 0.0)) continue;  // inverted when straight too: nothing to gain
        const int* tet = mesh_.tet(e);
        for (int k = 0; k < 6; ++k) straighten_edge(tet[4 + k], tet[kEdgeEnds[k][0]], tet[kEdgeEnds[k][1]]);
        ++this_round;
      }
      if (this_round == 0) break;
      straightened += this_round;
    }
    return straightened;
  }

  // The nodes that moved and the largest move.
  void measure_moves(CavityRounding& report) const {
    for (std::size_t node = 0; node < nodes_; ++node) {
      const Point3& d = move_[node];
      const double size = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      if (size > kMovedM) ++report.moved_nodes;
      report.largest_move_m = std::max(report.largest_move_m, size);
    }
  }

 private:
  // Every node at its reference place plus its move; TET10 edge nodes off the cavity first take
  // the mean move of their edge's two vertices.
  void place() {
    if (mesh_.nodes_per_tet == 10)
      for (std::size_t e = 0; e < mesh_.tet_count(); ++e) {
        if (mesh_.tet_region[e] == needle_) continue;
        const int* tet = mesh_.tet(e);
        for (int k = 0; k < 6; ++k) {
          const int middle = tet[4 + k], a = tet[kEdgeEnds[k][0]], b = tet[kEdgeEnds[k][1]];
          if (!on_cavity_[middle])
            for (int c = 0; c < 3; ++c) move_[middle][c] = 0.5 * (move_[a][c] + move_[b][c]);
        }
      }
    for (std::size_t node = 0; node < nodes_; ++node)
      for (int c = 0; c < 3; ++c) mesh_.nodes[node][c] = reference_[node][c] + move_[node][c];
  }

  // The mid-edge node `middle` of the edge (a, b) at the midpoint of its end vertices: a straight
  // edge (steps 3 and 5).
  void straighten_edge(int middle, int a, int b) {
    for (int c = 0; c < 3; ++c) {
      mesh_.nodes[middle][c] = 0.5 * (mesh_.nodes[a][c] + mesh_.nodes[b][c]);
      move_[middle][c] = mesh_.nodes[middle][c] - reference_[middle][c];
    }
  }

  double worst_around(int node) const {
    double worst = 1.0;
    for (int e : tets_at_[node]) worst = std::min(worst, straight_tet_quality(mesh_, static_cast<std::size_t>(e)));
    return worst;
  }

  // The free vertices of the tissue tets whose scaled Jacobian is below `least` (with repeats).
  std::vector<int> free_vertices_of_tets_below(double least) const {
    const MeshQuality quality = measure_quality(mesh_);
    std::vector<int> found;
    for (std::size_t e = 0; e < mesh_.tet_count(); ++e)
      if (mesh_.tet_region[e] != needle_ && quality.tet_scaled_jacobian[e] < least)
        for (int a = 0; a < vertices_; ++a)
          if (is_free_[mesh_.tet(e)[a]]) found.push_back(mesh_.tet(e)[a]);
    return found;
  }

  // Step 3's candidate places for one free vertex; true when it moved.
  bool move_to_best_candidate(int node) {
    Point3 centroid{}, follow{};
    double largest = 0.0;
    for (int other : neighbours_[node]) {
      for (int c = 0; c < 3; ++c) centroid[c] += mesh_.nodes[other][c] / static_cast<double>(neighbours_[node].size());
      const double size = squared_distance(move_[other], Point3{});
      if (on_cavity_[other] && size > largest) {
        largest = size;
        follow = move_[other];
      }
    }
    const Point3 start = mesh_.nodes[node];
    std::vector<Point3> candidates;
    for (double s : {0.25, 0.5, 0.75, 1.0})
      candidates.push_back({start[0] + s * (centroid[0] - start[0]), start[1] + s * (centroid[1] - start[1]),
                            start[2] + s * (centroid[2] - start[2])});
    for (double s : {0.5, 1.0})
      candidates.push_back({reference_[node][0] + s * follow[0], reference_[node][1] + s * follow[1],
                            reference_[node][2] + s * follow[2]});
    double best = worst_around(node);
    Point3 best_place = start;
    for (const Point3& candidate : candidates) {
      mesh_.nodes[node] = candidate;
      if (const double q = worst_around(node); q > best) {
        best = q;
        best_place = candidate;
      }
    }
    mesh_.nodes[node] = best_place;
    for (int c = 0; c < 3; ++c) move_[node][c] = best_place[c] - reference_[node][c];
    return best_place != start;
  }

  // Step 4's compass search for one vertex.
  void compass_search(int node) {
    double step = 0.0;
    for (int other : neighbours_[node]) step += std::sqrt(squared_distance(mesh_.nodes[node], mesh_.nodes[other]));
    step *= 0.25 / static_cast<double>(neighbours_[node].size());
    double best = worst_around(node);
    for (int halving = 0; halving < kCompassHalvings; ++halving) {
      bool moved = true;
      while (moved) {
        moved = false;
        for (int direction = 0; direction < 6; ++direction) {
          const Point3 start = mesh_.nodes[node];
          mesh_.nodes[node][direction / 2] += direction % 2 ? -step : step;
          if (const double q = worst_around(node); q > best) {
            best = q;
            moved = true;
          } else {
            mesh_.nodes[node] = start;
          }
        }
      }
      step *= 0.5;
    }
    for (int c = 0; c < 3; ++c) move_[node][c] = mesh_.nodes[node][c] - reference_[node][c];
  }

  TetMesh& mesh_;
  const std::vector<char>& on_cavity_;
  const std::size_t nodes_;  // the mesh's nodes before the needle's copies were made
  const int needle_, vertices_;
  std::vector<Point3> move_, reference_;
  std::vector<std::vector<int>> neighbours_, tets_at_;  // tissue tets only
  std::vector<int> free_vertices_;
  std::vector<char> is_free_;
};

}  // namespace

CavityRounding round_cavity(TetMesh& mesh, const std::function<Point3(const Point3&)>& closest_point) {
  CavityRounding report;
  const auto cavity = mesh.surface_faces.find("cavity");
  if (cavity == mesh.surface_faces.end()) return report;
  std::vector<char> on_cavity(mesh.nodes.size(), 0);
  for (int node : cavity->second) on_cavity[node] = 1;
  report.split_nodes = split_needle_nodes(mesh, on_cavity);
  CavityRounder rounder(mesh, on_cavity);
  rounder.project_cavity(closest_point);
  rounder.extend_moves();
  report.smoothing_rounds = rounder.smooth_poor_tets();
  rounder.relax_cavity_edges(report);
  report.untangled_vertices = rounder.untangle();
  report.straightened_tets = rounder.straighten_inverted_tets();
  rounder.measure_moves(report);
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
          {"straightened_tets", rounding.straightened_tets},
          {"tissue_volume_gained_mm3", rounding.tissue_volume_gained_m3 * 1e9}};
}

}  // namespace needlefem
