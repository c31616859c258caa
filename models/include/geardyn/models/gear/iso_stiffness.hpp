/// @file
/// @brief ISO 6336-1 (method B) estimates of the single-pair tooth stiffness c' and the mesh
/// stiffness c_γα, c_γβ of an involute gear pair, per unit face width.
///
/// These are the usual constant stiffness per unit contact length k of spec 01 §4.2. Units are SI
/// throughout: stiffness per metre of face width in N/m per m = N/m², so
/// 1 N/(mm·µm) = 1e9 N/m²; flexibility q' in m²/N (1 mm·µm/N = 1e-9 m²/N). ISO 6336 calls
/// "pinion" (index 1) the gear with fewer teeth, whichever one drives; the function applies that
/// rule itself.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "geardyn/models/gear/gear_geometry.hpp"

namespace geardyn {

/// @brief Options of CalcIsoMeshStiffness.
struct IsoStiffnessOptions {
  double blank_factor = 0.8;  ///< C_M [-], theoretical correction factor (0.8 solid discs)
  /// F_t K_A / b [N/m]; when below 100 N/mm = 1e5 N/m, c' is scaled by (F_t K_A / b / 1e5)^0.25
  /// (ISO 6336-1). Absent: c' for line loads of at least 100 N/mm.
  std::optional<double> line_load;
};

/// @brief ISO 6336-1 method B stiffness values, per unit face width [N/m²] unless stated.
struct IsoMeshStiffness {
  double theoretical_single_pair = 0.0;  ///< c'_th = 1/q' [N/m²]
  double single_pair = 0.0;  ///< c' = c'_th C_M C_R C_B cos β (× line-load factor) [N/m²]
  double mesh_alpha = 0.0;   ///< c_γα = c' (0.75 ε_α + 0.25) [N/m²]
  double mesh_beta = 0.0;    ///< c_γβ = 0.85 c_γα [N/m²]
  double q_prime = 0.0;  ///< q', minimum flexibility of a tooth pair [m²/N] (SI, not mm·µm/N)
  double blank_factor = 0.0;  ///< C_M [-] as used
  /// C_R [-], one per mesh: min(C_R(pinion), C_R(gear)), each 1 for a solid blank (the more
  /// flexible blank's value, ISO 6336-1: curves for a mate of similar or stiffer blank design)
  double rim_factor = 0.0;
  double basic_rack_factor = 0.0;  ///< C_B [-] = (C_B1 + C_B2) / 2
  // Added by the implementation:
  double line_load_factor = 1.0;  ///< (F_t K_A / b / 100 N/mm)^0.25 if below 100 N/mm, else 1
  /// True when ISO's index 1 (fewer teeth) is the spec's `gear`, i.e. z_gear < z_pinion.
  bool iso_pinion_is_spec_gear = false;
  /// Validity-range notes (x outside the q' fit range, ε_α < 1.2, clamped C_R inputs, ...).
  std::vector<std::string> warnings;
};

/// @brief ISO 6336-1:2006/2019 method B single and mesh stiffness of a pair.
///
/// q' = C1 + C2/z_n1 + C3/z_n2 + C4 x1 + C5 x1/z_n1 + C6 x2 + C7 x2/z_n2 + C8 x1² + C9 x2²
/// [mm·µm/N], index 1 = fewer teeth; internal gears and racks use z_n2 = ∞ (a rack is index 2). C_R
/// of a webbed blank: 1 + ln(b_s/b) / (5 exp(s_R / (5 m_n))), with b_s/b clamped to [0.2, 1.2] and
/// s_R/m_n ≥ 1; the mesh uses the smaller of the two blanks' values (one C_R per mesh, see
/// rim_factor).
/// @throws InvalidInput if options are not finite/positive, or a blank gives web_thickness
///   without rim_thickness (message names the field).
IsoMeshStiffness CalcIsoMeshStiffness(const GearPairGeometry& g, const IsoStiffnessOptions& o = {});

}  // namespace geardyn
