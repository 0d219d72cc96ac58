// The solves of the single-precision supernodal factor: forward and back substitution by
// supernodes, the subtrees concurrently and the top part's large supernodes shared by the threads.
// Algorithm and the reasons for it: single_precision_factor.hpp.
#include <omp.h>

#include <algorithm>
#include <atomic>
#include <optional>
#include <thread>

#include "integration/blas_threads.hpp"
#include "integration/single_precision_blas.hpp"
#include "integration/single_precision_factor.hpp"

namespace needlefem {

// One supernode of L z = y (LU: P_s first, L unit lower).
void SinglePrecisionFactor::forward(int s, float* y, float* above, float* gathered) const {
  const int first = super_[s], columns = super_[s + 1] - first;
  const int height = row_start_[s + 1] - row_start_[s], below = height - columns;
  const float* block = values_.data() + value_start_[s];
  const int one = 1;
  const float plus = 1.0f, zero = 0.0f;
  if (lu_)
    for (int c = 0; c < columns; ++c) std::swap(y[first + c], y[first + pivots_[first + c] - 1]);
  strsv_("L", "N", lu_ ? "U" : "N", &columns, block, &height, y + first, &one);
  if (below == 0) return;
  sgemv_("N", &below, &columns, &plus, block + columns, &height, y + first, &one, &zero, gathered, &one);
  const int* below_rows = rows_ + row_start_[s] + columns;
  for (int i = 0; i < below; ++i) {
    const int row = below_rows[i];
    (above && above_row_[row] ? above : y)[row] -= gathered[i];
  }
}

// One supernode of Lᵀ w = z (LU: U w = z).
void SinglePrecisionFactor::backward(int s, float* y, float* gathered) const {
  const int first = super_[s], columns = super_[s + 1] - first;
  const int height = row_start_[s + 1] - row_start_[s], below = height - columns;
  const float* block = values_.data() + value_start_[s];
  const int one = 1;
  const float plus = 1.0f, minus = -1.0f;
  if (below > 0) {
    const int* below_rows = rows_ + row_start_[s] + columns;
    for (int i = 0; i < below; ++i) gathered[i] = y[below_rows[i]];
    const float* right = block + (lu_ ? upper_offset_ : 0) + columns;
    sgemv_("T", &below, &columns, &minus, right, &height, gathered, &one, &plus, y + first, &one);
  }
  if (lu_) strsv_("U", "N", "N", &columns, block, &height, y + first, &one);
  else strsv_("L", "T", "N", &columns, block, &height, y + first, &one);
}

bool SinglePrecisionFactor::solve_shared(int s) const {
  const double columns = super_[s + 1] - super_[s], height = row_start_[s + 1] - row_start_[s];
  return columns * height > kSharedSolveEntries;
}

namespace {

// Thread t's part of [begin, end) split in `threads` contiguous ranges.
std::pair<int, int> share_of(int begin, int end, int t, int threads) {
  const long length = end - begin;
  return {begin + static_cast<int>(length * t / threads), begin + static_cast<int>(length * (t + 1) / threads)};
}

}  // namespace

// The solves' barriers spin whatever OMP_WAIT_POLICY says: their waits last microseconds, and
// under OMP_WAIT_POLICY=passive an OpenMP barrier puts the waiting thread to sleep and wakes it
// through the kernel, which costs more than sharing the top part saves (docs/measurements.md,
// "Speed").
class SinglePrecisionFactor::SpinBarrier {
 public:
  explicit SpinBarrier(int threads) : threads_(threads) {}
  void wait() {
    const int phase = phase_.load(std::memory_order_acquire);
    if (arrived_.fetch_add(1, std::memory_order_acq_rel) == threads_ - 1) {
      arrived_.store(0, std::memory_order_relaxed);  // before the others can leave
      phase_.store(phase + 1, std::memory_order_release);
      return;
    }
    for (long spins = 0; phase_.load(std::memory_order_acquire) == phase; ++spins)
      if (spins > kSpinsBeforeYield) std::this_thread::yield();  // a thread descheduled by another process
  }

