// Numeric supernodal Cholesky factorisation A = L Lᵀ, or LU factorisation A = L U of a matrix
// with a symmetric pattern, and their solves in single precision, on the supernodal symbolic
// factor that CHOLMOD's cholmod_analyze computed (its fill-reducing permutation P, postordered
// supernodes and their row structure; CHOLMOD 3 factors in double only, and only by Cholesky).
//
// Algorithm: left-looking supernodal Cholesky as in CHOLMOD's own numeric phase (Chen, Davis,
// Hager & Rajamanickam, ACM TOMS 35(3):22, 2008, §4): supernode j, columns k1..k2-1 of P A Pᵀ,
// gathers the updates C = L_d L_d1ᵀ of every earlier supernode d with rows in k1..k2-1 (BLAS
// ssyrk/sgemm), subtracts them, then factors its diagonal block (spotrf) and solves its rows below
// (strsm). The descendants that update j are found by CHOLMOD's linked lists: after each of its
// updates, d is linked into the list of the supernode owning its next row.
//
// Two levels of parallelism on OpenMP threads: independent subtrees of the supernodal
// elimination tree (chosen so that their work, about ncol·nrow² each, is balanced across the
// threads) are factored concurrently; the supernodes above them (the top separators of the
// nested-dissection ordering, dense and large) afterwards one at a time, each large one shared
// by the threads (its updates split by columns, its rows below the diagonal block by rows). A
// supernode in a subtree only updates supernodes of its own subtree or above, so the threads
// share nothing but the lists of the supernodes above, which each thread keeps for itself until
// the subtrees are done. BLAS runs on one thread inside each: OpenBLAS's own threads spin
// (sched_yield) after every call and take CPU time from the element loops (docs/speed.md). Solves split the same way: the forward substitution runs
// the subtrees concurrently, each thread gathering its updates of the rows above in its own
// vector, then the top part; the back substitution runs the top part, then the subtrees. The top
// part's large supernodes are shared: their diagonal blocks in panels of columns (each panel's
// triangle on one thread, its product with the block's other rows split by rows), the rows below
// split by rows (forward) or the block's columns (back): the dense root separators hold a large
// share of the brain-tip factor, and one thread streams it at a fraction of the memory bandwidth
// two reach (docs/speed.md, first section).
//
// LU: the same supernodes and tree, each holding a panel of L (its diagonal block whole) and one
// of Uᵀ (laid out like L's). Every update has two products, L_d Uᵀ_dᵀ for L's columns and
// Uᵀ_d L_dᵀ for U's rows; the diagonal block is factored with partial pivoting inside it
// (sgetrf, P_s A_ss = L_ss U_ss); then L_21 = A_21 U_ss⁻¹ and U_12 = L_ss⁻¹ P_s A_12. With a
// symmetric pattern the structure of Uᵀ is that of L, and pivoting inside a supernode moves no
// entry out of it. It is static pivoting: a pivot that the block cannot supply fails the
// factorisation (the caller then turns to a pivoting LU). Used for Newton matrices made
// unsymmetric by Coulomb friction, which are mildly so (the friction traction's dependence on the
// normal gap, on the contact surface's unknowns only).
//
// Why: the factor only preconditions GMRES (IDA's Newton-Krylov), where single precision is
// enough (the solution carries a relative error of about κ × 6e-8, as the single-precision solve
// of a double factor did), and CHOLMOD 3's numeric factorisation runs supernode after supernode
// with threads only inside BLAS calls, most of them too small to share. Measured on the 0.4 mm
// brain-tip Newton matrix: docs/speed.md.
#pragma once

#include <string>
#include <vector>

struct cholmod_factor_struct;
struct cholmod_sparse_struct;

namespace needlefem {

class SinglePrecisionFactor {
 public:
  // Structure: CHOLMOD's supernodal symbolic factor of the lower triangle `lower` (stype < 0,
  // columns in the original order). Both must outlive this object's use.
  void analyse(const cholmod_factor_struct& symbolic, const cholmod_sparse_struct& lower);
  // Factor the matrix with these values of `lower` (its x array layout). Returns false if a
  // pivot is not positive (failed_column() tells which column of P A Pᵀ).
  bool factor(const double* lower_values);
  // LU of the unsymmetric matrix A with A(i, j) = lower_values[p] and A(j, i) = upper_values[p]
  // for entry p at row i >= column j of `lower`. Returns false on a pivot below kSmallPivot
  // times its column's largest entry in its diagonal block.
  bool factor_lu(const double* lower_values, const double* upper_values);
  // x = A⁻¹ r (original order), with the last successful factor() or factor_lu().
  void solve(const double* r, double* x);

  long failed_column() const { return failed_column_; }
  // Subtrees factored concurrently (0 on one thread).
  int concurrent_subtrees() const;
  // Supernodes of the top part whose solves the threads share (0 on one thread).
  int shared_solve_supernodes() const;

