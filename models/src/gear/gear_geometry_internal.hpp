/// @file
/// @brief Pieces of the pair geometry shared by gear_geometry.cpp (gear pairs) and
/// rack_geometry.cpp (the gear–rack pair).
#pragma once

#include "geardyn/models/gear/gear_geometry.hpp"

namespace geardyn::internal {

/// inv α = tan α − α.
double Involute(double alpha);

/// The scalar and blank checks of CalcGearPairGeometry, in its order (a rack blank's tooth count
/// is not checked). @throws InvalidInput naming the field.
void ValidateGearPairSpec(const GearPairSpec& spec);

/// The other hand (kNone stays kNone).
HelixHand OppositeHand(HelixHand hand);

/// Total contact-line length extremes in units of b / cos β_b (spec 01 §4.1).
void ContactLineExtremes(double eps_alpha, double eps_beta, double* lo, double* hi);

/// m_t, α_t, β_b, p_bt and p_bn of the pair's spec (ISO 21771, transverse section).
void FillTransverseBasics(GearPairGeometry* pair);

/// Face width b = min(b1, b2), ε_α = g_α / p_bt (≥ 1), ε_β = b sin β / (π m_n) (≤
/// kMaxOverlapRatio), ε_γ and the contact-line lengths, from the pair's spec,
/// line_of_action_length, transverse_base_pitch and base_helix_angle. @throws InvalidInput naming
/// the ratio.
void FillContactRatios(GearPairGeometry* pair);

/// CalcGearPairGeometry for spec.gear.kind == kRack (gear_geometry.hpp, "Rack"); the spec has
/// passed ValidateGearPairSpec.
GearPairGeometry CalcRackPairGeometry(const GearPairSpec& spec);

}  // namespace geardyn::internal
