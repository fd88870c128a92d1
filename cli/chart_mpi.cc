#include "chart_mpi.h"

#include <chrono>
#include <cstdlib>
#include <mutex>
#include <string>

#include "chart_journal.h"
#include "chart_record.h"
#include "ltp/core/elapsed.h"

#ifdef LTP_WITH_MPI
#include <mpi.h>
#endif

namespace ltp::cli {

#ifdef LTP_WITH_MPI

Ranks StartRanks() {
  // Not started by mpirun/srun: one rank, and no MPI start-up cost (a singleton MPI_Init
  // spawns a helper daemon and takes a good fraction of a second).
  if (!std::getenv("OMPI_COMM_WORLD_SIZE") && !std::getenv("PMIX_RANK") && !std::getenv("PMI_SIZE"))
    return {};
  int initialized = 0;
  MPI_Initialized(&initialized);
  if (!initialized) {
    int provided = 0;
    // Only the main thread calls MPI; OpenMP threads compute.
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
  }
  Ranks r;
  MPI_Comm_rank(MPI_COMM_WORLD, &r.rank);
  MPI_Comm_size(MPI_COMM_WORLD, &r.size);
  return r;
}

void StopRanks() {
  int initialized = 0, finalized = 0;
  MPI_Initialized(&initialized);
  MPI_Finalized(&finalized);
  if (initialized && !finalized) MPI_Finalize();
}

void AbortRanks(int code) {
  int initialized = 0;
  MPI_Initialized(&initialized);
  if (initialized) MPI_Abort(MPI_COMM_WORLD, code);
  std::exit(code);
}

size_t DistributedSweep(const Ranks& ranks, const Scene& scene, const ParameterMap& base,
                        const SweepGrid& grid, const std::vector<size_t>& indices,
                        const SweepOptions& options,
                        const std::function<void(SweepPoint&&)>& on_point,
                        const std::atomic<bool>* cancel) {
  if (ranks.size == 1) return RunSweep(scene, base, grid, indices, options, on_point, cancel);
  size_t done = 0, next = 0;
  size_t round = static_cast<size_t>(ranks.size) * 16;
  while (next < indices.size()) {
    const size_t end = std::min(indices.size(), next + round);
    // Round-robin within the round: neighbouring points (similar cost) go to different ranks.
    std::vector<size_t> mine;
    for (size_t i = next + static_cast<size_t>(ranks.rank); i < end;
         i += static_cast<size_t>(ranks.size))
      mine.push_back(indices[i]);
    const auto start = std::chrono::steady_clock::now();
    std::string payload;
    std::mutex payload_mutex;
    PointWriter writer;  // a fresh one per round: rank 0 reads each round's records afresh
    done += RunSweep(
        scene, base, grid, mine, options,
        [&](SweepPoint&& p) {
          if (ranks.rank == 0) {
            on_point(std::move(p));
          } else {
            std::lock_guard<std::mutex> lock(payload_mutex);
            payload += writer.Records(p, true);
          }
        },
        cancel);
    // Gather the other ranks' points on rank 0.
    int length = static_cast<int>(payload.size());
    std::vector<int> lengths(static_cast<size_t>(ranks.size)),
        offsets(static_cast<size_t>(ranks.size));
    MPI_Gather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
    std::string all;
    if (ranks.rank == 0) {
      int total = 0;
      for (int r = 0; r < ranks.size; ++r) {
        offsets[static_cast<size_t>(r)] = total;
        total += lengths[static_cast<size_t>(r)];
      }
      all.resize(static_cast<size_t>(total));
    }
    MPI_Gatherv(payload.data(), length, MPI_CHAR, all.data(), lengths.data(), offsets.data(),
                MPI_CHAR, 0, MPI_COMM_WORLD);
    if (ranks.rank == 0) {
      // Each rank's records in turn: its diagnostic texts precede the points that use them.
      for (int r = 1; r < ranks.size; ++r) {
        const size_t from = static_cast<size_t>(offsets[static_cast<size_t>(r)]);
        const std::string part =
            all.substr(from, static_cast<size_t>(lengths[static_cast<size_t>(r)]));
        PointReader reader;
        for (const std::string& record : FramedPayloads(part))
          if (std::optional<SweepPoint> p = reader.Read(record)) {
            on_point(std::move(*p));
            ++done;
          }
      }
    }
    // Grow the rounds until one takes about two seconds: frequent enough that little is lost
    // to a killed job, rare enough that the gathers cost nothing.
    double elapsed = SecondsSince(start);
    MPI_Allreduce(MPI_IN_PLACE, &elapsed, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    if (elapsed < 1.0) round *= 2;
    next = end;
  }
  return done;
}

#else

Ranks StartRanks() { return {}; }
void StopRanks() {}
void AbortRanks(int code) { std::exit(code); }

size_t DistributedSweep(const Ranks&, const Scene& scene, const ParameterMap& base,
                        const SweepGrid& grid, const std::vector<size_t>& indices,
                        const SweepOptions& options,
                        const std::function<void(SweepPoint&&)>& on_point,
                        const std::atomic<bool>* cancel) {
  return RunSweep(scene, base, grid, indices, options, on_point, cancel);
}

#endif

}  // namespace ltp::cli
