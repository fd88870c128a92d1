#pragma once
// An OpenFAST operating point (a set of `.lin` files) as a scene, so that every command that
// takes a scene name takes `.lin` files too.
#include <memory>

#include "ltp/models/scene.h"
#include "ltp/openfast/linearization.h"
#include "ltp/openfast/mbc3.h"

namespace ltp {

/// Mbc3(op), or null when its blade channels are not recognised (Mbc3 throws InputError): the
/// files' coordinates then. Computed once per operating point and shared (at 250 states each
/// call is an eigen-decomposition of the averaged matrix and a description of every mode).
std::shared_ptr<const Mbc3Result> Mbc3OrNull(const LinOperatingPoint& op);

/// A scene over the files: name "openfast: <files>", parameters `trig` (1, the default:
/// trigonometric interpolation; 0: nearest-sample hold) and `mbc` (1: multi-blade coordinates,
/// the default when MBC applies, see ltp/openfast/mbc3.h; 0: the files' coordinates).
/// docs/sampled-models.md says why these defaults. `mbc`: Mbc3OrNull(op) when the caller has it
/// (else computed here). @throws InputError as MakeLinOperatingPoint.
Scene MakeLinScene(const LinOperatingPoint& op, std::shared_ptr<const Mbc3Result> mbc = nullptr);

}  // namespace ltp
