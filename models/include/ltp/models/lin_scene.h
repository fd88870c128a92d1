#pragma once
// An OpenFAST operating point (a set of `.lin` files) as a scene, so that every command that
// takes a scene name takes `.lin` files too.
#include "ltp/models/scene.h"
#include "ltp/openfast/linearization.h"

namespace ltp {

/// A scene over the files: name "openfast: <files>", parameters `trig` (0: nearest-sample
/// hold, 1: trigonometric interpolation) and `mbc` (0: the files' coordinates, 1: multi-blade
/// coordinates, see ltp/openfast/mbc3.h). @throws InputError as MakeLinOperatingPoint.
Scene MakeLinScene(const LinOperatingPoint& op);

}  // namespace ltp
