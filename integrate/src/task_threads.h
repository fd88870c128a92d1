#pragma once
// Independent tasks of one computation shared by the cores of an analysis whose other threads
// would otherwise wait for it (Magnus–Filon's generators: every segment needs them first).
#include <functional>

namespace ltp::internal {

/// Runs task(0), …, task(count − 1) on `threads` threads: this one and threads − 1 started here,
/// each taking the next task when it finishes one (list the largest first). Returns when all
/// are done; the first exception a task throws is rethrown here after the others finished.
void RunTasks(int count, int threads, const std::function<void(int)>& task);

/// The threads to share work with from inside an analysis's parallel region: its team's size
/// (the analysis's --threads), 1 outside one.
int TeamThreads();

}  // namespace ltp::internal
