/// @file
/// @brief The straight bevel pair inputs shared by the bevel geometry and mesh-frame tests.
#pragma once

#include "geardyn/common/units.hpp"
#include "geardyn/models/gear/bevel_geometry.hpp"

namespace geardyn::test {

/// A straight bevel pair z1/z2 of outer module m_et [m], face b [m], 20° pressure angle, at the
/// shaft angle Σ [deg], unshifted.
inline BevelPairSpec BevelSpec(int z1, int z2, double m_et, double b, double sigma_deg) {
  BevelPairSpec s;
  s.outer_module = m_et;
  s.pressure_angle = DegToRad(20.0);
  s.shaft_angle = DegToRad(sigma_deg);
  s.pinion_teeth = z1;
  s.gear_teeth = z2;
  s.face_width = b;
  return s;
}

}  // namespace geardyn::test
