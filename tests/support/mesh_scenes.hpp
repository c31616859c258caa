/// @file
/// @brief The mesh test scenes shared by the mesh frame, Jacobian and stiffness-core tests:
/// {external, internal} × {spur, right-hand, left-hand pinion} × {drive +1, −1} × {pinion at the
/// origin with the gear on +X, arbitrary pinion centre and line-of-centres angle}.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "geardyn/common/eigen_types.hpp"
#include "geardyn/common/units.hpp"
#include "geardyn/models/gear/gear_geometry.hpp"
#include "geardyn/models/mesh/mesh_frame.hpp"

namespace geardyn::test {

/// A named mesh placement (the name is the gtest parameter name).
struct MeshScene {
  std::string name;
  MeshPlacement placement;
};

/// One scene: base radii, operating pressure angle and base helix angle of an external or
/// internal pair, the pinion hand and drive sign, at the origin or moved to an arbitrary pinion
/// centre and line-of-centres angle (the centre distance follows from the base radii).
inline MeshPlacement MakeMeshPlacement(bool internal, HelixHand hand, int drive_sign, bool moved) {
  MeshPlacement p;
  p.internal = internal;
  p.pinion_base_radius = internal ? 0.031 : 0.042;
  p.gear_base_radius = internal ? 0.094 : 0.071;
  p.operating_pressure_angle = DegToRad(internal ? 21.3 : 23.1);
  p.base_helix_angle = hand == HelixHand::kNone ? 0.0 : DegToRad(internal ? 14.2 : 18.7);
  p.pinion_hand = hand;
  p.drive_sign = drive_sign;
  const double gamma = moved ? 2.31 : 0.0;
  p.pinion_center = moved ? Vector3(0.13, -0.21, 0.07) : Vector3::Zero();
  const double radius_sum = internal ? p.gear_base_radius - p.pinion_base_radius
                                     : p.pinion_base_radius + p.gear_base_radius;
  const double C = radius_sum / std::cos(p.operating_pressure_angle);
  p.gear_center = p.pinion_center + C * Vector3(std::cos(gamma), std::sin(gamma), 0.0);
  return p;
}

/// All 24 scenes, named e.g. "external_rh_drive_neg_moved".
inline std::vector<MeshScene> AllMeshScenes() {
  std::vector<MeshScene> scenes;
  for (bool internal : {false, true}) {
    for (HelixHand hand : {HelixHand::kNone, HelixHand::kRight, HelixHand::kLeft}) {
      for (int s : {1, -1}) {
        for (bool moved : {false, true}) {
          const std::string hand_name = hand == HelixHand::kNone    ? "spur"
                                        : hand == HelixHand::kRight ? "rh"
                                                                    : "lh";
          scenes.push_back({std::string(internal ? "internal_" : "external_") + hand_name +
                                (s > 0 ? "_drive_pos" : "_drive_neg") +
                                (moved ? "_moved" : "_origin"),
                            MakeMeshPlacement(internal, hand, s, moved)});
        }
      }
    }
  }
  return scenes;
}

}  // namespace geardyn::test
