#include "ltp/integrate/threads.h"

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
  // The worker threads OpenBLAS started when it was loaded keep spinning (sched_yield) for
  // ~0.1 s before they sleep, on the cores ltp's own threads need: stop them. With one thread
  // OpenBLAS never hands them work again (it would start them anew if it did). Measured: the
  // 401 × 401 Mathieu map 0.47 → 0.42 s.
  using Shutdown = int (*)();
  if (auto shutdown = reinterpret_cast<Shutdown>(dlsym(RTLD_DEFAULT, "blas_thread_shutdown_")))
    shutdown();
  return true;
}

}  // namespace ltp
