#include "integration/blas_threads.hpp"

#include <dlfcn.h>

#include <cstdlib>
#include <string_view>

#include <fmt/core.h>

namespace needlefem {

namespace {

// OpenBLAS's calls, looked up once; null under another BLAS.
struct OpenBlasThreadCalls {
  OpenBlasThreadCalls()
      : set(reinterpret_cast<void (*)(int)>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"))),
        get(reinterpret_cast<int (*)()>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"))) {}
  void (*set)(int);
  int (*get)();
};

const OpenBlasThreadCalls& openblas() {
  static const OpenBlasThreadCalls calls;
  return calls;
}

}  // namespace

const char* openblas_kernel() {
  const auto corename = reinterpret_cast<char* (*)()>(dlsym(RTLD_DEFAULT, "openblas_get_corename"));
  return corename ? corename() : "";
}

const char* openblas_core_for_unrecognised_cpu() {
  if (std::string_view(openblas_kernel()) != "Prescott") return nullptr;
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512cd") && __builtin_cpu_supports("avx512bw") &&
      __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512vl"))
    return "SkylakeX";
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return "Haswell";
  if (__builtin_cpu_supports("avx")) return "Sandybridge";
  return nullptr;
}

std::string openblas_coretype_note() {
  const char* core = openblas_core_for_unrecognised_cpu();
  if (!core || std::getenv("OPENBLAS_CORETYPE")) return "";
  return fmt::format("OpenBLAS did not recognise this CPU and runs its generic {} kernels; for its faster ones "
                     "export OPENBLAS_CORETYPE={} before starting needlefem (scripts/blas_env.sh; docs/speed.md)",
                     openblas_kernel(), core);
}

void start_blas_on_one_thread() {
  const OpenBlasThreadCalls& calls = openblas();
  if (calls.set && !std::getenv("OPENBLAS_NUM_THREADS")) calls.set(1);
}

BlasThreads::BlasThreads(int threads) {
  const OpenBlasThreadCalls& calls = openblas();
  if (!calls.set || !calls.get) return;
  previous_ = calls.get();
  if (previous_ != threads) calls.set(threads);
}

BlasThreads::~BlasThreads() {
  const OpenBlasThreadCalls& calls = openblas();
  if (previous_ > 0 && calls.get() != previous_) calls.set(previous_);
}

}  // namespace needlefem
