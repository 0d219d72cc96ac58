// OpenBLAS's thread count, set for a scope. needlefem runs BLAS on one thread (set at start-up,
// start_blas_on_one_thread): OpenBLAS's idle threads spin after every call, even a vector
// operation of PETSc's, against the OpenMP element loops; code whose own OpenMP threads each call
// BLAS asks for one thread, and a double-precision factorisation whose large BLAS-3 calls are its
// work asks for the cores. Other BLAS libraries have no such call: the scope then does nothing.
// The measurements behind these choices are in docs/speed.md.
#pragma once

#include <string>

namespace needlefem {

// The OpenBLAS kernel family this CPU should run where OpenBLAS did not recognise the CPU, or
// null. Debian 12's OpenBLAS 0.3.21 picks its kernels by CPU model and falls back to "Prescott"
// (SSE3) for a model it does not know, such as the Xeons of family 6, model 207 (Emerald Rapids),
// whose AVX-512 runs "SkylakeX"'s kernels several times faster (docs/speed.md). The choice follows
// the instruction sets the CPU reports (AVX-512 F/CD/BW/DQ/VL: SkylakeX; AVX2 and FMA: Haswell;
// AVX: Sandybridge). This is the one place the rule is written.
const char* openblas_core_for_unrecognised_cpu();

// OpenBLAS reads OPENBLAS_CORETYPE once, when it loads, so only the environment that starts
// needlefem can choose the kernels. When OpenBLAS runs its fallback kernels on a CPU with faster
// ones and OPENBLAS_CORETYPE is unset: one line saying which value to export (ending
// "export OPENBLAS_CORETYPE=VALUE ..."; scripts/blas_env.sh reads it); else "".
std::string openblas_coretype_note();

// One BLAS thread for the process, unless OPENBLAS_NUM_THREADS is set (OpenBLAS then started
// with that many); the BlasThreads scopes below change it where more pay.
void start_blas_on_one_thread();

// The kernel family OpenBLAS runs ("SkylakeX", ...), or "" under another BLAS; run summaries
// record it beside their timings.
const char* openblas_kernel();

class BlasThreads {
 public:
  explicit BlasThreads(int threads);
  ~BlasThreads();
  BlasThreads(const BlasThreads&) = delete;
  BlasThreads& operator=(const BlasThreads&) = delete;

 private:
  int previous_ = 0;  // 0: nothing to restore
};

}  // namespace needlefem
