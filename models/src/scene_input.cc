#include "ltp/models/scene_input.h"

#include <optional>

#include "ltp/core/error.h"
#include "ltp/models/lin_scene.h"
#include "ltp/openfast/linearization.h"
#include "ltp/openfast/mbc3.h"

namespace ltp {

LoadedScene LoadSceneInput(const std::vector<std::string>& names,
                           const std::vector<std::string>& assignments) {
  if (names.empty()) throw InputError("no scene given");
  std::optional<LinOperatingPoint> op;
  std::shared_ptr<const Mbc3Result> mbc;  // one MBC3 of the files for every model built of them
  Scene scene;
  if (names.size() > 1 && !LooksLikeLinInput(names.front()))
    throw InputError("unexpected argument '" + names[1] + "' after scene '" + names.front() +
                     "': only OpenFAST .lin input takes several files");
  if (names.size() > 1 || LooksLikeLinInput(names.front())) {
    op = ReadLinOperatingPoint(names);
    mbc = Mbc3OrNull(*op);
    scene = MakeLinScene(*op, mbc);
  } else {
    scene = LoadScene(names.front());
  }
  std::vector<std::pair<std::string, std::string>> overrides;
  for (const std::string& a : assignments) overrides.push_back(SplitAssignment(a));
  ParameterMap parameters = scene.Resolve(overrides);
  PeriodicSystem system = scene.build(parameters);
  std::vector<Diagnostic> diagnostics;
  if (op)  // the caveats of the coordinates actually analysed (the build threw without an MBC3)
    diagnostics = LinCaveats(parameters.at("mbc") == 1 ? InMultiBladeCoordinates(*op, *mbc) : *op);
  std::vector<PeriodicSystem> alternatives;
  if (op) {
    ParameterMap other = parameters;
    other.at("trig") = 1 - other.at("trig");
    alternatives.push_back(scene.build(other));
    // The MBC transform leaves the exact exponents unchanged, so the other coordinates differ
    // only in what the samples miss — and alias differently: a 1P blade term is harmonic 1 in
    // blade coordinates but 0 and ±3 in MBC, where three azimuths fold it onto a constant
    // that both interpolations share (docs/sampled-models.md).
    // No MBC3 without recognised blade states: both coordinates are then the files'.
    if (mbc && mbc->applicable && mbc->blades >= 3) {
      other = parameters;
      other.at("mbc") = 1 - other.at("mbc");
      // A trigonometric model is carried into the analysed model's coordinates (the same
      // exponents, a finite Fourier series again): an analysis of the modes below a cut-off
      // projects both on one state space, and in the multi-blade frame the blade-coordinate
      // model is as nearly constant as the analysed one. Held samples are not: T(ψ) turns
      // within each hold.
      // One constant in its own coordinates (one azimuth) keeps its states and takes only the
      // other channels: its exponents are then its A's eigenvalues, exact, where its states
      // carried over would make it periodic (harmonics 0 to ±3 wherever fixed and rotating
      // states couple) and costly to integrate (250 states from one file: 130 s, nearly all of
      // it this model).
      PeriodicSystem built = scene.build(other);
      const FourierMatrix* a = built.fourier_A();
      if (built.form() == PeriodicSystem::Form::kFourier) try {
          built = TransformedMultiBlade(built, *op, *mbc, parameters.at("mbc") == 1,
                                        /*channels_only=*/a && a->max_harmonic() == 0);
        } catch (const InputError&) {
          // not a finite series after all: compared in its own coordinates
        }
      alternatives.push_back(std::move(built));
    }
  }
  return {std::move(scene), std::move(parameters), std::move(system), std::move(diagnostics),
          std::move(alternatives)};
}

}  // namespace ltp
