#pragma once
// An OpenFAST operating point (a set of `.lin` files) as a scene, so that every command that
// takes a scene name takes `.lin` files too.
#include "ltp/models/scene.h"
#include "ltp/openfast/linearization.h"

namespace ltp {

/// A scene over the files: name "openfast: <files>", parameters `trig` (1, the default:
/// trigonometric interpolation; 0: nearest-sample hold) and `mbc` (1: multi-blade coordinates,
/// the default when MBC applies, see ltp/openfast/mbc3.h; 0: the files' coordinates).
/// docs/sampled-models.md says why these defaults. @throws InputError as MakeLinOperatingPoint.
Scene MakeLinScene(const LinOperatingPoint& op);

}  // namespace ltp
