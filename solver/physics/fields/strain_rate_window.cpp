#include "physics/fields/strain_rate_window.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "physics/fields/point_quantities.hpp"

namespace needlefem::fields {

StrainRateWindow::StrainRateWindow(double longest_window_s, double spacing_s)
    : longest_window_s_(longest_window_s), spacing_s_(spacing_s) {
  if (!(longest_window_s > 0.0) || !(spacing_s > 0.0))
    throw std::invalid_argument("StrainRateWindow: the window and the snapshot spacing must be positive");
}

bool StrainRateWindow::wants_snapshot(double t) const {
  // Round-off in t (a sum of step sizes) must not skip a snapshot that is due.
  return snapshots_.empty() || t >= snapshots_.back().time + spacing_s_ * (1.0 - 1e-9);
}

void StrainRateWindow::add_snapshot(double t, std::vector<material::Mat3d> deformation_gradients) {
  if (!snapshots_.empty() && !(t > snapshots_.back().time))
    throw std::invalid_argument("StrainRateWindow: snapshots must come in increasing time");
  if (!snapshots_.empty() && deformation_gradients.size() != snapshots_.back().deformation_gradient.size())
    throw std::invalid_argument("StrainRateWindow: every snapshot must hold the same points");
  snapshots_.push_back({t, std::move(deformation_gradients)});
  // Keep the last snapshot at or before t - longest window (it brackets the window's start).
  while (snapshots_.size() >= 2 && snapshots_[1].time <= t - longest_window_s_) snapshots_.pop_front();
}

std::vector<double> StrainRateWindow::rate(double window_s) const {
  if (snapshots_.empty()) throw std::logic_error("StrainRateWindow::rate before any snapshot");
  if (!(window_s > 0.0) || window_s > longest_window_s_ * (1.0 + 1e-12))
    throw std::invalid_argument("StrainRateWindow::rate: the window must be positive and at most the longest");
  const Snapshot& now = snapshots_.back();
  const double start = now.time - window_s;
  // The snapshots a and b around the window's start, and the weight of b.
  std::size_t b = 0;
  while (b < snapshots_.size() && snapshots_[b].time <= start) ++b;
  const std::size_t a = b == 0 ? 0 : b - 1;
  b = std::min(b, snapshots_.size() - 1);
  const double span = snapshots_[b].time - snapshots_[a].time;
  const double weight = (b == a || start <= snapshots_[a].time) ? 0.0 : (start - snapshots_[a].time) / span;

  const std::size_t points = now.deformation_gradient.size();
  std::vector<double> rates(points);
#pragma omp parallel for schedule(static)
  for (std::size_t p = 0; p < points; ++p) {
    const material::Mat3d F_start = (1.0 - weight) * snapshots_[a].deformation_gradient[p] +
                                    weight * snapshots_[b].deformation_gradient[p];
    const material::Mat3d F_relative = now.deformation_gradient[p] * material::inverse(F_start);
    // λ_max² - 1 from b - I: a short window's stretch is close to 1, and ln(1 + x) keeps its digits.
    const material::Mat3d b_minus_identity = F_relative * material::transpose(F_relative) - material::Mat3d::identity();
    rates[p] = 0.5 * std::log1p(symmetric_eigenvalues(b_minus_identity)[2]) / window_s;
  }
  return rates;
}

}  // namespace needlefem::fields
