// Equations: gap_spline.hpp.
#include "physics/contact/gap_spline.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include <fmt/core.h>

namespace needlefem::contact {

namespace {

constexpr long kCoarse = 4;  // the coarse pass samples every fourth node along each axis

// Uniform cubic B-spline weights of the four coefficients around a point at t in [0, 1) of its
// cell, and their first and second derivatives (per cell width).
struct Basis {
  double w[4], d[4], dd[4];
  explicit Basis(double t) {
    const double s = 1.0 - t, t2 = t * t, t3 = t2 * t;
    w[0] = s * s * s / 6.0;
    w[1] = (3.0 * t3 - 6.0 * t2 + 4.0) / 6.0;
    w[2] = (-3.0 * t3 + 3.0 * t2 + 3.0 * t + 1.0) / 6.0;
    w[3] = t3 / 6.0;
    d[0] = -0.5 * s * s;
    d[1] = 1.5 * t2 - 2.0 * t;
    d[2] = -1.5 * t2 + t + 0.5;
    d[3] = 0.5 * t2;
    dd[0] = s;
    dd[1] = 3.0 * t - 2.0;
    dd[2] = 1.0 - 3.0 * t;
    dd[3] = t;
  }
};

// The quasi-interpolant along one axis of a box of values (stride between neighbours, count
// along the axis, `lines` starting offsets); the end nodes keep their samples.
void quasi_interpolate(std::vector<double>& f, const std::vector<std::size_t>& starts, std::size_t stride, long count) {
#pragma omp parallel for schedule(static)
  for (std::size_t l = 0; l < starts.size(); ++l) {
    const std::size_t s = starts[l];
    double previous = f[s];
    for (long i = 1; i + 1 < count; ++i) {
      const std::size_t at = s + static_cast<std::size_t>(i) * stride;
      const double here = f[at];
      f[at] = (-previous + 8.0 * here - f[at + stride]) / 6.0;
      previous = here;
    }
  }
}

}  // namespace

GapSpline::GapSpline(const Point3& lo, const Point3& hi, double spacing, double edge_radius, bool prism_below,
                     double max_nodes, const std::function<double(const Point3&)>& gap)
    : h_(spacing), prism_below_(prism_below) {
  if (!(spacing > 0.0)) throw std::invalid_argument("the gap spline's spacing must be positive");
  if (!(max_nodes >= kMinNodeLimit))
    throw std::invalid_argument(fmt::format("the gap spline's node limit {:g} is below {:g}", max_nodes, kMinNodeLimit));
  double band = 0.0;
  // The grid over [lo, hi] grown by the band and the stencil, for the spacing h_.
  auto lay_out = [&] {
    band = kBandCells * h_;
    const double margin = band + 4.0 * h_;
    Point3 top{};
    for (int a = 0; a < 3; ++a) lo_[a] = lo[a] - margin, top[a] = hi[a] + margin;
    if (prism_below_) {
      // Read for every point deeper than z_floor_: its stencil's nodes (three each way) lie deeper
      // than B + ρ behind the rear face, where the band's closest points are on the shaft.
      lo_[2] = std::min(lo_[2], -(band + edge_radius) - 6.0 * h_);
      z_floor_ = lo_[2] + 3.0 * h_;
    }
    for (int a = 0; a < 3; ++a) n_[a] = static_cast<long>(std::ceil((top[a] - lo_[a]) / h_)) + 1;
    return static_cast<double>(n_[0]) * static_cast<double>(n_[1]) * static_cast<double>(n_[2]);
  };
  for (double nodes = lay_out(); nodes > max_nodes; nodes = lay_out()) h_ *= 1.01 * std::cbrt(nodes / max_nodes);
  auto node = [&](long i, long j, long k) { return Point3{lo_[0] + i * h_, lo_[1] + j * h_, lo_[2] + k * h_}; };

  // Coarse pass: the gap at every fourth node (and the last), to skip the nodes far from the surface.
  long m[3];
  for (int a = 0; a < 3; ++a) m[a] = (n_[a] - 1 + kCoarse - 1) / kCoarse + 1;
  std::vector<double> coarse(static_cast<std::size_t>(m[0] * m[1] * m[2]));
#pragma omp parallel for collapse(2) schedule(dynamic)
  for (long K = 0; K < m[2]; ++K)
    for (long J = 0; J < m[1]; ++J)
      for (long I = 0; I < m[0]; ++I)
        coarse[static_cast<std::size_t>(I + m[0] * (J + m[1] * K))] = gap(node(kCoarse * I, kCoarse * J, kCoarse * K));

  std::vector<double> f(static_cast<std::size_t>(n_[0] * n_[1] * n_[2]));
#pragma omp parallel for collapse(2) schedule(dynamic)
  for (long k = 0; k < n_[2]; ++k)
    for (long j = 0; j < n_[1]; ++j)
      for (long i = 0; i < n_[0]; ++i) {
        const long I = (i + kCoarse / 2) / kCoarse, J = (j + kCoarse / 2) / kCoarse, K = (k + kCoarse / 2) / kCoarse;
        const double gc = coarse[static_cast<std::size_t>(I + m[0] * (J + m[1] * K))];
        const double di = i - kCoarse * I, dj = j - kCoarse * J, dk = k - kCoarse * K;
        const double apart = h_ * std::sqrt(di * di + dj * dj + dk * dk);
        f[index(i, j, k)] = std::abs(gc) - apart > band ? std::copysign(band, gc)
                                                        : std::clamp(gap(node(i, j, k)), -band, band);
      }

  // Coefficients: the quasi-interpolant along x, then y, then z.
  std::vector<std::size_t> starts;
  for (long k = 0; k < n_[2]; ++k)
    for (long j = 0; j < n_[1]; ++j) starts.push_back(index(0, j, k));
  quasi_interpolate(f, starts, 1, n_[0]);
  starts.clear();
  for (long k = 0; k < n_[2]; ++k)
    for (long i = 0; i < n_[0]; ++i) starts.push_back(index(i, 0, k));
  quasi_interpolate(f, starts, static_cast<std::size_t>(n_[0]), n_[1]);
  starts.clear();
  for (long j = 0; j < n_[1]; ++j)
    for (long i = 0; i < n_[0]; ++i) starts.push_back(index(i, j, 0));
  quasi_interpolate(f, starts, static_cast<std::size_t>(n_[0] * n_[1]), n_[2]);
  coefficient_ = std::move(f);
}

std::optional<ObstacleProjection> GapSpline::project(const Point3& xi) const {
  const bool on_floor = prism_below_ && xi[2] < z_floor_;
  double u[3] = {(xi[0] - lo_[0]) / h_, (xi[1] - lo_[1]) / h_, ((on_floor ? z_floor_ : xi[2]) - lo_[2]) / h_};
  long cell[3];
  for (int a = 0; a < 3; ++a) {
    // Cells whose stencil (coefficients cell - 1 .. cell + 2) stays off the end nodes.
    if (!(u[a] >= 2.0 && u[a] < static_cast<double>(n_[a] - 3))) return std::nullopt;
    cell[a] = static_cast<long>(u[a]);
  }
  const Basis bx(u[0] - cell[0]), by(u[1] - cell[1]), bz(u[2] - cell[2]);
  // s (metres), its gradient and Hessian per cell and per cell squared.
  double s = 0.0, g[3] = {0, 0, 0}, H[6] = {0, 0, 0, 0, 0, 0};  // H: xx yy zz xy xz yz
  for (int c = 0; c < 4; ++c)
    for (int b = 0; b < 4; ++b) {
      const double* row = &coefficient_[index(cell[0] - 1, cell[1] - 1 + b, cell[2] - 1 + c)];
      double v = 0.0, vx = 0.0, vxx = 0.0;
      for (int a = 0; a < 4; ++a) {
        const double coefficient = row[a];
        v += bx.w[a] * coefficient;
        vx += bx.d[a] * coefficient;
        vxx += bx.dd[a] * coefficient;
      }
      const double wy = by.w[b], dy = by.d[b], ddy = by.dd[b], wz = bz.w[c], dz = bz.d[c], ddz = bz.dd[c];
      s += v * wy * wz;
      g[0] += vx * wy * wz;
      g[1] += v * dy * wz;
      g[2] += v * wy * dz;
      H[0] += vxx * wy * wz;
      H[1] += v * ddy * wz;
      H[2] += v * wy * ddz;
      H[3] += vx * dy * wz;
      H[4] += vx * wy * dz;
      H[5] += v * dy * dz;
    }
  if (!(std::abs(s) <= kTrustCells * h_)) return std::nullopt;
  if (on_floor) g[2] = H[2] = H[4] = H[5] = 0.0;  // the prism: nothing changes along z
  ObstacleProjection p;
  p.gap = s;
  for (int i = 0; i < 3; ++i) p.normal[i] = g[i] / h_;
  const double hessian[9] = {H[0], H[3], H[4], H[3], H[1], H[5], H[4], H[5], H[2]};
  for (int i = 0; i < 9; ++i) p.normal_gradient[i] = hessian[i] / (h_ * h_);
  return p;
}

}  // namespace needlefem::contact