 private:
  // An update of supernode j by d: d's rows p1..p2-1 (offsets in its row list) lie in j's columns.
  struct Update {
    int d, p1, p2;
  };
  struct Workspace {
    std::vector<int> map;       // per row of P A Pᵀ: its offset in the current supernode's rows
    std::vector<float> update;  // an update matrix C
    std::vector<Update> updates;
  };
  // Supernodes of the top part whose work (columns × rows²) is above this are shared by the
  // threads; the barriers that sharing needs cost more than smaller ones.
  static constexpr double kSharedSupernodeWork = 1e7;
  // The solves read each entry once, so they share supernodes by entries (columns × rows); the
  // panel width trades the triangles' share done on one thread against the barriers.
  static constexpr double kSharedSolveEntries = 2e5;
  static constexpr int kSolvePanel = 128;
  // LU: a pivot below this times its column's largest entry in the diagonal block fails: it
  // would carry single precision's round-off (6e-8 of the column) at a relative 6e-2.
  static constexpr float kSmallPivot = 1e-6f;

  std::size_t lower_position(int row, int column) const;  // in values_, of P A Pᵀ, row >= column
  std::size_t lu_position(int row, int column) const;     // in values_, of P A Pᵀ, any entry
  void zero_values(std::size_t count);
  bool factor_values();  // the numeric factorisation of the values loaded

  bool factor_range(int first, int last, std::vector<int>& head, Workspace& work);
  bool factor_top(std::vector<int>& head, std::vector<Workspace>& work);
  void take_updates(int j, std::vector<int>& head, std::vector<Update>& updates);
  void apply_update(int j, const Update& u, int c0, int c1, const std::vector<int>& map, std::vector<float>& update);
  bool factor_diagonal(int j);
  void solve_below(int j, int r0, int r1);
  void map_rows(int j, std::vector<int>& map) const;
  void finish(int j, std::vector<int>& head);  // links j to the supernode its rows below update
  void link(int d, std::vector<int>& head);
  void plan_subtrees(int threads);
  // One supernode of L z = y: its rows below go to `above` where above_row_ marks them (a thread's
  // own updates of the top part), else to y.
  void forward(int s, float* y, float* above, float* gathered) const;
  void backward(int s, float* y, float* gathered) const;  // one supernode of Lᵀ w = z
  // The same for a supernode of the top part, called by every thread t of a team of `threads`:
  // the diagonal block in panels of kSolvePanel columns, each panel's triangle on one thread and
  // its product with the block's other rows split among the threads, the rows below it too.
  class SpinBarrier;
  void forward_shared(int s, float* y, float* gathered, int t, int threads, SpinBarrier& barrier) const;
  void backward_shared(int s, float* y, float* gathered, int t, int threads, SpinBarrier& barrier) const;
  bool solve_shared(int s) const;  // large enough to share in the solves

  // The symbolic factor (CHOLMOD's arrays): supernode s has columns super_[s]..super_[s+1]-1,
  // rows rows_[row_start_[s]..row_start_[s+1]) (its own columns first, all ascending) and its
  // values column-major from value_start_[s], leading dimension its number of rows.
  const int* super_ = nullptr;
  const int* row_start_ = nullptr;
  const int* value_start_ = nullptr;
  const int* rows_ = nullptr;
  const int* perm_ = nullptr;
  int supernodes_ = 0, n_ = 0;
  std::size_t max_update_ = 0;
  std::vector<int> supernode_of_column_;
  const cholmod_sparse_struct* lower_ = nullptr;
  std::vector<int> inverse_;         // column of P A Pᵀ per original column
  std::vector<std::size_t> target_;  // per entry of `lower`: its position in values_
  // LU: per entry of `lower` (row i >= column j): the positions of A(i, j) and of A(j, i).
  std::vector<std::size_t> lu_target_, lu_target_transposed_;
  std::vector<float> values_;  // L's panels, then (LU) Uᵀ's from upper_offset_
  std::size_t upper_offset_ = 0;
  bool lu_ = false;           // the last factorisation is an LU
  std::vector<int> pivots_;   // LU: per column of P A Pᵀ, sgetrf's pivot inside its supernode (from 1)
  std::vector<float> column_largest_;  // LU: per column, its largest entry in its diagonal block
  // Per supernode: the next of its rows to update an ancestor with, and its list successor.
  std::vector<int> next_row_, next_in_list_;
  // Per thread planned at analyse() (omp_get_max_threads()): the subtrees given to it, as
  // postorder ranges [first, last) of supernodes (a smaller team takes them in turn); top_: the
  // other supernodes (ancestors of the subtrees), ascending.
  std::vector<std::vector<std::pair<int, int>>> thread_ranges_;
  std::vector<int> top_;
  std::vector<char> above_row_;  // per column: it belongs to a top supernode (and there are subtrees)
  std::vector<float> work_;
  std::vector<std::vector<float>> gathered_, above_;  // per thread
  // Per thread, kept from one factorisation to the next: the update matrices alone are up to
  // CHOLMOD's largest update (maxcsize) each, whose fresh pages the kernel would zero every time.
  std::vector<Workspace> workspaces_;
  long failed_column_ = -1;
};

}  // namespace needlefem
