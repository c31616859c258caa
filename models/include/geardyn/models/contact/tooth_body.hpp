/// @file
/// @brief Tooth bodies of the quasi-flexible-body (QFB) gear of Kim et al. (2015) (spec 03
/// "Bodies"): the tooth types, the tooth's transverse section from its outline, its mass and
/// inertia, and the mass the tooth coordinates add to the gear trunk's (the arrow matrix).
///
/// **Types** (Kim's Table 1; DOF per tooth): kRigid 0 (teeth part of the trunk); kRevolute 1,
/// Kim's case 2 ("type A"): a revolute joint at the root with a rotational spring–damper k_b,
/// c_b; kBushing 3, Kim's case 1 ("type B"): a bushing at the root, radial and tangential
/// translations u_r, u_t of the root point and the rotation φ. For two 50-tooth gears on the
/// torsional rig (one θz per gear): 2 + 100 = 102 (type A) and 2 + 300 = 302 (type B), Kim's
/// counts; with the 6-DOF gear bodies 12 + 100 = 112 and 12 + 300 = 312.
///
/// **Section** (CalcToothSection). The transverse section of one external tooth is the region
/// r_f ≤ r ≤ r_a, |φ| ≤ ψ(r) of polar coordinates about the gear centre (φ from the tooth's
/// centreline): two involute flanks, ψ(r) = ψ_b − inv α(r) with cos α(r) = r_b/r and
/// ψ_b = s_t/(2r) + inv α_t (s_t the transverse thickness at the reference radius r), above the
/// base circle; radial flanks ψ = ψ_b below it when r_f < r_b; the tip arc; and the root circle
/// arc between the two flank feet. **The root fillet is not modelled**: the material of the
/// fillets (below the flank feet, outside the radial extension) is left in the trunk, and the
/// tooth ends on the root circle. Its moments are 1-D integrals
/// \f[ A = ∫ 2ψ r\,dr,\quad A\bar r = ∫ 2\sin ψ\, r^2 dr,\quad J_O = ∫ 2ψ r^3 dr, \f]
/// evaluated by Gauss–Legendre quadrature in the roll angle t = tan α (r = r_b√(1+t²), smooth
/// where ψ(r) has a (r − r_b)^{3/2} term at the base circle).
///
/// **Mass** (ToothInertia). m = ρ b A, J_O = ρ b ∫r² dA about the gear axis, J_c = J_O − m r̄²
/// about the centroid, the joint (pivot) P on the centreline at the root circle, r_p = r_f, and
/// d = r̄ − r_p (the centroid's distance from P). Or given m and J_c (the centroid still from the
/// geometry).
///
/// **Mass matrix** (ToothCouplingMass, AssembleToothMass). Tooth coordinates are RELATIVE to
/// the trunk. In the trunk's rotating frame the centroid of tooth k moves tangentially by
/// r̄ θ + u_t + d φ, radially by u_r, and the tooth turns by θ + φ, so its kinetic energy is
/// ½ m (r̄ θ̇ + u̇_t + d φ̇)² + ½ m u̇_r² + ½ J_c (θ̇ + φ̇)²: in (θ, u_r, u_t, φ)
/// \f[ M_k = \begin{bmatrix} J_O & 0 & m\bar r & J_c + m\bar r d \\ 0 & m & 0 & 0 \\ m\bar r
///     & 0 & m & m d \\ J_c + m\bar r d & 0 & m d & J_c + m d^2 \end{bmatrix} \f]
/// (type A keeps θ and φ). These couplings with the trunk's θz do not depend on the tooth's
/// angular position (rotation invariance about the axis) and are kept exactly: the teeth form an
/// arrow matrix with the trunk's θz. The θθ entry J_O is NOT added: the scene's gear inertia
/// (mass) is that of the whole gear, teeth included, so with the teeth locked the torsional
/// inertia is the scene's J exactly; the trunk's own inertia J − z J_O must be positive
/// (CheckTrunkInertia). Neglected: the coupling of the tooth coordinates with the trunk's
/// translations x, y (it rotates with the tooth: time-varying); docs/design.md "Tooth bodies"
/// bounds its effect on the rig.
#pragma once

#include <functional>
#include <string>

#include "geardyn/common/eigen_types.hpp"
#include "geardyn/models/gear/gear_geometry.hpp"

