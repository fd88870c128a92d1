#pragma once
// Test hook: SLICOT MB03BD's rare non-convergence (INFO > 0, met on isotropic rotors whose
// multipliers are nearly triple) cannot be produced on demand, so the tests make the next
// `count` periodic Schur calls fail to exercise the fallback (floquet.cc, MultiplierLogs).
// Not thread-safe; tests only.
namespace ltp::internal {
void InjectPeriodicSchurFailures(int count);
}  // namespace ltp::internal
