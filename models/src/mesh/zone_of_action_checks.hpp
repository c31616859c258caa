/// @file
/// @brief Validation of the zone-of-action geometry shared by the mesh models (internal).
#pragma once

#include <cmath>

#include "geardyn/common/check.hpp"
#include "geardyn/common/units.hpp"
#include "geardyn/models/mesh/contact_lines.hpp"

namespace geardyn::internal {

/// @brief Checks the geometric fields of `zone`: length, face width and transverse base pitch
/// finite and > 0 [m], |β_b| < π/2 [rad], pitch-point offset finite [m].
/// @throws InvalidInput naming the first offending field `zone.<field>`.
inline void CheckZoneGeometry(const ZoneOfAction& zone) {
  GEARDYN_THROW_UNLESS(std::isfinite(zone.length) && zone.length > 0.0,
                       "zone.length: must be finite and > 0 [m], got " << zone.length);
  GEARDYN_THROW_UNLESS(std::isfinite(zone.face_width) && zone.face_width > 0.0,
                       "zone.face_width: must be finite and > 0 [m], got " << zone.face_width);
  GEARDYN_THROW_UNLESS(
      std::isfinite(zone.transverse_base_pitch) && zone.transverse_base_pitch > 0.0,
      "zone.transverse_base_pitch: must be finite and > 0 [m], got " << zone.transverse_base_pitch);
  GEARDYN_THROW_UNLESS(
      std::isfinite(zone.base_helix_angle) && std::abs(zone.base_helix_angle) < 0.5 * kPi,
      "zone.base_helix_angle: must satisfy |beta_b| < pi/2 [rad], got " << zone.base_helix_angle);
  GEARDYN_THROW_UNLESS(
      std::isfinite(zone.pitch_point_offset),
      "zone.pitch_point_offset: must be finite [m], got " << zone.pitch_point_offset);
}

}  // namespace geardyn::internal
