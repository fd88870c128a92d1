#include "ltp/floquet/threads.h"

#include <dlfcn.h>
#include <omp.h>

#include <algorithm>

namespace ltp {

int ThreadsFor(int requested) {
  const int machine = std::max(omp_get_num_procs(), omp_get_max_threads());
  return requested > 0 ? std::min(requested, machine) : omp_get_max_threads();
}

bool UseSingleThreadedBlas() {
  // Looked up at run time: the LAPACK/BLAS actually loaded may be OpenBLAS, the reference BLAS
  // (single-threaded already) or another implementation chosen by Debian's alternatives.
  using SetThreads = void (*)(int);
  auto set = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
  if (!set) return false;
  set(1);
  return true;
}

}  // namespace ltp
