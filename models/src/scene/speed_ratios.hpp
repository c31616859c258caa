/// @file
/// @brief Kinematic speed ratios of a scene's gears relative to a reference gear (internal).
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <string_view>

#include "geardyn/models/scene/scene.hpp"

namespace geardyn::internal {

/// @brief Ω_gear / Ω_reference for every gear connected to the reference, and the first
/// kinematic conflict (a closed loop of meshes whose ratios do not agree), if any.
struct SpeedRatios {
  std::map<std::string, double, std::less<>> ratio;  ///< gear name → Ω_gear / Ω_ref [-]
  std::optional<std::size_t> conflict_mesh;          ///< index into scene.meshes
  std::optional<std::size_t> conflict_bearing;       ///< index into scene.bearings
  std::optional<std::size_t> conflict_shaft;         ///< index into scene.shafts
  std::string conflict_gear;                         ///< the gear whose ratio disagrees
  double ratio_known = 0.0;    ///< its ratio through the rest of the graph [-]
  double ratio_implied = 0.0;  ///< its ratio implied by the conflicting element [-]
};

/// @brief Propagates speed ratios from `reference` through the meshes (external: −z_i/z_j,
/// internal: +z_i/z_j), through bearings between two bodies (gears or shafts) with
/// stiffness(5, 5) > 0 (ratio 1) and from a shaft to the gears on it (ratio 1).
/// @pre every mesh's and bearing's gear names exist in scene.gears.
SpeedRatios CalcSpeedRatios(const Scene& scene, std::string_view reference);

}  // namespace geardyn::internal
