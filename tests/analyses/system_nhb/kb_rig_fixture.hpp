/// @file
/// @brief The Kahraman–Blankenship rig (built-in scene) with a nonlinear slice mesh for the
/// system nonlinear HB tests: 10 slices, a 0.2 mm centre-distance allowance (backlash
/// j_bn ≈ 0.14 mm, never closed at these loads: single-sided contact loss), mesh damping ratio
/// 0.05, and the pinion torque = brake torque = `torque` [N·m].
#pragma once

#include <string>
#include <vector>

#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"

namespace geardyn::testing {

inline SystemModel KbRigSliceModel(double torque = 100.0) {
  const std::string t = std::to_string(torque);
  const std::vector<std::string> overrides = {"mesh.pinion-wheel.model=\"slices\"",
                                              "mesh.pinion-wheel.slices=10",
                                              "mesh.pinion-wheel.center_distance=0.1502",
                                              "mesh.pinion-wheel.damping_ratio=0.05",
                                              "operating_point.torque=" + t,
                                              "load.brake.torque=" + t};
  return BuildSceneSystem(LoadScene("builtin:kahraman-blankenship-rig", overrides)).model;
}

}  // namespace geardyn::testing
