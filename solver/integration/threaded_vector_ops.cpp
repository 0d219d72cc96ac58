#include "integration/threaded_vector_ops.hpp"

#include <nvector/nvector_petsc.h>
#include <omp.h>
#include <petscvec.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <type_traits>
#include <vector>

namespace needlefem {

namespace {

// Below this length the threads' start-up costs more than they save.
constexpr PetscInt kSerialBelow = 16384;

// The local arrays of an operation's vectors: inputs read, the output written (an input may be
// the output: PETSc hands out the same array). Unlike petsc_arrays.hpp's views these never
// throw: SUNDIALS's C code calls the operations, and no exception may cross it.
template <bool kWritable>
class LocalArray {
 public:
  using Pointer = std::conditional_t<kWritable, PetscScalar*, const PetscScalar*>;
  explicit LocalArray(N_Vector v) : vec_(N_VGetVector_Petsc(v)) {
    VecGetLocalSize(vec_, &size_);
    if constexpr (kWritable)
      VecGetArray(vec_, &data_);
    else
      VecGetArrayRead(vec_, &data_);
  }
  ~LocalArray() {
    if constexpr (kWritable)
      VecRestoreArray(vec_, &data_);
    else
      VecRestoreArrayRead(vec_, &data_);
  }
  LocalArray(const LocalArray&) = delete;
  LocalArray& operator=(const LocalArray&) = delete;
  Pointer data() const { return data_; }
  PetscInt size() const { return size_; }

 private:
  Vec vec_;
  PetscInt size_ = 0;
  Pointer data_ = nullptr;
};
using Input = LocalArray<false>;
using Output = LocalArray<true>;

template <class Body>
void for_each_index(PetscInt n, Body&& body) {
  if (n < kSerialBelow) {
    for (PetscInt i = 0; i < n; ++i) body(i);
    return;
  }
#pragma omp parallel for schedule(static)
  for (PetscInt i = 0; i < n; ++i) body(i);
}

// Σ term(i): a part per thread, [n t / T, n (t + 1) / T), the parts added in thread order.
template <class Term>
double sum_in_thread_order(PetscInt n, Term&& term) {
  // Eight running sums, so that the additions do not wait on each other (and vectorise).
  const auto part_sum = [&](PetscInt begin, PetscInt end) {
    constexpr int kLanes = 8;
    std::array<double, kLanes> lanes{};
    PetscInt i = begin;
    for (; i + kLanes <= end; i += kLanes)
      for (int j = 0; j < kLanes; ++j) lanes[j] += term(i + j);
    double sum = 0.0;
    for (; i < end; ++i) sum += term(i);
    for (double lane : lanes) sum += lane;
    return sum;
  };
  if (n < kSerialBelow) return part_sum(0, n);
  std::vector<double> parts(static_cast<std::size_t>(omp_get_max_threads()), 0.0);
#pragma omp parallel
  {
    const PetscInt t = omp_get_thread_num(), count = omp_get_num_threads();
    parts[static_cast<std::size_t>(t)] = part_sum(n * t / count, n * (t + 1) / count);
  }
  double sum = 0.0;
  for (double part : parts) sum += part;
  return sum;
}

// z_i = op(x_i, y_i).
template <class Op>
void elementwise(N_Vector x, N_Vector y, N_Vector z, Op op) {
  const Input in_x(x), in_y(y);
  const Output out(z);
  const double *xs = in_x.data(), *ys = in_y.data();
  double* zs = out.data();
  for_each_index(out.size(), [&](PetscInt i) { zs[i] = op(xs[i], ys[i]); });
}

void linear_sum(realtype a, N_Vector x, realtype b, N_Vector y, N_Vector z) {
  elementwise(x, y, z, [a, b](double p, double q) { return a * p + b * q; });
}

void product(N_Vector x, N_Vector y, N_Vector z) {
  elementwise(x, y, z, [](double p, double q) { return p * q; });
}

void quotient(N_Vector x, N_Vector y, N_Vector z) {
  elementwise(x, y, z, [](double p, double q) { return p / q; });
}

void scale(realtype c, N_Vector x, N_Vector z) {
  elementwise(x, x, z, [c](double p, double) { return c * p; });
}

void constant(realtype c, N_Vector z) {
  const Output out(z);
  double* zs = out.data();
  for_each_index(out.size(), [&](PetscInt i) { zs[i] = c; });
}

realtype dot_product(N_Vector x, N_Vector y) {
  const Input in_x(x), in_y(y);
  const double *xs = in_x.data(), *ys = in_y.data();
  return sum_in_thread_order(in_x.size(), [&](PetscInt i) { return xs[i] * ys[i]; });
}

realtype max_norm(N_Vector x) {
  const Input in_x(x);
  const double* xs = in_x.data();
  const PetscInt n = in_x.size();
  double largest = 0.0;
#pragma omp parallel for schedule(static) reduction(max : largest) if (n >= kSerialBelow)
  for (PetscInt i = 0; i < n; ++i) largest = std::max(largest, std::abs(xs[i]));
  return largest;
}

// √(Σ (x_i w_i)² / n) over the entries i that `counts`, n the length (the vector's whole: these
// operations serve vectors on one rank only).
template <class Counts>
realtype weighted_rms(N_Vector x, N_Vector w, Counts counts) {
  const Input in_x(x), in_w(w);
  const double *xs = in_x.data(), *ws = in_w.data();
  const double sum = sum_in_thread_order(in_x.size(), [&](PetscInt i) {
    const double v = counts(i) ? xs[i] * ws[i] : 0.0;
    return v * v;
  });
  return std::sqrt(sum / static_cast<double>(in_x.size()));
}

realtype weighted_rms_norm(N_Vector x, N_Vector w) {
  return weighted_rms(x, w, [](PetscInt) { return true; });
}

realtype weighted_rms_norm_masked(N_Vector x, N_Vector w, N_Vector id) {
  const Input in_id(id);
  const double* ids = in_id.data();
  return weighted_rms(x, w, [ids](PetscInt i) { return ids[i] > 0.0; });
}

}  // namespace

bool use_threaded_vector_operations(N_Vector v) {
  MPI_Comm comm = MPI_COMM_NULL;
  int ranks = 0;
  if (PetscObjectGetComm(reinterpret_cast<PetscObject>(N_VGetVector_Petsc(v)), &comm) != 0 ||
      MPI_Comm_size(comm, &ranks) != MPI_SUCCESS || ranks != 1)
    return false;
  v->ops->nvlinearsum = linear_sum;
  v->ops->nvconst = constant;
  v->ops->nvprod = product;
  v->ops->nvdiv = quotient;
  v->ops->nvscale = scale;
  v->ops->nvdotprod = dot_product;
  v->ops->nvmaxnorm = max_norm;
  v->ops->nvwrmsnorm = weighted_rms_norm;
  v->ops->nvwrmsnormmask = weighted_rms_norm_masked;
  return true;
}

}  // namespace needlefem
