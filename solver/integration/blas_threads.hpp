// OpenBLAS's thread count, set for a scope. needlefem runs BLAS on one thread (app/main.cpp:
// OpenBLAS's idle threads spin against the OpenMP element loops); code whose own OpenMP threads
// each call BLAS asks for one thread, and a double-precision factorisation whose large BLAS-3
// calls are its work asks for the cores. Other BLAS libraries have no such call: the scope then
// does nothing.
#pragma once

namespace needlefem {

// The OpenBLAS kernel family this CPU should run where OpenBLAS did not recognise the CPU, or
// null. Debian 12's OpenBLAS 0.3.21 picks its kernels by CPU model and falls back to "Prescott"
// (SSE3) for a model it does not know, such as the Xeons of family 6, model 207 (Emerald Rapids):
// single-precision GEMM then ran at 35 instead of 174 GFlop/s on one core with the "SkylakeX"
// kernels that the CPU's AVX-512 supports, and the tied brain-tip benchmark took 24.9 s instead
// of 12.8 s. The choice follows the instruction sets the CPU reports (AVX-512 F/CD/BW/DQ/VL:
// SkylakeX; AVX2 and FMA: Haswell; AVX: Sandybridge). OpenBLAS reads OPENBLAS_CORETYPE once, when
// it loads, so the caller sets it and restarts the process (app/main.cpp).
const char* openblas_core_for_unrecognised_cpu();

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