namespace geardyn {

/// @brief How a tooth is joined to its trunk (see the @file).
enum class ToothBodyType {
  kRigid,     ///< 0 DOF: the tooth is part of the trunk
  kRevolute,  ///< 1 DOF (Kim's type A, case 2): rotation φ about the root joint
  kBushing,   ///< 3 DOF (Kim's type B, case 1): u_r, u_t of the root point, then φ
};

/// Name: "rigid", "revolute", "bushing".
const char* ToString(ToothBodyType type);

/// DOF per tooth: 0, 1, 3.
int ToothDofs(ToothBodyType type);

/// @brief Moments of one tooth's transverse section about the gear centre (see the @file).
struct ToothSection {
  double area = 0.0;             ///< A [m²]
  double centroid_radius = 0.0;  ///< r̄, distance of the centroid from the gear axis [m]
  double polar_moment = 0.0;     ///< ∫ r² dA about the gear axis [m⁴]
  double root_radius = 0.0;      ///< r_f, where the section ends [m]
  double root_thickness = 0.0;   ///< s_f = 2 r_f sin ψ(r_f), chord at the root circle [m]
  double height = 0.0;           ///< h = r_a − r_f [m]
};

/// @brief The section of an external involute tooth (see the @file).
/// @param[in] gear one gear of a pair (GearPairGeometry::pinion or ::gear).
/// @throws InvalidInput naming `gear.kind` for an internal gear (its teeth are the gaps of an
///   external one: not modelled), or `gear.tooth_thickness_transverse` when the flanks cross
///   below the tip (ψ(r_a) ≤ 0).
ToothSection CalcToothSection(const GearGeometry& gear);

/// @brief The section of the region r_in ≤ r ≤ r_out, |φ| ≤ ψ(r), for a given half angle ψ(r) of
/// a polar region (the general integrator behind CalcToothSection; n-point Gauss–Legendre in r).
/// @param[in] half_angle ψ(r) [rad], 0 ≤ ψ < π. @param[in] r_in, r_out [m], 0 ≤ r_in < r_out.
/// @param[in] points Gauss–Legendre points, ≥ 2.
ToothSection IntegratePolarSection(const std::function<double(double)>& half_angle, double r_in,
                                   double r_out, int points);

/// @brief Mass properties of one tooth (see the @file); all SI.
struct ToothInertia {
  double mass = 0.0;              ///< m [kg]
  double centroid_radius = 0.0;   ///< r̄ [m]
  double pivot_radius = 0.0;      ///< r_p, the root joint on the centreline [m]
  double centroid_inertia = 0.0;  ///< J_c about the centroid, axis ∥ gear axis [kg m²]
  /// J_O = J_c + m r̄², about the gear axis [kg m²].
  double AxisInertia() const { return centroid_inertia + mass * centroid_radius * centroid_radius; }
  /// J_p = J_c + m d², about the joint [kg m²].
  double PivotInertia() const {
    const double d = centroid_radius - pivot_radius;
    return centroid_inertia + mass * d * d;
  }
};

/// @brief m = ρ b A, J_c = ρ b (∫r² dA − A r̄²), r_p = r_f.
/// @param[in] density ρ > 0 [kg/m³]; @param[in] face_width b > 0 [m].
/// @throws InvalidInput naming density or face_width.
ToothInertia CalcToothInertia(const ToothSection& section, double density, double face_width);

/// @brief (1 + ToothDofs) square mass block of one tooth in (θz of the trunk, tooth coordinates
/// in the order u_r, u_t, φ / φ) (see the @file). kRigid: the 1×1 zero.
MatrixX ToothCouplingMass(ToothBodyType type, const ToothInertia& tooth);

/// @brief The teeth of one gear as the core sees them.
struct ToothSet {
  ToothBodyType type = ToothBodyType::kRigid;
  int teeth = 0;         ///< z [-]
  ToothInertia inertia;  ///< of every tooth (identical teeth)
  /// Number of internal coordinates: z·ToothDofs(type).
  int num_coordinates() const { return teeth * ToothDofs(type); }
};

/// @brief The mass the teeth of both gears add on x = [q_i (12); q_j (12); pinion teeth; gear
/// teeth] (n = 12 + both sets' coordinates): the arrow blocks of ToothCouplingMass on θz
/// (indices 5 and 11) and each tooth's coordinates; the θz diagonal gets nothing (the scene's
/// gear inertia already contains the teeth).
MatrixX AssembleToothMass(const ToothSet& pinion, const ToothSet& gear);

/// @brief Checks that a gear's trunk keeps a positive inertia: J − z J_O > 0 and m − z m_t > 0.
/// @param[in] what name of the gear for the message ("gear.wheel").
/// @throws InvalidInput naming `what`.inertia / .mass, the teeth's share and the gear's value.
void CheckTrunkInertia(const ToothSet& teeth, double gear_mass, double gear_inertia,
                       const std::string& what);

}  // namespace geardyn
