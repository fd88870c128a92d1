// Fuzz target: YAML scene files. Parses the text, builds the system with its defaults (which runs
// every up-front check: sizes, finiteness, boundedness of A(t) over the period, singular mass
// matrices) and does what `ltp info` does with it: evaluate the matrices, a snapshot eigenvalue
// problem and the Fourier fit. The Floquet analysis itself is left to the regression tests of
// the reproducers (tests/cli/exit_codes_cli_test.cc): its cost grows with the input by design.
#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_target.h"
#include "ltp/core/fourier_fit.h"
#include "ltp/models/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  ltp::fuzz::RefuseOnlyWithLtpErrors([&] {
    const ltp::Scene scene = ltp::ParseSceneYaml(text, "fuzz.yaml");
    const ltp::PeriodicSystem system = scene.Build();
    if (system.states() > 64) return;  // bounded by the scene limits; keep each run short
    for (double s : {0.0, 0.37, 0.5, 0.999}) {
      const ltp::LtiSystem snap = system.Snapshot(s * system.period());
      if (!snap.A.allFinite()) std::abort();  // Build promised a bounded A(t)
      if (snap.A.size()) (void)snap.A.eigenvalues();
    }
    ltp::FourierFitOptions fit;
    fit.tol = 1e-10;
    (void)ltp::ToFourier(system, fit);
  });
  return 0;
}
