// Equations: cad_needle.hpp.
#include "physics/contact/cad_needle.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

namespace needlefem::contact {

namespace {

// Dropped eigenvalues of Σ θ n nᵀ (relative to the largest): normal spreads below ~11°.
constexpr double kSpreadCutoff = 1e-2;
// Rear-face facets: vertices within this fraction of the tip's size of z = 0, normal within
// acos(0.999) = 2.6° of -z.
constexpr double kRearTolerance = 1e-6;
constexpr double kRearNormal = 0.999;
// Trimming of the offset surface: tolerance in units of ρ (above the offset's own error on a
// curved face, ρ θ²/2 with θ half the facet angle: 1e-3 ρ for 20 µm facets on a 0.25 mm fillet),
// and bisection steps for a crossing (2^-30 of a facet).
constexpr double kTrimTolerance = 1e-3;
constexpr int kBisections = 30;
// Cut pieces with less area than this times the tip's size squared are dropped.
constexpr double kDegenerate = 1e-18;
// Length of the shaft tube behind the rear face, in tip sizes.
constexpr double kShaftExtension = 1.0;
// Below this fraction of the tip's size the closest point is the point itself (normal: the
// pseudo-normal, G = 0).
constexpr double kOnSurface = 1e-12;
// Gap spline: spacing ρ / kSplineCellsPerRadius (why 6: gap_spline.hpp), grown by the spline where
// its grid would hold more than kSplineNodeLimit nodes.
constexpr double kSplineCellsPerRadius = 6.0;
constexpr double kSplineNodeLimit = 2.5e7;

double dot(const Point3& a, const Point3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Point3 cross(const Point3& a, const Point3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Point3 sub(const Point3& a, const Point3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double norm(const Point3& a) { return std::sqrt(dot(a, a)); }

// Eigen-decomposition of a symmetric 3x3 matrix by cyclic Jacobi rotations: A = V diag(w) Vᵀ,
// eigenvectors in the columns of V (row-major).
void symmetric_eigen(Matrix3 A, std::array<double, 3>& w, Matrix3& V) {
  V = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  for (int sweep = 0; sweep < 50; ++sweep) {
    const double off = A[1] * A[1] + A[2] * A[2] + A[5] * A[5];
    if (off < 1e-30 * (A[0] * A[0] + A[4] * A[4] + A[8] * A[8]) + 1e-300) break;
    for (int p = 0; p < 2; ++p)
      for (int q = p + 1; q < 3; ++q) {
        const double apq = A[3 * p + q];
        if (apq == 0.0) continue;
        const double theta = (A[3 * q + q] - A[3 * p + p]) / (2.0 * apq);
        const double t = (theta >= 0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1.0));
        const double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
        for (int k = 0; k < 3; ++k) {  // A <- Jᵀ A J
          const double akp = A[3 * k + p], akq = A[3 * k + q];
          A[3 * k + p] = c * akp - s * akq;
          A[3 * k + q] = s * akp + c * akq;
        }
        for (int k = 0; k < 3; ++k) {
          const double apk = A[3 * p + k], aqk = A[3 * q + k];
          A[3 * p + k] = c * apk - s * aqk;
          A[3 * q + k] = s * apk + c * aqk;
        }
        for (int k = 0; k < 3; ++k) {
          const double vkp = V[3 * k + p], vkq = V[3 * k + q];
          V[3 * k + p] = c * vkp - s * vkq;
          V[3 * k + q] = s * vkp + c * vkq;
        }
      }
  }
  w = {A[0], A[4], A[8]};
}

// Removes the facets on the rear face (z = 0, facing -z) and extrudes the rim they leave to
// z = -length. Returns the number of facets removed.
std::size_t open_rear_face(TriangleSoup& soup, double tolerance, double length) {
  auto& V = soup.vertices;
  std::vector<std::array<int, 3>> kept;
  std::size_t removed = 0;
  for (const auto& t : soup.triangles) {
    const Point3 n = cross(sub(V[t[1]], V[t[0]]), sub(V[t[2]], V[t[0]]));
    const bool on_rear = std::abs(V[t[0]][2]) <= tolerance && std::abs(V[t[1]][2]) <= tolerance &&
                         std::abs(V[t[2]][2]) <= tolerance && n[2] < -kRearNormal * norm(n);
    if (on_rear) ++removed;
    else kept.push_back(t);
  }
  soup.triangles = std::move(kept);
  std::map<std::pair<int, int>, int> directed;  // edge (a, b) as traversed -> count
  for (const auto& t : soup.triangles)
    for (int a = 0; a < 3; ++a) ++directed[{t[a], t[(a + 1) % 3]}];
  std::map<int, int> behind;  // rim vertex -> its copy at z = -length
  auto copy_of = [&](int v) {
    auto [it, fresh] = behind.emplace(v, static_cast<int>(V.size()));
    if (fresh) V.push_back({V[v][0], V[v][1], -length});
    return it->second;
  };
  std::vector<std::array<int, 3>> tube;
  for (const auto& [edge, count] : directed) {
    const auto [a, b] = edge;
    if (directed.count({b, a})) continue;  // an interior edge
    const int a2 = copy_of(a), b2 = copy_of(b);
    tube.push_back({b, a, a2});
    tube.push_back({b, a2, b2});
  }
  soup.triangles.insert(soup.triangles.end(), tube.begin(), tube.end());
  return removed;
}

// The offset surface: every vertex of `tip` moved inwards by ρ m (cad_needle.hpp), so that its faces
// lie at distance ρ from the tip's. `facet_normal`: each facet's unit normal.
TriangleSoup offset_inwards(const TriangleSoup& tip, double edge_radius, std::vector<Point3>& facet_normal) {
  const std::size_t nv = tip.vertices.size();
  std::vector<Matrix3> normal_sum(nv, Matrix3{});
  std::vector<Point3> normal_rhs(nv, Point3{});
  for (const auto& t : tip.triangles) {
    Point3 n = cross(sub(tip.vertices[t[1]], tip.vertices[t[0]]), sub(tip.vertices[t[2]], tip.vertices[t[0]]));
    const double l = norm(n);
    for (auto& c : n) c /= l;
    facet_normal.push_back(n);
    for (int a = 0; a < 3; ++a) {
      const Point3 e1 = sub(tip.vertices[t[(a + 1) % 3]], tip.vertices[t[a]]);
      const Point3 e2 = sub(tip.vertices[t[(a + 2) % 3]], tip.vertices[t[a]]);
      const double angle = std::acos(std::clamp(dot(e1, e2) / (norm(e1) * norm(e2)), -1.0, 1.0));
      for (int i = 0; i < 3; ++i) {
        normal_rhs[t[a]][i] += angle * n[i];
        for (int j = 0; j < 3; ++j) normal_sum[t[a]][3 * i + j] += angle * n[i] * n[j];
      }
    }
  }
  TriangleSoup offset{tip.vertices, {}};
  for (std::size_t v = 0; v < nv; ++v) {
    std::array<double, 3> w{};
    Matrix3 Q{};
    symmetric_eigen(normal_sum[v], w, Q);
    const double largest = std::max({w[0], w[1], w[2]});
    Point3 m{};
    for (int k = 0; k < 3; ++k) {
      if (!(w[k] > kSpreadCutoff * largest)) continue;
      const Point3 q{Q[k], Q[3 + k], Q[6 + k]};
      const double coefficient = dot(q, normal_rhs[v]) / w[k];
      for (int i = 0; i < 3; ++i) m[i] += coefficient * q[i];
    }
    for (int i = 0; i < 3; ++i) offset.vertices[v][i] -= edge_radius * m[i];
  }
  return offset;
}

}  // namespace

CadNeedleShape::CadNeedleShape(TriangleSoup tip, double edge_radius) : edge_radius_(edge_radius) {
  if (!(edge_radius >= 0.0)) throw std::invalid_argument("the edge radius must not be negative");
  if (const std::size_t open = orient_outward(tip))
    throw std::invalid_argument("its triangulation is not closed (" + std::to_string(open) +
                                " edges not shared by exactly two facets)");
  tip_volume_ = enclosed_volume(tip);
  Point3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (const auto& v : tip.vertices)
    for (int d = 0; d < 3; ++d) lo[d] = std::min(lo[d], v[d]), hi[d] = std::max(hi[d], v[d]);
  scale_ = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  if (open_rear_face(tip, kRearTolerance * scale_, kShaftExtension * scale_) == 0)
    throw std::invalid_argument("it has no rear face on z = 0 facing -z (flush with the entry face)");

  surface_ = std::make_unique<TriangleSurface>(tip);
  if (edge_radius_ == 0.0) {
    core_ = std::make_unique<TriangleSurface>(std::move(tip));
    sign_reliable_.assign(core_->soup().triangles.size(), 1);
    return;
  }

  std::vector<Point3> facet_normal;
  trim_core(tip, offset_inwards(tip, edge_radius_, facet_normal), facet_normal);

  spline_ = std::make_unique<GapSpline>(lo, hi, edge_radius_ / kSplineCellsPerRadius, edge_radius_, true,
                                        kSplineNodeLimit, [this](const Point3& xi) { return project_exact(xi).gap; });
}

void CadNeedleShape::trim_core(const TriangleSoup& tip, TriangleSoup offset, const std::vector<Point3>& facet_normal) {
  const std::size_t nv = tip.vertices.size();
  // Trimmed to the core's boundary {d(y, tip surface) = ρ}: near an edge the offset faces run on
  // past the edge of the core (by ρ tan(θ/2) at an edge whose normals differ by θ), and those
  // parts lie closer than ρ to the tip's surface. With r(y) = d(y, tip surface) - ρ, a vertex is
  // kept where r >= -tolerance (a moved vertex of a curved face lies a little closer than ρ to
  // the facets around it); a triangle with kept and dropped vertices is cut where r falls below
  // the kept vertex's own r (or 0), found by bisection on r itself (not linear along the edge).
  // The cut must not overshoot the core's edge: a face run on by δ beyond it turns the normal by
  // about sqrt(2 δ/d) at distance d (measured: 0.05 rad for δ = 0.2 µm at d = 140 µm).
  const double tolerance = kTrimTolerance * edge_radius_;
  auto r = [&](const Point3& y) { return surface_->closest(y).distance - edge_radius_; };
  std::vector<double> r_at(nv);
#pragma omp parallel for schedule(dynamic, 256)
  for (std::size_t v = 0; v < nv; ++v) r_at[v] = r(offset.vertices[v]);
  auto kept_vertex = [&](int v) { return r_at[v] >= -tolerance; };
  // Per triangle: kept whole, or cut, with the cut point on each edge (a, a+1) whose ends differ
  // (the bisections are the trimming's cost, done on the threads; pieces are assembled in order).
  const std::size_t nt = tip.triangles.size();
  std::vector<char> whole(nt);
  std::vector<std::array<Point3, 3>> cut_point(nt);
#pragma omp parallel for schedule(dynamic, 256)
  for (std::size_t f = 0; f < nt; ++f) {
    const auto& t = tip.triangles[f];
    const Point3 n = cross(sub(offset.vertices[t[1]], offset.vertices[t[0]]), sub(offset.vertices[t[2]], offset.vertices[t[0]]));
    const bool turned = dot(n, facet_normal[f]) <= 0.0;
    whole[f] = kept_vertex(t[0]) && kept_vertex(t[1]) && kept_vertex(t[2]) && !turned;
    if (whole[f]) continue;
    for (int a = 0; a < 3; ++a) {
      const int i = t[a], j = t[(a + 1) % 3];
      if (kept_vertex(i) == kept_vertex(j)) continue;
      const int inner = kept_vertex(i) ? i : j;
      Point3 in = offset.vertices[inner], out = offset.vertices[inner == i ? j : i];
      const double level = std::min(0.0, r_at[inner]);
      for (int k = 0; k < kBisections; ++k) {
        const Point3 mid{0.5 * (in[0] + out[0]), 0.5 * (in[1] + out[1]), 0.5 * (in[2] + out[2])};
        (r(mid) >= level ? in : out) = mid;
      }
      cut_point[f][a] = in;
    }
  }
  std::vector<char> vertex_whole(nv, 1);  // every triangle around it kept whole and unturned
  std::vector<char> triangle_whole;
  for (std::size_t f = 0; f < nt; ++f) {
    const auto& t = tip.triangles[f];
    if (whole[f]) {
      offset.triangles.push_back(t);
      triangle_whole.push_back(1);
      continue;
    }
    for (int a = 0; a < 3; ++a) vertex_whole[t[a]] = 0;
    std::vector<int> polygon;
    for (int a = 0; a < 3; ++a) {
      const int i = t[a], j = t[(a + 1) % 3];
      if (kept_vertex(i)) polygon.push_back(i);
      if (kept_vertex(i) == kept_vertex(j)) continue;
      polygon.push_back(static_cast<int>(offset.vertices.size()));
      offset.vertices.push_back(cut_point[f][a]);
    }
    for (std::size_t k = 1; k + 1 < polygon.size(); ++k) {
      const std::array<int, 3> piece{polygon[0], polygon[k], polygon[k + 1]};
      const Point3 n = cross(sub(offset.vertices[piece[1]], offset.vertices[piece[0]]),
                             sub(offset.vertices[piece[2]], offset.vertices[piece[0]]));
      if (!(norm(n) > kDegenerate * scale_ * scale_)) continue;  // a sliver where the cut meets a vertex
      offset.triangles.push_back(piece);
      triangle_whole.push_back(0);
    }
  }
  if (offset.triangles.empty())
    throw std::invalid_argument("no core is left after moving its faces inwards by needle.edge_radius_um");
  sign_reliable_.resize(offset.triangles.size());
  for (std::size_t f = 0; f < offset.triangles.size(); ++f) {
    const auto& t = offset.triangles[f];
    sign_reliable_[f] = triangle_whole[f] && vertex_whole[t[0]] && vertex_whole[t[1]] && vertex_whole[t[2]];
  }
  core_ = std::make_unique<TriangleSurface>(std::move(offset));
}

ObstacleProjection CadNeedleShape::project(const Point3& xi) const {
  if (spline_)
    if (const std::optional<ObstacleProjection> p = spline_->project(xi)) return *p;
  return project_exact(xi);
}

ObstacleProjection CadNeedleShape::project_exact(const Point3& xi) const {
  const TriangleSurface::Closest c = core_->closest(xi);
  const Point3 offset = sub(xi, c.point);
  // Inside the core iff deeper than ρ inside the tip; the core's own pseudo-normal says so where
  // its triangles around the closest point are whole.
  const bool outside = sign_reliable_[static_cast<std::size_t>(c.triangle)]
                           ? dot(offset, c.pseudo_normal) >= 0.0
                           : surface_->signed_distance(xi) >= -edge_radius_;
  ObstacleProjection p;
  p.gap = (outside ? c.distance : -c.distance) - edge_radius_;
  if (c.distance <= kOnSurface * scale_) {
    p.normal = c.pseudo_normal;
    return p;
  }
  const double sign = outside ? 1.0 : -1.0, d = c.distance;
  const Point3 u{offset[0] / d, offset[1] / d, offset[2] / d};
  for (int i = 0; i < 3; ++i) p.normal[i] = sign * u[i];
  if (c.feature == TriangleSurface::Feature::Face) return p;
  const Point3& t = c.edge_direction;
  const bool edge = c.feature == TriangleSurface::Feature::Edge;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      p.normal_gradient[3 * i + j] = sign * ((i == j ? 1.0 : 0.0) - u[i] * u[j] - (edge ? t[i] * t[j] : 0.0)) / d;
  return p;
}

}  // namespace needlefem::contact
