/// @file
/// @brief Straight bevel pair geometry (issue 19): the pitch cones of two gears on intersecting
/// axes at a shaft angle Σ, the mean section where the mesh interface sits, and the virtual
/// cylindrical (Tredgold) spur pair of that section that gives the contact ratio and, later, the
/// mesh stiffness (ISO 10300-1's virtual cylindrical gears; ISO 23509 for the cone data).
///
/// **Cones** (ISO 23509, "pitch cone" data; the same for straight and spiral teeth): with the
/// ratio u = z₂/z₁, the pitch cone angles δ₁ = atan(sin Σ / (u + cos Σ)), δ₂ = Σ − δ₁; the outer
/// pitch diameters d_e = z m_et (m_et the outer transverse module, at the heel); the outer cone
/// distance R_e = d_e1 / (2 sin δ₁) (= d_e2 / (2 sin δ₂)); the mean cone distance R_m = R_e − b/2
/// (b the face width along the cone element); the mean module m_m = m_et R_m / R_e; the mean pitch
/// radii r_m = z m_m / 2 = R_m sin δ.
///
/// **Virtual spur pair** (Tredgold's approximation at the mean back cone, ISO 10300-1 §A for
/// β_m = 0): radii r_v = r_m / cos δ (virtual teeth z_v = z / cos δ, not integers), base radii
/// r_vb = r_v cos α, tip radii r_va = r_v + h_am with the mean addenda h_am1 = m_m (h_aP* + x_hm1),
/// h_am2 = m_m (h_aP* − x_hm1) (the Gleason pair's ±x), centre distance a_v = r_v1 + r_v2, path
/// of contact g_vα = √(r_va1² − r_vb1²) + √(r_va2² − r_vb2²) − a_v sin α, contact ratio
/// ε_vα = g_vα / (π m_m cos α). With straight teeth the normal and transverse sections coincide,
/// so α is the pressure angle of both.
///
/// **Scope.** External straight bevel pairs with δ₂ < 90° (a crown gear, δ₂ = 90°, and internal
/// bevel gears, δ₂ > 90°, have infinite or negative virtual radii and are refused), no spiral
/// angle, no tip or root angle details (the mean section is all the mesh interface reads).
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace geardyn {

/// @brief Inputs of a straight bevel pair.
struct BevelPairSpec {
  double outer_module = 0.0;                ///< m_et, outer transverse module (at the heel) [m]
  double pressure_angle = 0.0;              ///< α [rad], of the tooth profile (straight teeth)
  double shaft_angle = 0.0;                 ///< Σ ∈ (0, π) [rad], the angle between the axes
  int pinion_teeth = 0;                     ///< z₁ [-]
  int gear_teeth = 0;                       ///< z₂ [-]
  double face_width = 0.0;                  ///< b [m], along the cone element
  double addendum_coefficient = 1.0;        ///< h_aP* [-] of the mean section
  double pinion_profile_shift = 0.0;        ///< x_hm1 [-] (the gear gets −x_hm1)
  std::optional<double> pinion_cone_angle;  ///< δ₁ [rad] if given: checked, not used
  std::optional<double> gear_cone_angle;    ///< δ₂ [rad] if given: checked, not used
};

/// @brief Everything derived from a BevelPairSpec (lengths m, angles rad).
struct BevelPairGeometry {
  BevelPairSpec spec;
  double gear_ratio = 0.0;                   ///< u = z₂/z₁ [-]
  double pinion_cone_angle = 0.0;            ///< δ₁ [rad]
  double gear_cone_angle = 0.0;              ///< δ₂ = Σ − δ₁ [rad]
  double pinion_outer_pitch_diameter = 0.0;  ///< d_e1 = z₁ m_et [m]
  double gear_outer_pitch_diameter = 0.0;    ///< d_e2 [m]
  double outer_cone_distance = 0.0;          ///< R_e [m]
  double mean_cone_distance = 0.0;           ///< R_m = R_e − b/2 [m]
  double mean_module = 0.0;                  ///< m_m = m_et R_m / R_e [m]
  double pinion_mean_pitch_radius = 0.0;     ///< r_m1 = R_m sin δ₁ [m]
  double gear_mean_pitch_radius = 0.0;       ///< r_m2 [m]
  double pinion_virtual_teeth = 0.0;         ///< z_v1 = z₁ / cos δ₁ [-]
  double gear_virtual_teeth = 0.0;           ///< z_v2 [-]
  double pinion_virtual_radius = 0.0;        ///< r_v1 = r_m1 / cos δ₁ [m]
  double gear_virtual_radius = 0.0;          ///< r_v2 [m]
  double pinion_virtual_base_radius = 0.0;   ///< r_vb1 = r_v1 cos α [m]
  double gear_virtual_base_radius = 0.0;     ///< r_vb2 [m]
  double pinion_virtual_tip_radius = 0.0;    ///< r_va1 = r_v1 + m_m (h_aP* + x_hm1) [m]
  double gear_virtual_tip_radius = 0.0;      ///< r_va2 = r_v2 + m_m (h_aP* − x_hm1) [m]
  double virtual_center_distance = 0.0;      ///< a_v = r_v1 + r_v2 [m]
  double mean_base_pitch = 0.0;              ///< p_b = π m_m cos α [m]
  double path_of_contact_length = 0.0;       ///< g_vα [m]
  /// Where the path of contact starts and ends on the virtual line of action, as distances from
  /// T1 (its tangency point on the pinion's virtual base circle) [m]: T1A, T1E, and the pitch
  /// point T1C = r_vb1 tan α.
  double path_start_from_pinion_tangent = 0.0;
  double path_end_from_pinion_tangent = 0.0;
  double pitch_point_from_pinion_tangent = 0.0;
  double contact_ratio = 0.0;         ///< ε_vα = g_vα / p_b [-]
  std::vector<std::string> warnings;  ///< accepted with a note (a face wider than R_e/3)
};

/// @brief Derives the bevel pair (see the @file).
/// @throws InvalidInput whose message starts with the field: "outer_module" (not finite or below
///   kMinNormalModule), "pressure_angle" (outside (0, 45°)), "shaft_angle" (outside (0, 180°)),
///   "pinion.teeth"/"gear.teeth" (< 3), "face_width" (not positive, or not below R_e: no inner
///   end), "addendum_coefficient", "pinion_profile_shift" (not finite), "gear_cone_angle"
///   (δ₂ ≥ 90°: crown or internal bevel gear), "pinion_cone_angle"/"gear_cone_angle" (given and
///   differing from the value the teeth and Σ imply by more than 1e-6 rad, both values named),
///   "pinion.tip_interference"/"gear.tip_interference" (the mate's tip meets the flank inside the
///   virtual base circle), "contact_ratio" (ε_vα < 1).
BevelPairGeometry CalcBevelPairGeometry(const BevelPairSpec& spec);

}  // namespace geardyn
