// Equations: triangle_surface.hpp.
#include "physics/contact/triangle_surface.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdint>
#include <unordered_map>
#include <stdexcept>
#include <utility>

namespace needlefem::contact {

namespace {

Point3 sub(const Point3& a, const Point3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Point3 add(const Point3& a, const Point3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
Point3 scale(const Point3& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
double dot(const Point3& a, const Point3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Point3 cross(const Point3& a, const Point3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double norm(const Point3& a) { return std::sqrt(dot(a, a)); }
Point3 unit(const Point3& a) {
  const double l = norm(a);
  return l > 0.0 ? scale(a, 1.0 / l) : Point3{0.0, 0.0, 0.0};
}

// Closest point of triangle abc to p (Ericson §5.1.5) and its feature: -1 face, 0..2 the vertex
// a, b, c, 3..5 the edge ab, bc, ca.
std::pair<Point3, int> closest_on_triangle(const Point3& p, const Point3& a, const Point3& b, const Point3& c) {
  const Point3 ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) return {a, 0};
  const Point3 bp = sub(p, b);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return {b, 1};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return {add(a, scale(ab, d1 / (d1 - d3))), 3};
  const Point3 cp = sub(p, c);
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return {c, 2};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return {add(a, scale(ac, d2 / (d2 - d6))), 5};
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
    return {add(b, scale(sub(c, b), (d4 - d3) / ((d4 - d3) + (d5 - d6)))), 4};
  const double denom = 1.0 / (va + vb + vc);
  return {add(a, add(scale(ab, vb * denom), scale(ac, vc * denom))), -1};
}

constexpr int kLeafSize = 4;

// An undirected edge's key: its two vertex indices, smaller first.
std::uint64_t edge_key(int a, int b) {
  const auto [lo, hi] = std::minmax(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(lo)) << 32) | static_cast<std::uint32_t>(hi);
}

}  // namespace

TriangleSurface::TriangleSurface(TriangleSoup soup) : soup_(std::move(soup)) {
  const auto& V = soup_.vertices;
  const auto& T = soup_.triangles;
  if (T.empty()) throw std::invalid_argument("TriangleSurface: no triangles");
  face_normals_.resize(T.size());
  vertex_normals_.assign(V.size(), Point3{});
  std::unordered_map<std::uint64_t, Point3> edge_sum;
  edge_sum.reserve(2 * T.size());
  for (std::size_t t = 0; t < T.size(); ++t) {
    const auto& [i, j, k] = T[t];
    face_normals_[t] = unit(cross(sub(V[j], V[i]), sub(V[k], V[i])));
    const int corner[3] = {i, j, k};
    for (int a = 0; a < 3; ++a) {
      const int p = corner[a], q = corner[(a + 1) % 3], r = corner[(a + 2) % 3];
      const Point3 e1 = unit(sub(V[q], V[p])), e2 = unit(sub(V[r], V[p]));
      const double angle = std::acos(std::clamp(dot(e1, e2), -1.0, 1.0));
      vertex_normals_[p] = add(vertex_normals_[p], scale(face_normals_[t], angle));
      auto& sum = edge_sum[edge_key(p, q)];
      sum = add(sum, face_normals_[t]);
    }
  }
  for (auto& n : vertex_normals_) n = unit(n);
  edge_normals_.resize(T.size());
  for (std::size_t t = 0; t < T.size(); ++t)
    for (int a = 0; a < 3; ++a) edge_normals_[t][a] = unit(edge_sum[edge_key(T[t][a], T[t][(a + 1) % 3])]);

  order_.resize(T.size());
  for (std::size_t t = 0; t < T.size(); ++t) order_[t] = static_cast<int>(t);
  nodes_.reserve(2 * T.size() / kLeafSize + 1);
  build(0, static_cast<int>(T.size()));
}

int TriangleSurface::build(int first, int count) {
  const auto& V = soup_.vertices;
  const auto& T = soup_.triangles;
  Node node;
  node.lo = {std::numeric_limits<double>::max(), std::numeric_limits<double>::max(), std::numeric_limits<double>::max()};
  node.hi = {std::numeric_limits<double>::lowest(), std::numeric_limits<double>::lowest(),
             std::numeric_limits<double>::lowest()};
  for (int i = first; i < first + count; ++i)
    for (int a = 0; a < 3; ++a)
      for (int d = 0; d < 3; ++d) {
        node.lo[d] = std::min(node.lo[d], V[T[order_[i]][a]][d]);
        node.hi[d] = std::max(node.hi[d], V[T[order_[i]][a]][d]);
      }
  const int id = static_cast<int>(nodes_.size());
  nodes_.push_back(node);
  if (count <= kLeafSize) {
    Node& leaf = nodes_[id];
    leaf.first = first;
    leaf.count = count;
    // Mean normal, each face's turned to agree with the first's (a leaf's triangles need not be
    // consistently oriented); a leaf folded over an edge gets a thick slab, never a wrong one.
    for (int i = first; i < first + count; ++i) {
      const Point3& n = face_normals_[static_cast<std::size_t>(order_[i])];
      leaf.slab_normal = add(leaf.slab_normal, scale(n, dot(n, face_normals_[order_[first]]) < 0.0 ? -1.0 : 1.0));
    }
    leaf.slab_normal = unit(leaf.slab_normal);
    leaf.slab_lo = std::numeric_limits<double>::max();
    leaf.slab_hi = std::numeric_limits<double>::lowest();
    for (int i = first; i < first + count; ++i)
      for (int a = 0; a < 3; ++a) {
        const double s = dot(leaf.slab_normal, V[T[order_[i]][a]]);
        leaf.slab_lo = std::min(leaf.slab_lo, s);
        leaf.slab_hi = std::max(leaf.slab_hi, s);
      }
    return id;
  }
  int axis = 0;
  for (int d = 1; d < 3; ++d)
    if (node.hi[d] - node.lo[d] > node.hi[axis] - node.lo[axis]) axis = d;
  auto centroid = [&](int t) { return V[T[t][0]][axis] + V[T[t][1]][axis] + V[T[t][2]][axis]; };
  const int half = count / 2;
  std::nth_element(order_.begin() + first, order_.begin() + first + half, order_.begin() + first + count,
                   [&](int a, int b) { return centroid(a) < centroid(b); });
  const int left = build(first, half);
  const int right = build(first + half, count - half);
  nodes_[id].left = left;
  nodes_[id].right = right;
  return id;
}

void TriangleSurface::test_triangle(int t, const Point3& x, Closest& best) const {
  const auto& [i, j, k] = soup_.triangles[static_cast<std::size_t>(t)];
  const auto& V = soup_.vertices;
  const auto [p, feature] = closest_on_triangle(x, V[i], V[j], V[k]);
  const double d = norm(sub(x, p));
  if (!(d < best.distance)) return;  // also a NaN from a degenerate triangle
  best.point = p;
  best.distance = d;
  best.triangle = t;
  const int corner[3] = {i, j, k};
  if (feature < 0) {
    best.feature = Feature::Face;
    best.pseudo_normal = face_normals_[static_cast<std::size_t>(t)];
  } else if (feature < 3) {
    best.feature = Feature::Vertex;
    best.pseudo_normal = vertex_normals_[static_cast<std::size_t>(corner[feature])];
  } else {
    const int e = feature == 3 ? 0 : feature == 4 ? 1 : 2;
    best.feature = Feature::Edge;
    best.pseudo_normal = edge_normals_[static_cast<std::size_t>(t)][e];
    best.edge_direction = unit(sub(V[corner[(e + 1) % 3]], V[corner[e]]));
  }
}

TriangleSurface::Closest TriangleSurface::closest_brute_force(const Point3& x) const {
  Closest best;
  best.distance = std::numeric_limits<double>::max();
  for (std::size_t t = 0; t < soup_.triangles.size(); ++t) test_triangle(static_cast<int>(t), x, best);
  return best;
}

TriangleSurface::Closest TriangleSurface::closest(const Point3& x) const {
  Closest best;
  best.distance = std::numeric_limits<double>::max();
  auto box_distance2 = [&](const Node& n) {
    double d2 = 0.0;
    for (int d = 0; d < 3; ++d) {
      const double out = x[d] < n.lo[d] ? n.lo[d] - x[d] : x[d] > n.hi[d] ? x[d] - n.hi[d] : 0.0;
      d2 += out * out;
    }
    return d2;
  };
  constexpr int kMaxDepth = 128;
  std::array<std::pair<int, double>, kMaxDepth> stack{};
  int top = 0;
  stack[top++] = {0, box_distance2(nodes_[0])};
  while (top > 0) {
    const auto [id, d2] = stack[--top];
    if (d2 >= best.distance * best.distance) continue;
    const Node& n = nodes_[static_cast<std::size_t>(id)];
    if (n.left < 0) {
      // Distance to the slab, less a round-off margin so that it stays a lower bound.
      const double s = dot(n.slab_normal, x);
      const double slab = std::max(n.slab_lo - s, s - n.slab_hi) - 1e-12 * (std::abs(s) + best.distance);
      if (slab >= best.distance) continue;
      for (int i = n.first; i < n.first + n.count; ++i) test_triangle(order_[static_cast<std::size_t>(i)], x, best);
      continue;
    }
    const double dl = box_distance2(nodes_[static_cast<std::size_t>(n.left)]);
    const double dr = box_distance2(nodes_[static_cast<std::size_t>(n.right)]);
    // The nearer child is popped first.
    if (dl < dr) {
      stack[top++] = {n.right, dr};
      stack[top++] = {n.left, dl};
    } else {
      stack[top++] = {n.left, dl};
      stack[top++] = {n.right, dr};
    }
  }
  return best;
}

double TriangleSurface::signed_distance(const Point3& x) const {
  const Closest c = closest(x);
  return dot(sub(x, c.point), c.pseudo_normal) < 0.0 ? -c.distance : c.distance;
}

std::size_t orient_outward(TriangleSoup& soup) {
  auto& T = soup.triangles;
  std::unordered_map<std::uint64_t, std::vector<int>> users;  // undirected edge -> triangles
  users.reserve(2 * T.size());
  for (std::size_t t = 0; t < T.size(); ++t)
    for (int a = 0; a < 3; ++a) users[edge_key(T[t][a], T[t][(a + 1) % 3])].push_back(static_cast<int>(t));
  std::size_t open = 0;
  for (const auto& [edge, list] : users) open += list.size() != 2;
  // Breadth-first: a neighbour that traverses a shared edge in the same direction is flipped.
  auto directed = [&](int t, int a, int b) {
    for (int k = 0; k < 3; ++k)
      if (T[t][k] == a && T[t][(k + 1) % 3] == b) return true;
    return false;
  };
  std::vector<char> done(T.size(), 0);
  for (std::size_t seed = 0; seed < T.size(); ++seed) {
    if (done[seed]) continue;
    std::vector<int> queue{static_cast<int>(seed)}, component;
    done[seed] = 1;
    while (!queue.empty()) {
      const int t = queue.back();
      queue.pop_back();
      component.push_back(t);
      for (int a = 0; a < 3; ++a) {
        const int p = T[t][a], q = T[t][(a + 1) % 3];
        for (int u : users[edge_key(p, q)]) {
          if (u == t || done[u]) continue;
          if (directed(u, p, q)) std::swap(T[u][1], T[u][2]);
          done[u] = 1;
          queue.push_back(u);
        }
      }
    }
    TriangleSoup part{soup.vertices, {}};
    for (int t : component) part.triangles.push_back(T[t]);
    if (enclosed_volume(part) < 0.0)
      for (int t : component) std::swap(T[t][1], T[t][2]);
  }
  return open;
}

double enclosed_volume(const TriangleSoup& soup) {
  double six_v = 0.0;
  for (const auto& [i, j, k] : soup.triangles)
    six_v += dot(soup.vertices[i], cross(soup.vertices[j], soup.vertices[k]));
  return six_v / 6.0;
}

}  // namespace needlefem::contact
