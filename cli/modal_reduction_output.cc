// What an analysis of the modes below a cut-off kept and left out (modal_reduction_output.h).
#include "modal_reduction_output.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <numbers>

#include "format.h"

namespace ltp::cli {

namespace {
constexpr double kPi = std::numbers::pi;
}  // namespace

nlohmann::json ReductionJson(const std::optional<ModalReduction>& m) {
  if (!m) return nullptr;
  nlohmann::json dropped = nlohmann::json::array();
  for (const auto& l : m->dropped)
    dropped.push_back({{"re", JsonNumber(l.real())}, {"im", JsonNumber(l.imag())}});
  return {{"cutoff_hz", m->cutoff / (2 * kPi)},
          {"states", m->kept},
          {"check_cutoff_hz", m->check_cutoff / (2 * kPi)},
          {"check_states", m->check_kept},
          {"truncation_change", JsonNumber(m->truncation_change)},
          {"tail", JsonNumber(m->tail)},
          {"dropped_mean_eigenvalues", dropped},
          {"periodic_part", JsonNumber(m->periodic_part)}};
}

void PrintReduction(const ModalReduction& m, int states) {
  double dropped_max = -std::numeric_limits<double>::infinity();
  for (const auto& l : m.dropped) dropped_max = std::max(dropped_max, l.real());
  std::cout << "\n  modes below " << Num(m.cutoff / (2 * kPi), 4) << " Hz only: " << m.kept
            << " of " << states << " states (the numbers from the projection at "
            << Num(m.check_cutoff / (2 * kPi), 4) << " Hz, " << m.check_kept
            << " states; truncation moves them by " << Num(m.truncation_change, 2)
            << " 1/s, the modes beyond by about " << Num(m.tail, 2) << ")\n";
  if (!m.dropped.empty())
    std::cout << "  left out: " << m.dropped.size()
              << " modes, mean-A eigenvalues up to Re λ = " << Num(dropped_max, 4)
              << " 1/s, periodic part ‖A(t) − Ā‖ ≤ " << Num(m.periodic_part, 2) << "\n";
}

}  // namespace ltp::cli
