/// @file
/// @brief The zone of action shared by the contact-line and transmission-error tests: a base
/// pitch of ≈ 2 mm module, a 24 mm face and a steel-like line stiffness, and Zone(ε_α, ε_β, …).
#pragma once

#include <cmath>

#include "geardyn/models/mesh/contact_lines.hpp"

namespace geardyn::test {

inline constexpr double kPitch = 0.0059;  // p_bt [m] (m_n ≈ 2 mm)
inline constexpr double kFace = 0.024;    // B [m]
inline constexpr double kK = 1.4e10;      // k [N/m²] (≈ c_γ = 14 N/(mm·µm))

/// A zone with the given contact ratios: g_α = ε_α p_bt, tan β_b = ε_β p_bt / B.
inline ZoneOfAction Zone(double eps_alpha, double eps_beta, double offset = 0.0, int drive_sign = 1,
                         double beta_sign = 1.0) {
  ZoneOfAction z;
  z.length = eps_alpha * kPitch;
  z.face_width = kFace;
  z.transverse_base_pitch = kPitch;
  z.base_helix_angle = beta_sign * std::atan(eps_beta * kPitch / kFace);
  z.pitch_point_offset = offset;
  z.drive_sign = drive_sign;
  return z;
}

}  // namespace geardyn::test
