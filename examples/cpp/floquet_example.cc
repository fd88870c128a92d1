// Floquet exponents of the built-in damped Mathieu oscillator y'' + c y' + (a - 2q cos 2t) y = u.
#include <iostream>

#include "ltp/floquet/floquet.h"
#include "ltp/models/scene.h"

int main() {
  const ltp::PeriodicSystem system =
      ltp::LoadScene("mathieu").Build({{"a", "1.5"}, {"q", "2"}, {"c", "0.05"}});
  const ltp::FloquetResult result = ltp::AnalyzeFloquet(system);  // the defaults of `ltp floquet`
  std::cout.precision(12);
  for (const ltp::FloquetMode& mode : result.modes)
    std::cout << "exponent " << mode.exponent << " 1/s\n";  // (Re λ, Im λ)
  if (result.error_estimate)  // the defaults estimate it; empty when not asked for
    std::cout << "error estimate " << *result.error_estimate << " 1/s\n";
  std::cout << "verdict " << ltp::ToString(result.verdict) << '\n';
  return result.ok ? 0 : 1;
}
