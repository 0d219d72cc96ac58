// Algorithm and the reasons for it: single_precision_factor.hpp.
#include "integration/single_precision_factor.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include <cholmod.h>

#include "integration/blas_threads.hpp"
#include "integration/single_precision_blas.hpp"

namespace needlefem {

namespace {

// Subtracts an update C (count x width, column-major) from a panel of supernode j (first column
// k1, leading dimension height): C's column jj from j's column column_rows[jj] - k1, its row ii
// from j's row map[rows[ii]]. lower_only: rows ii >= jj only (rows then starts at column_rows).
void subtract_update(float* panel, int height, int k1, const int* column_rows, int width, const int* rows, int count,
                     const std::vector<int>& map, const float* c, bool lower_only) {
  for (int jj = 0; jj < width; ++jj) {
    float* target = panel + static_cast<std::size_t>(column_rows[jj] - k1) * height;
    const float* from = c + static_cast<std::size_t>(jj) * count;
    for (int ii = lower_only ? jj : 0; ii < count; ++ii) target[map[rows[ii]]] -= from[ii];
  }
}

}  // namespace

void SinglePrecisionFactor::analyse(const cholmod_factor& symbolic, const cholmod_sparse& lower) {
  if (!symbolic.is_super) throw std::logic_error("single-precision factor: CHOLMOD's symbolic factor is not supernodal");
  super_ = static_cast<const int*>(symbolic.super);
  row_start_ = static_cast<const int*>(symbolic.pi);
  value_start_ = static_cast<const int*>(symbolic.px);
  rows_ = static_cast<const int*>(symbolic.s);
  perm_ = static_cast<const int*>(symbolic.Perm);
  supernodes_ = static_cast<int>(symbolic.nsuper);
  n_ = static_cast<int>(symbolic.n);
  max_update_ = symbolic.maxcsize;
  // L's panels; LU adds Uᵀ's behind them. Reserved for both (address space only until written)
  // so that an LU's growth copies nothing: the copy would hold L's panels three times at once.
  values_.clear();
  values_.reserve(2 * symbolic.xsize);
  values_.assign(symbolic.xsize, 0.0f);
  upper_offset_ = symbolic.xsize;
  work_.assign(n_, 0.0f);
  supernode_of_column_.resize(n_);
  for (int s = 0; s < supernodes_; ++s)
    std::fill(supernode_of_column_.begin() + super_[s], supernode_of_column_.begin() + super_[s + 1], s);

  inverse_.resize(n_);
  for (int k = 0; k < n_; ++k) inverse_[perm_[k]] = k;
  lower_ = &lower;
  const int* column_start = static_cast<const int*>(lower.p);
  const int* row_index = static_cast<const int*>(lower.i);
  target_.resize(column_start[lower.ncol]);
  for (int j = 0; j < static_cast<int>(lower.ncol); ++j)
    for (int p = column_start[j]; p < column_start[j + 1]; ++p) {
      const int a = inverse_[row_index[p]], b = inverse_[j];
      target_[p] = lower_position(std::max(a, b), std::min(a, b));
    }
  lu_target_.clear();
  lu_target_transposed_.clear();
  next_row_.assign(supernodes_, 0);
  next_in_list_.assign(supernodes_, -1);
  plan_subtrees(omp_get_max_threads());
  const std::size_t threads = thread_ranges_.size();
  gathered_.assign(threads, std::vector<float>(symbolic.maxesize));
  workspaces_.clear();
  for (std::size_t t = 0; t < threads; ++t)
    workspaces_.push_back({std::vector<int>(n_), std::vector<float>(max_update_), {}});
  above_.assign(threads > 1 ? threads : 0, std::vector<float>(n_, 0.0f));
  above_row_.assign(n_, 0);
  if (threads > 1)
    for (int j : top_) std::fill(above_row_.begin() + super_[j], above_row_.begin() + super_[j + 1], 1);
}

// Position in values_ of entry (row, column) of P A Pᵀ, row >= column: L's panel of the
// supernode owning the column.
std::size_t SinglePrecisionFactor::lower_position(int row, int column) const {
  const int s = supernode_of_column_[column];
  const int* first = rows_ + row_start_[s];
  const int* last = rows_ + row_start_[s + 1];
  const int* found = std::lower_bound(first, last, row);
  if (found == last || *found != row) throw std::logic_error("single-precision factor: entry outside the factor");
  return value_start_[s] + static_cast<std::size_t>(column - super_[s]) * (last - first) + (found - first);
}

// Position in values_ of entry (row, column) of P A Pᵀ for LU: at or below the diagonal, L's
// panel; above it, in the owning supernode's diagonal block (L's panel holds it whole), else
// in Uᵀ's panel, laid out like L's from upper_offset_.
std::size_t SinglePrecisionFactor::lu_position(int row, int column) const {
  if (row >= column) return lower_position(row, column);
  const int s = supernode_of_column_[row];
  if (column < super_[s + 1]) {
    const auto height = static_cast<std::size_t>(row_start_[s + 1] - row_start_[s]);
    return value_start_[s] + static_cast<std::size_t>(column - super_[s]) * height + (row - super_[s]);
  }
  return upper_offset_ + lower_position(column, row);
}

// Splits the supernodal elimination tree into subtrees for the threads: starting from its roots,
// the heaviest subtree is split (its root moved to the top part, its children becoming subtrees)
// until a largest-first assignment of the subtrees to the threads is within 5 % of even.
void SinglePrecisionFactor::plan_subtrees(int threads) {
  thread_ranges_.assign(std::max(threads, 1), {});
  top_.clear();
  if (threads < 2) {
    top_.resize(supernodes_);
    std::iota(top_.begin(), top_.end(), 0);
    return;
  }
  std::vector<int> parent(supernodes_, -1), size(supernodes_, 1);
  std::vector<double> work(supernodes_, 0.0);
  std::vector<std::vector<int>> children(supernodes_);
  std::vector<int> roots;
  for (int s = 0; s < supernodes_; ++s) {  // postordered: children before parents
    const double columns = super_[s + 1] - super_[s], height = row_start_[s + 1] - row_start_[s];
    work[s] += columns * height * height;
    if (height > columns) {
      parent[s] = supernode_of_column_[rows_[row_start_[s] + static_cast<int>(columns)]];
      work[parent[s]] += work[s];
      size[parent[s]] += size[s];
      children[parent[s]].push_back(s);
    } else {
      roots.push_back(s);
    }
  }
  std::vector<int> subtrees = roots;
  const auto heavier = [&](int a, int b) { return work[a] > work[b]; };
  std::vector<double> load(threads);
  std::vector<std::vector<int>> assigned(threads);
  for (int split = 0; split < 4 * supernodes_; ++split) {
    std::sort(subtrees.begin(), subtrees.end(), heavier);
    std::fill(load.begin(), load.end(), 0.0);
    for (auto& a : assigned) a.clear();
    for (int s : subtrees) {
      const auto lightest = std::min_element(load.begin(), load.end()) - load.begin();
      load[lightest] += work[s];
      assigned[lightest].push_back(s);
    }
    const double total = std::accumulate(load.begin(), load.end(), 0.0);
    if (*std::max_element(load.begin(), load.end()) <= 1.05 * total / threads || children[subtrees.front()].empty())
      break;
    const int heaviest = subtrees.front();
    subtrees.erase(subtrees.begin());
    subtrees.insert(subtrees.end(), children[heaviest].begin(), children[heaviest].end());
    top_.push_back(heaviest);
  }
  for (int t = 0; t < threads; ++t) {
    for (int s : assigned[t]) thread_ranges_[t].emplace_back(s - size[s] + 1, s + 1);
    std::sort(thread_ranges_[t].begin(), thread_ranges_[t].end());
  }
  std::sort(top_.begin(), top_.end());
}

int SinglePrecisionFactor::concurrent_subtrees() const {
  if (thread_ranges_.size() < 2) return 0;
  std::size_t count = 0;
  for (const auto& ranges : thread_ranges_) count += ranges.size();
  return static_cast<int>(count);
}

int SinglePrecisionFactor::shared_solve_supernodes() const {
  if (thread_ranges_.size() < 2) return 0;
  return static_cast<int>(std::count_if(top_.begin(), top_.end(), [&](int s) { return solve_shared(s); }));
}

void SinglePrecisionFactor::link(int d, std::vector<int>& head) {
  const int owner = supernode_of_column_[rows_[row_start_[d] + next_row_[d]]];
  next_in_list_[d] = head[owner];
  head[owner] = d;
}

// Takes the list of supernodes d that update j, with the rows of each in j's columns, and links
// each d to the supernode its next rows update.
void SinglePrecisionFactor::take_updates(int j, std::vector<int>& head, std::vector<Update>& updates) {
  const int k2 = super_[j + 1];
  updates.clear();
  for (int d = head[j], following = -1; d != -1; d = following) {
    following = next_in_list_[d];
    const int d_first_row = row_start_[d], d_height = row_start_[d + 1] - d_first_row;
    Update u{d, next_row_[d], next_row_[d]};
    while (u.p2 < d_height && rows_[d_first_row + u.p2] < k2) ++u.p2;
    updates.push_back(u);
    next_row_[d] = u.p2;
    if (u.p2 < d_height) link(d, head);
  }
}

// Columns [c0, c1) of d's update of j, subtracted from j's block at the rows `map` gives.
// Cholesky: C = L_d(p1+c0:end, :) L_d(p1+c0:p1+c1, :)ᵀ, its lower part. LU: for L's side
// (j's diagonal block whole, and below it) C = L_d(p1:end, :) Uᵀ_d(p1+c0:p1+c1, :)ᵀ; for U's
// side (j's columns as rows of U, right of the diagonal block) C = Uᵀ_d(p2:end, :)
// L_d(p1+c0:p1+c1, :)ᵀ. Each share writes only its own columns of j's panels.
void SinglePrecisionFactor::apply_update(int j, const Update& u, int c0, int c1, const std::vector<int>& map,
                                         std::vector<float>& update) {
  const int k1 = super_[j], height = row_start_[j + 1] - row_start_[j];
  float* block = values_.data() + value_start_[j];
  const int d = u.d, d_columns = super_[d + 1] - super_[d];
  const int d_first_row = row_start_[d], d_height = row_start_[d + 1] - d_first_row;
  const int width = c1 - c0;
  if (width <= 0) return;
  const float one = 1.0f, zero = 0.0f;
  const float* d_block = values_.data() + value_start_[d];
  const int* d_rows = rows_ + d_first_row;
  float* c = update.data();
  if (!lu_) {
    const int below = d_height - u.p1 - c0, further = below - width;
    const float* source = d_block + u.p1 + c0;
    ssyrk_("L", "N", &width, &d_columns, &one, source, &d_height, &zero, c, &below);
    if (further > 0)
      sgemm_("N", "T", &further, &width, &d_columns, &one, source + width, &d_height, source, &d_height, &zero,
             c + width, &below);
    subtract_update(block, height, k1, d_rows + u.p1 + c0, width, d_rows + u.p1 + c0, below, map, c, true);
    return;
  }
  const float* d_upper = d_block + upper_offset_;
  const int all = d_height - u.p1, further = d_height - u.p2;
  sgemm_("N", "T", &all, &width, &d_columns, &one, d_block + u.p1, &d_height, d_upper + u.p1 + c0, &d_height, &zero,
         c, &all);
  subtract_update(block, height, k1, d_rows + u.p1 + c0, width, d_rows + u.p1, all, map, c, false);
  if (further <= 0) return;
  sgemm_("N", "T", &further, &width, &d_columns, &one, d_upper + u.p2, &d_height, d_block + u.p1 + c0, &d_height,
         &zero, c, &further);
  subtract_update(block + upper_offset_, height, k1, d_rows + u.p1 + c0, width, d_rows + u.p2, further, map, c, false);
}

// Cholesky: L_11 L_11ᵀ = A_11. LU: P_1 A_11 = L_11 U_11 with partial pivoting inside the block
// (LAPACK sgetrf); a pivot below kSmallPivot times its column's largest entry in the block
// counts as failed: pivoting stays inside supernodes, so a nearly singular block cannot be
// rescued from outside.
bool SinglePrecisionFactor::factor_diagonal(int j) {
  const int columns = super_[j + 1] - super_[j], height = row_start_[j + 1] - row_start_[j];
  float* block = values_.data() + value_start_[j];
  int info = 0;
  if (!lu_) {
    spotrf_("L", &columns, block, &height, &info);
    if (info != 0) failed_column_ = super_[j] + info - 1;
    return info == 0;
  }
  float* largest = column_largest_.data() + super_[j];
  for (int c = 0; c < columns; ++c) {
    const float* column = block + static_cast<std::size_t>(c) * height;
    largest[c] = 0.0f;
    for (int r = 0; r < columns; ++r) largest[c] = std::max(largest[c], std::abs(column[r]));
  }
  sgetrf_(&columns, &columns, block, &height, pivots_.data() + super_[j], &info);
  for (int c = 0; c < columns; ++c)
    if (!(std::abs(block[static_cast<std::size_t>(c) * height + c]) > kSmallPivot * largest[c])) {
      failed_column_ = super_[j] + c;
      return false;
    }
  return true;
}

// Rows [r0, r1) of j's part below its diagonal block. Cholesky: L_21 = A_21 L_11⁻ᵀ. LU:
// L_21 = A_21 U_11⁻¹, and U_12ᵀ = (P_1 A_12)ᵀ L_11⁻ᵀ on Uᵀ's panel.
void SinglePrecisionFactor::solve_below(int j, int r0, int r1) {
  const int columns = super_[j + 1] - super_[j], height = row_start_[j + 1] - row_start_[j], rows = r1 - r0;
  if (rows <= 0) return;
  const float one = 1.0f;
  float* block = values_.data() + value_start_[j];
  if (!lu_) {
    strsm_("R", "L", "T", "N", &rows, &columns, &one, block, &height, block + columns + r0, &height);
    return;
  }
  strsm_("R", "U", "N", "N", &rows, &columns, &one, block, &height, block + columns + r0, &height);
  float* upper = block + upper_offset_ + columns + r0;
  const int* pivots = pivots_.data() + super_[j];
  for (int c = 0; c < columns; ++c)
    if (pivots[c] - 1 != c)
      std::swap_ranges(upper + static_cast<std::size_t>(c) * height, upper + static_cast<std::size_t>(c) * height + rows,
                       upper + static_cast<std::size_t>(pivots[c] - 1) * height);
  strsm_("R", "L", "T", "U", &rows, &columns, &one, block, &height, upper, &height);
}

void SinglePrecisionFactor::map_rows(int j, std::vector<int>& map) const {
  for (int k = row_start_[j]; k < row_start_[j + 1]; ++k) map[rows_[k]] = k - row_start_[j];
}

void SinglePrecisionFactor::finish(int j, std::vector<int>& head) {
  const int columns = super_[j + 1] - super_[j], height = row_start_[j + 1] - row_start_[j];
  if (height == columns) return;
  next_row_[j] = columns;
  link(j, head);
}

bool SinglePrecisionFactor::factor_range(int first, int last, std::vector<int>& head, Workspace& work) {
  for (int j = first; j < last; ++j) {
    map_rows(j, work.map);
    take_updates(j, head, work.updates);
    for (const Update& u : work.updates) apply_update(j, u, 0, u.p2 - u.p1, work.map, work.update);
    const int columns = super_[j + 1] - super_[j], height = row_start_[j + 1] - row_start_[j];
    if (!factor_diagonal(j)) return false;
    solve_below(j, 0, height - columns);
    finish(j, head);
  }
  return true;
}

// The top part, supernode after supernode, each shared by the threads: its columns for the
// updates, the rows below its diagonal block for the triangular solve. Small supernodes go to
// one thread: a barrier costs more than they do.
bool SinglePrecisionFactor::factor_top(std::vector<int>& head, std::vector<Workspace>& work) {
  // Whether supernode i of the top part factored, by the parity of i: a thread reads entry i % 2
  // after the barrier that ends its single writer; the next writer of that entry, i + 2's, comes
  // after i + 1's barrier, which no thread passes before all have read.
  bool factored[2] = {true, true};
  std::vector<Update>& updates = work.front().updates;
  std::vector<int>& map = work.front().map;
#pragma omp parallel num_threads(static_cast<int>(work.size()))
  {
    // The shares are of the team OpenMP gave, which may be smaller than asked for.
    const int t = omp_get_thread_num(), threads = omp_get_num_threads();
    for (std::size_t i = 0; i < top_.size(); ++i) {
      const int j = top_[i];
      bool& done = factored[i % 2];
      const int columns = super_[j + 1] - super_[j], height = row_start_[j + 1] - row_start_[j];
      const bool shared = threads > 1 && static_cast<double>(columns) * height * height > kSharedSupernodeWork;
      if (!shared) {
#pragma omp single
        done = factor_range(j, j + 1, head, work.front());
        if (!done) break;
        continue;
      }
#pragma omp single
      {
        map_rows(j, map);
        take_updates(j, head, updates);
      }
      // The thread's share: j's columns k1+c_begin..k1+c_end-1, where column c costs the entries of
      // j's panels it updates (Cholesky: height - c; LU: height in L's panel and height - columns in
      // Uᵀ's), so that each share costs about the same.
      const auto column_cost = [&](int c) { return lu_ ? 2.0 * height - columns : static_cast<double>(height - c); };
      const auto boundary = [&](int part) {
        double total = 0.0;
        for (int c = 0; c < columns; ++c) total += column_cost(c);
        const double target = total * part / threads;
        double cost = 0.0;
        int c = 0;
        while (c < columns && cost + column_cost(c) <= target) cost += column_cost(c++);
        return part == threads ? columns : c;
      };
      const int k1 = super_[j], c_begin = boundary(t), c_end = boundary(t + 1);
      for (const Update& u : updates) {  // d's rows p1..p2-1 are j's columns, ascending
        const int* inside = rows_ + row_start_[u.d] + u.p1;
        const int count = u.p2 - u.p1;
        const int c0 = static_cast<int>(std::lower_bound(inside, inside + count, k1 + c_begin) - inside);
        const int c1 = static_cast<int>(std::lower_bound(inside, inside + count, k1 + c_end) - inside);
        apply_update(j, u, c0, c1, map, work[t].update);
      }
#pragma omp barrier
#pragma omp single
      {
        // Its dense factorisation is one LAPACK call: BLAS gets the cores while the team waits.
        const BlasThreads cores(threads);
        done = factor_diagonal(j);
      }
      if (!done) break;
      const int below = height - columns;
      solve_below(j, below * t / threads, below * (t + 1) / threads);
#pragma omp barrier
#pragma omp single
      finish(j, head);
    }
  }
  return factored[0] && factored[1];
}

bool SinglePrecisionFactor::factor(const double* lower_values) {
  lu_ = false;
  const auto entries = static_cast<std::ptrdiff_t>(target_.size());
  zero_values(upper_offset_);
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t p = 0; p < entries; ++p) values_[target_[p]] = static_cast<float>(lower_values[p]);
  return factor_values();
}

