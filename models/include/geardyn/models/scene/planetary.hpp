/// @file
/// @brief Kinematics, drive sign and mesh phasing of a planetary (epicyclic) gear set
/// (PlanetaryDef, scene.hpp): the facts that the scene → system builder needs beyond the
/// parallel-axis rules.
///
/// **Speeds** (Willis): relative to the carrier every mesh obeys the fixed-axis rule, so with
/// t = Ω_s − Ω_c: Ω_s = Ω_c + t, Ω_r = Ω_c − (z_s/z_r) t, Ω_p = Ω_c − (z_s/z_p) t, and the fixed
/// member has Ω = 0. Every member's speed is a_m t (PlanetarySpeedFactors).
///
/// **Drive sign** of the sun meshes, s_s = sign of the external torque T_s on the sun: from the
/// operating point's torque T on its body m ∈ {sun, ring, carrier} by the static torque ratios
/// T_s : T_r : T_c = 1 : z_r/z_s : −(1 + z_r/z_s) (ideal, lossless). The ring meshes have the
/// planet as pinion, whose driving torque is the reaction of the sun mesh: s_r = −s_s.
///
/// **Mesh phasing** (Parker & Lin 2004, J. Mech. Des. 126, "Mesh phasing relationships in
/// planetary and epicyclic gears"), in geardyn's convention: every planetary mesh has the same
/// mesh frequency, so its phase is θ_k = θ + φ_k with phase ratio 1, where θ_k = 0 means a contact
/// line through the mesh's pitch point (mid face) and θ_k grows by 2π per base pitch of travel
/// along the path of contact (A → E). Rolling the set in the drive direction by a sun angle δ
/// (relative to the carrier) advances every θ_k by z_s δ. With planet n at ψ_n:
/// \f[ φ_{s,n} = −s_s z_s (ψ_n − ψ_0), \qquad φ_{r,n} = φ_{s,n} + Δ \pmod{2π}, \f]
/// i.e. Parker & Lin's sun–planet phase z_s ψ_n/2π and ring–planet phase −z_r ψ_n/2π (cycles of
/// lag, for s_s = +1), which agree because (z_s + z_r) ψ_n / 2π is an integer (the assembly
/// condition the reader enforces). Δ is the ring–planet phase of a planet relative to its own
/// sun–planet mesh, from the planet's tooth geometry in the transverse plane at mid face
/// (CalcSunRingMeshPhase):
/// \f[ Δ = −z_p\,(\mathrm{inv}\,α_{w,sp} + \mathrm{inv}\,α_{w,rp} + π − Θ_b), \qquad
///     Θ_b = s_t / r + 2\,\mathrm{inv}\,α_t, \f]
/// with α_w the transverse operating pressure angles of the two meshes, Θ_b the planet's tooth
/// thickness angle at the base circle (s_t the transverse tooth thickness at the reference radius
/// r, α_t the transverse pressure angle; no backlash allowance). The sun mesh loads one flank of
/// the planet's teeth and the ring mesh the other; Δ is the roll (in base pitches, × 2π) between
/// a loaded flank at the sun-side pitch point and the nearest one at the ring-side pitch point.
/// For standard gears (x = 0, α_w = α_t) Δ = π (z_p − 1) mod 2π: 0 for odd z_p, π for even z_p.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "geardyn/models/gear/gear_geometry.hpp"
#include "geardyn/models/scene/scene.hpp"

namespace geardyn {

/// @brief a_m of every member of the set (sun, ring, carrier, planets) with Ω_m = a_m t and
/// t = Ω_s − Ω_c [-] (see the @file); a_fixed = 0.
std::map<std::string, double, std::less<>> PlanetarySpeedFactors(const PlanetaryDef& set);

/// @brief Drive sign s_s = ±1 of the set's sun meshes (see the @file); +1 with a warning when the
/// operating point's torque is 0 or not on a central member of the set.
int PlanetarySunDriveSign(const Scene& scene, const PlanetaryDef& set,
                          std::vector<std::string>* warnings = nullptr);

/// @brief Δ = θ_ring − θ_sun [rad] in [0, 2π) of one planet (see the @file).
/// @param[in] sun_planet geometry of the sun–planet pair (pinion = sun, gear = planet).
/// @param[in] planet_ring geometry of the planet–ring pair (pinion = planet, gear = ring).
double CalcSunRingMeshPhase(const GearPairGeometry& sun_planet,
                            const GearPairGeometry& planet_ring);

/// @brief Phase offsets φ [rad] in [0, 2π) of the sun meshes and ring meshes, per planet.
struct PlanetaryMeshPhases {
  std::vector<double> sun;   ///< φ_{s,n}
  std::vector<double> ring;  ///< φ_{r,n}
};

/// @brief The offsets of the @file for the set's planets and sun drive sign s_s.
PlanetaryMeshPhases CalcPlanetaryMeshPhases(const PlanetaryDef& set, int sun_drive_sign);

}  // namespace geardyn
