#pragma once
// Sweeps across MPI ranks (`mpirun -n P ltp chart ...`, build with -DLTP_WITH_MPI=ON). Every
// rank computes a share of the points with all its threads; rank 0 receives every point and
// is the only one that writes. Without MPI (or with one rank) this is RunSweep.
#include <functional>
#include <vector>

#include "ltp/studies/sweep.h"

namespace ltp::cli {

struct Ranks {
  int rank = 0;
  int size = 1;
};

/// Initialises MPI when built with it (a singleton run without mpirun is one rank).
Ranks StartRanks();
/// Finalises MPI (no-op without it).
void StopRanks();
/// Aborts every rank (after an error on one of them, so the others do not wait forever).
[[noreturn]] void AbortRanks(int code);

/// Computes `indices` across all ranks; on rank 0, `on_point` receives every point (its own
/// as they complete, the others' at the end of each round of work; rounds grow until one
/// takes about two seconds). Other ranks never call it. Returns the number of points done.
size_t DistributedSweep(const Ranks& ranks, const Scene& scene, const ParameterMap& base,
                        const SweepGrid& grid, const std::vector<size_t>& indices,
                        const SweepOptions& options,
                        const std::function<void(SweepPoint&&)>& on_point,
                        const std::atomic<bool>* cancel);

}  // namespace ltp::cli