 private:
  static constexpr long kSpinsBeforeYield = 1L << 20;
  const int threads_;
  std::atomic<int> arrived_{0}, phase_{0};
};

void SinglePrecisionFactor::forward_shared(int s, float* y, float* gathered, int t, int threads,
                                           SpinBarrier& barrier) const {
  const int first = super_[s], columns = super_[s + 1] - first;
  const int height = row_start_[s + 1] - row_start_[s], below = height - columns;
  const float* block = values_.data() + value_start_[s];
  float* own = y + first;  // the supernode's rows of y
  const int one = 1;
  const float plus = 1.0f, minus = -1.0f, zero = 0.0f;
  const auto at = [&](int row, int column) { return block + row + static_cast<std::size_t>(column) * height; };
  if (lu_ && t == 0)
    for (int c = 0; c < columns; ++c) std::swap(own[c], own[pivots_[first + c] - 1]);
  for (int p0 = 0; p0 < columns; p0 += kSolvePanel) {
    const int width = std::min(kSolvePanel, columns - p0);
    if (t == 0) strsv_("L", "N", lu_ ? "U" : "N", &width, at(p0, p0), &height, own + p0, &one);
    barrier.wait();
    const auto [r0, r1] = share_of(p0 + width, columns, t, threads);
    const int rows = r1 - r0;
    if (rows > 0) sgemv_("N", &rows, &width, &minus, at(r0, p0), &height, own + p0, &one, &plus, own + r0, &one);
    barrier.wait();
  }
  if (below == 0) return;
  const auto [i0, i1] = share_of(0, below, t, threads);
  const int rows = i1 - i0;
  if (rows > 0) sgemv_("N", &rows, &columns, &plus, at(columns + i0, 0), &height, own, &one, &zero, gathered + i0, &one);
  const int* below_rows = rows_ + row_start_[s] + columns;  // all after the supernode's own rows
  for (int i = i0; i < i1; ++i) y[below_rows[i]] -= gathered[i];
  barrier.wait();
}

void SinglePrecisionFactor::backward_shared(int s, float* y, float* gathered, int t, int threads,
                                            SpinBarrier& barrier) const {
  const int first = super_[s], columns = super_[s + 1] - first;
  const int height = row_start_[s + 1] - row_start_[s], below = height - columns;
  const float* block = values_.data() + value_start_[s];
  float* own = y + first;
  const int one = 1;
  const float plus = 1.0f, minus = -1.0f;
  const auto at = [&](int row, int column) { return block + row + static_cast<std::size_t>(column) * height; };
  if (below > 0) {
    const int* below_rows = rows_ + row_start_[s] + columns;
    const auto [i0, i1] = share_of(0, below, t, threads);
    for (int i = i0; i < i1; ++i) gathered[i] = y[below_rows[i]];
    barrier.wait();
    const float* right = block + (lu_ ? upper_offset_ : 0) + columns;
    const auto [c0, c1] = share_of(0, columns, t, threads);
    const int width = c1 - c0;
    if (width > 0)
      sgemv_("T", &below, &width, &minus, right + static_cast<std::size_t>(c0) * height, &height, gathered, &one,
             &plus, own + c0, &one);
    barrier.wait();
  }
  for (int p0 = (columns - 1) / kSolvePanel * kSolvePanel; p0 >= 0; p0 -= kSolvePanel) {
    const int width = std::min(kSolvePanel, columns - p0);
    if (t == 0) {
      if (lu_) strsv_("U", "N", "N", &width, at(p0, p0), &height, own + p0, &one);
      else strsv_("L", "T", "N", &width, at(p0, p0), &height, own + p0, &one);
    }
    barrier.wait();
    if (p0 == 0) break;
    // The rows above the panel: LU U(0:p0, panel) own(panel); Cholesky L(panel, 0:p0)ᵀ own(panel).
    if (lu_) {
      const auto [r0, r1] = share_of(0, p0, t, threads);
      const int rows = r1 - r0;
      if (rows > 0) sgemv_("N", &rows, &width, &minus, at(r0, p0), &height, own + p0, &one, &plus, own + r0, &one);
    } else {
      const auto [c0, c1] = share_of(0, p0, t, threads);
      const int count = c1 - c0;
      if (count > 0) sgemv_("T", &width, &count, &minus, at(p0, c0), &height, own + p0, &one, &plus, own + c0, &one);
    }
    barrier.wait();
  }
}

void SinglePrecisionFactor::solve(const double* r, double* x) {
  const auto n = static_cast<std::size_t>(n_);
  const int threads = static_cast<int>(thread_ranges_.size());
  float* y = work_.data();
  const BlasThreads one_each(1);
  for (std::size_t k = 0; k < n; ++k) y[k] = static_cast<float>(r[perm_[k]]);  // y = P r
  if (threads > 1) {  // L z = y on the subtrees, shared out as in factor_values()
#pragma omp parallel num_threads(threads)
    for (int planned = omp_get_thread_num(); planned < threads; planned += omp_get_num_threads()) {
      float* above = above_[planned].data();
      for (int j : top_) std::fill(above + super_[j], above + super_[j + 1], 0.0f);
      for (const auto& [first, last] : thread_ranges_[planned])
        for (int s = first; s < last; ++s) forward(s, y, above, gathered_[planned].data());
    }
    for (int j : top_)
      for (int k = super_[j]; k < super_[j + 1]; ++k)
        for (const auto& above : above_) y[k] += above[k];
  }
  float* gathered = gathered_.front().data();
  if (threads > 1) {  // the top part: L z = y, then Lᵀ w = z
    std::optional<SpinBarrier> barrier;
#pragma omp parallel num_threads(threads)
    {
      // Shares and barrier are of the team OpenMP gave: a barrier waiting for more threads than
      // run would never open.
      const int t = omp_get_thread_num(), team = omp_get_num_threads();
#pragma omp single
      barrier.emplace(team);  // implicit barrier: every thread sees it
      for (int s : top_) {
        if (solve_shared(s)) {
          forward_shared(s, y, gathered, t, team, *barrier);
        } else {
          if (t == 0) forward(s, y, nullptr, gathered);
          barrier->wait();
        }
      }
      for (auto s = top_.rbegin(); s != top_.rend(); ++s) {
        if (solve_shared(*s)) {
          backward_shared(*s, y, gathered, t, team, *barrier);
        } else {
          if (t == 0) backward(*s, y, gathered);
          barrier->wait();
        }
      }
    }
  } else {
    for (int s : top_) forward(s, y, nullptr, gathered);
    for (auto s = top_.rbegin(); s != top_.rend(); ++s) backward(*s, y, gathered);
  }
  if (threads > 1) {
#pragma omp parallel num_threads(threads)
    for (int planned = omp_get_thread_num(); planned < threads; planned += omp_get_num_threads())
      for (auto range = thread_ranges_[planned].rbegin(); range != thread_ranges_[planned].rend(); ++range)
        for (int s = range->second - 1; s >= range->first; --s) backward(s, y, gathered_[planned].data());
  }
  for (std::size_t k = 0; k < n; ++k) x[perm_[k]] = static_cast<double>(y[k]);  // x = Pᵀ w
}

}  // namespace needlefem