bool SinglePrecisionFactor::factor_lu(const double* lower_values, const double* upper_values) {
  lu_ = true;
  const auto entries = static_cast<std::ptrdiff_t>(target_.size());
  if (lu_target_.empty()) {  // the first LU: its positions and Uᵀ's panels
    const int* column_start = static_cast<const int*>(lower_->p);
    const int* row_index = static_cast<const int*>(lower_->i);
    lu_target_.resize(entries);
    lu_target_transposed_.resize(entries);
    for (int j = 0; j < static_cast<int>(lower_->ncol); ++j)
      for (int p = column_start[j]; p < column_start[j + 1]; ++p) {
        const int a = inverse_[row_index[p]], b = inverse_[j];
        lu_target_[p] = lu_position(a, b);
        lu_target_transposed_[p] = lu_position(b, a);
      }
    values_.resize(2 * upper_offset_);
    pivots_.resize(n_);
    column_largest_.resize(n_);
  }
  zero_values(values_.size());
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t p = 0; p < entries; ++p) {
    values_[lu_target_[p]] = static_cast<float>(lower_values[p]);
    values_[lu_target_transposed_[p]] = static_cast<float>(upper_values[p]);
  }
  return factor_values();
}

void SinglePrecisionFactor::zero_values(std::size_t count) {
  const auto size = static_cast<std::ptrdiff_t>(count);
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t k = 0; k < size; ++k) values_[k] = 0.0f;
}

