#include "ltp/floquet/threads.h"

#include <omp.h>

#include <algorithm>

namespace ltp {

int ThreadsFor(int requested) {
  const int machine = std::max(omp_get_num_procs(), omp_get_max_threads());
  return requested > 0 ? std::min(requested, machine) : omp_get_max_threads();
}

}  // namespace ltp
