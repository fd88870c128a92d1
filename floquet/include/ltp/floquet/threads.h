#pragma once
// How many OpenMP threads an analysis runs on.

namespace ltp {

/// `requested` threads (0 = all cores), never more than the machine has: asking the OpenMP
/// runtime for thousands fails with its own message ("Thread creation failed"), and more
/// threads than cores only add contention.
int ThreadsFor(int requested);

}  // namespace ltp