bool SinglePrecisionFactor::factor_values() {
  failed_column_ = -1;
  const int threads = static_cast<int>(thread_ranges_.size());
  const BlasThreads one_each(1);
  std::vector<std::vector<int>> heads(threads, std::vector<int>(supernodes_, -1));
  bool ok = true;
  if (threads > 1) {
    // Thread t takes the subtrees planned for threads t, t + team, ...: OpenMP may give fewer
    // threads than planned (OMP_THREAD_LIMIT, a nested parallel region, dynamic teams).
#pragma omp parallel num_threads(threads) reduction(&& : ok)
    for (int planned = omp_get_thread_num(); planned < threads; planned += omp_get_num_threads())
      for (const auto& [first, last] : thread_ranges_[planned])
        if (ok) ok = factor_range(first, last, heads[planned], workspaces_[planned]);
  }
  if (!ok) return false;
  // The lists of each thread joined into the first's.
  std::vector<int>& head = heads.front();
  for (int j : top_)
    for (int t = 1; t < threads; ++t) {
      if (heads[t][j] == -1) continue;
      int last = heads[t][j];
      while (next_in_list_[last] != -1) last = next_in_list_[last];
      next_in_list_[last] = head[j];
      head[j] = heads[t][j];
    }
  return factor_top(head, workspaces_);
}

}  // namespace needlefem
