#pragma once
// How many OpenMP threads an analysis runs on.

namespace ltp {

/// `requested` threads (0 = all cores), never more than the machine has: asking the OpenMP
/// runtime for thousands fails with its own message ("Thread creation failed"), and more
/// threads than cores only add contention.
int ThreadsFor(int requested);

/// Makes the BLAS under LAPACK (OpenBLAS, when that is the one loaded) run on one thread, for
/// the whole process. ltp parallelises over sweep points, segments and frequencies itself, and
/// OpenBLAS's own threads under that (or beside another busy process) oversubscribe the cores
/// and spin (the HTF checks of `ltp pfrf tower-rotor` ran an order of magnitude slower on a
/// loaded 2-core machine). Programs that own the process call this once (the `ltp` command and the
/// Python module do); a host application that tunes its BLAS itself need not.
/// Returns false when the BLAS offers no such switch (nothing changed).
bool UseSingleThreadedBlas();

}  // namespace ltp
