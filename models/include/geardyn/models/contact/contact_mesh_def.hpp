/// @file
/// @brief What a scene's `[mesh.contact]` table asks of the tooth-contact mesh (model =
/// "contact", spec 03): tooth bodies, tooth mass, the contact law, friction, the flank profile and
/// the face slices — all SI — and the defaults derived from the gear geometry. One table per
/// mesh; its tooth settings apply to the teeth of both gears. Scene keys: docs/scene-format.md,
/// "Tooth contact".
#pragma once

#include <optional>
#include <string>

#include "geardyn/models/contact/contact_law.hpp"
#include "geardyn/models/contact/friction.hpp"
#include "geardyn/models/contact/tooth_body.hpp"
#include "geardyn/models/gear/gear_geometry.hpp"

namespace geardyn {

/// @brief The flank profile the contact search uses.
enum class ContactProfile {
  kInvolute,  ///< exact involutes (closed-form contact on the line of action, spec 03)
  kBiarc,     ///< Kim's approximation of each flank by biarcs (Bolton's method)
};

/// Name: "involute", "biarc".
const char* ToString(ContactProfile profile);

/// Default density of the teeth: steel [kg/m³].
inline constexpr double kSteelDensity = 7850.0;
/// Default Young's modulus (Kim et al. Table 4, steel) [Pa].
inline constexpr double kSteelYoungModulus = 2.0e11;
/// Default Poisson's ratio of steel [-].
inline constexpr double kSteelPoisson = 0.3;
/// Shear correction factor of the bushing's default tangential stiffness (rectangular section).
inline constexpr double kShearCorrection = 5.0 / 6.0;

/// @brief The `[mesh.contact]` table of one mesh (see docs/scene-format.md "Tooth contact").
struct ContactMeshDef {
  ToothBodyType teeth = ToothBodyType::kRigid;  ///< tooth bodies of both gears
  double bending_stiffness = 0.0;               ///< k_b > 0 [N·m/rad] (revolute, bushing rotation)
  double bending_damping = 0.0;                 ///< c_b ≥ 0 [N·m·s/rad]
  /// Bushing radial / tangential stiffness [N/m]; absent: from the tooth geometry
  /// (ResolveBushing).
  std::optional<double> bushing_radial_stiffness;
  std::optional<double> bushing_tangential_stiffness;
  /// Bushing radial / tangential damping [N·s/m]; absent: stiffness-proportional, k·c_b/k_b.
  std::optional<double> bushing_radial_damping;
  std::optional<double> bushing_tangential_damping;
  double density = kSteelDensity;             ///< ρ [kg/m³] of the teeth (not with tooth_mass)
  std::optional<double> tooth_mass;           ///< m [kg] of one tooth, with tooth_inertia
  std::optional<double> tooth_inertia;        ///< J_c [kg·m²] of one tooth about its centroid
  ContactLaw law = KimContactLaw();           ///< normal contact law (kLine: contact_modulus set)
  double young_modulus = kSteelYoungModulus;  ///< E [Pa] (line law, bushing defaults)
  double poisson = kSteelPoisson;             ///< ν [-] (line law, bushing defaults)
  double friction_coefficient = 0.0;          ///< μ ≥ 0 [-] (Kim Eq. 13; 0: frictionless)
  double friction_speed = kDefaultFrictionSpeed;       ///< ε > 0 [m/s] (friction.hpp)
  ContactProfile profile = ContactProfile::kInvolute;  ///< flank profile
  int arcs = 4;                                        ///< biarcs per flank (profile = "biarc")
  double tip_corner_radius = 0.0;  ///< radius of the rounded tip corner [m] (0: sharp)
  int face_slices = 1;             ///< slices of the face width, each a transverse contact
};

/// @brief Stiffness and damping of a type-B (bushing) tooth joint.
struct BushingJoint {
  double radial_stiffness = 0.0;      ///< k_r [N/m]
  double tangential_stiffness = 0.0;  ///< k_t [N/m]
  double rotational_stiffness = 0.0;  ///< k_b [N·m/rad]
  double radial_damping = 0.0;        ///< c_r [N·s/m]
  double tangential_damping = 0.0;    ///< c_t [N·s/m]
  double rotational_damping = 0.0;    ///< c_b [N·m·s/rad]
};

/// @brief The bushing of one gear's teeth: the given values, else the tooth as a uniform bar of
/// its root section A_f = s_f b (s_f the chord at the root circle, b the face width) and length
/// h = r_a − r_f: compression k_r = E A_f / h and shear k_t = κ G A_f / h with G = E/(2(1 + ν)),
/// κ = 5/6 (kShearCorrection). These are upper bounds of the real compliances of a tapered
/// tooth on an elastic rim (the rotation k_b, which Kim gives, dominates the tooth's compliance
/// along the line of action; Kim gives no translational values). Dampings default to
/// k·c_b/k_b (the rotational joint's time constant).
BushingJoint ResolveBushing(const ContactMeshDef& def, const GearGeometry& gear);

/// @brief The tooth set of one gear: the type, z, and the mass properties from the section
/// (CalcToothSection × density × face width) or from tooth_mass / tooth_inertia (centroid and
/// joint from the section).
/// @throws InvalidInput as CalcToothSection (internal gears) when the teeth are not rigid.
ToothSet ResolveToothSet(const ContactMeshDef& def, const GearGeometry& gear);

}  // namespace geardyn
