#pragma once
// Built-in scenes defined in their own files and registered in BuiltinScenes()
// (builtin_scenes.cc). Internal to ltp_core. Append new declarations; do not reorder.
#include "ltp/models/scene.h"

namespace ltp {

/// `rotor`: N lead-lag blades on a flexible support (rotor_scene.cc).
Scene RotorScene();
/// `flap`: rotor blade flapping in forward flight (flap_scene.cc).
Scene FlapScene();
/// `tower-rotor`: the partial-FRF paper's flexible rotor system (tower_rotor.cc).
Scene TowerRotorScene();

}  // namespace ltp
