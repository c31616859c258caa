/// @file
/// @brief ISO 6336-1 method B tooth stiffness (c', c_γα, c_γβ).
///
/// Sources: ISO 6336-1:2006 §9 (tooth stiffness parameters, method B) and ISO 6336-1:2019 §9,
/// which splits c_γ into c_γα and c_γβ = 0.85 c_γα. Choices made here where the standard is
/// silent or ambiguous:
/// * Index 1 is the gear with fewer teeth ("pinion" in ISO 6336) whichever member drives; on a tie
///   the spec's pinion is index 1. For an internal pair the external member always has fewer teeth.
/// * Internal gears: ISO 6336-1 replaces z_n2 by infinity in q' (the terms C3/z_n2 and
///   C7 x2/z_n2 vanish). It gives no other rule for x2; the ring's x2 enters C6 x2 + C9 x2² with
///   the ISO 21771 sign used throughout geardyn (positive x thickens the ring's teeth).
/// * C_R: ISO 6336-1 gives one gear blank factor for the mesh, from the web thickness b_s and rim
///   thickness s_R of a webbed blank (solid discs: C_R = 1); its curves are mean values for a
///   mating gear of similar or stiffer blank design. A pair therefore takes the C_R of its more
///   flexible blank, min(C_R1, C_R2): the other blank is then the "similar or stiffer" mate. Two
///   equal webbed blanks give the single-web value (not its square; KISSsoft prints the same one
///   value per mesh), one webbed blank gives its own value, two solid blanks 1. Each blank's
///   b_s/b uses its own face width b.
#include "geardyn/models/gear/iso_stiffness.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "geardyn/common/check.hpp"
#include "geardyn/common/units.hpp"

namespace geardyn {
namespace {

// ISO 6336-1 Table (method B, q' fit) constants C1..C9 [mm·µm/N].
constexpr double kC[9] = {0.04723,  0.15551,  0.25791, -0.00635, -0.11654,
                          -0.00193, -0.24188, 0.00529, 0.00182};
constexpr double kMmUmPerNToSi = 1e-9;      // 1 mm·µm/N = 1e-3 m · 1e-6 m / N
constexpr double kReferenceLineLoad = 1e5;  // 100 N/mm in N/m

std::string Str(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

/// C_R of one blank (ISO 6336-1): 1 for a solid blank, else 1 + ln(b_s/b) / (5 e^{s_R/(5 m_n)})
/// with b_s/b clamped to [0.2, 1.2] and s_R/m_n to ≥ 1 as the standard prescribes.
double RimFactor(const GearBlank& blank, const std::string& name, double m_n,
                 std::vector<std::string>* warnings) {
  if (!blank.web_thickness) return 1.0;
  GEARDYN_THROW_UNLESS(blank.rim_thickness.has_value(),
                       name << ".rim_thickness: required with web_thickness for ISO 6336-1 C_R");
  double bs_b = *blank.web_thickness / blank.face_width;
  double sr_m = *blank.rim_thickness / m_n;
  if (bs_b < 0.2 || bs_b > 1.2) {
    warnings->push_back(name + ".web_thickness: b_s/b = " + Str(bs_b) +
                        " outside [0.2, 1.2]; clamped for C_R as ISO 6336-1 prescribes");
    bs_b = std::clamp(bs_b, 0.2, 1.2);
  }
  if (sr_m < 1.0) {
    warnings->push_back(name + ".rim_thickness: s_R/m_n = " + Str(sr_m) +
                        " below 1; set to 1 for C_R as ISO 6336-1 prescribes");
    sr_m = 1.0;
  }
  return 1.0 + std::log(bs_b) / (5.0 * std::exp(sr_m / 5.0));
}

/// C_B of one basic rack (ISO 6336-1): [1 + 0.5 (1.2 − h_fP/m_n)] [1 − 0.02 (20° − α_Pn)].
double BasicRackFactor(const GearBlank& blank, double alpha_n) {
  return (1.0 + 0.5 * (1.2 - blank.dedendum_coefficient)) *
         (1.0 - 0.02 * (20.0 - RadToDeg(alpha_n)));
}

}  // namespace

IsoMeshStiffness CalcIsoMeshStiffness(const GearPairGeometry& g, const IsoStiffnessOptions& o) {
  GEARDYN_THROW_UNLESS(std::isfinite(o.blank_factor) && o.blank_factor > 0.0,
                       "blank_factor: must be finite and positive, got " << o.blank_factor);
  if (o.line_load) {
    GEARDYN_THROW_UNLESS(std::isfinite(*o.line_load) && *o.line_load > 0.0,
                         "line_load: must be finite and positive, got " << *o.line_load << " N/m");
  }
  const GearPairSpec& spec = g.spec;
  IsoMeshStiffness out;

  // ISO index 1 = fewer teeth (a rack has infinitely many).
  const bool swap = !g.rack && spec.gear.teeth < spec.pinion.teeth;
  out.iso_pinion_is_spec_gear = swap;
  const GearGeometry& g1 = swap ? g.gear : g.pinion;
  const GearGeometry& g2 = swap ? g.pinion : g.gear;
  const double zn1 = g1.virtual_teeth;
  // z_n2 = ∞ for an internal gear (ISO 6336-1) and for a rack (the limit z_2 → ∞).
  const double inv_zn2 = g2.kind == GearKind::kExternal ? 1.0 / g2.virtual_teeth : 0.0;
  const double x1 = g1.profile_shift;
  const double x2 = g2.profile_shift;

  // q' [mm·µm/N] (ISO 6336-1 method B).
  const double q_mm_um = kC[0] + kC[1] / zn1 + kC[2] * inv_zn2 + kC[3] * x1 + kC[4] * x1 / zn1 +
                         kC[5] * x2 + kC[6] * x2 * inv_zn2 + kC[7] * x1 * x1 + kC[8] * x2 * x2;
  GEARDYN_DEMAND(q_mm_um > 0.0);
  if (x1 < x2 || x1 + x2 < -0.5 || x1 + x2 > 2.0) {
    out.warnings.push_back("q_prime: profile shifts x1 = " + Str(x1) + ", x2 = " + Str(x2) +
                           " (index 1 = fewer teeth) lie outside the range of the ISO 6336-1 "
                           "fit (x1 >= x2, -0.5 <= x1 + x2 <= 2)");
  }
  if (spec.helix_angle > DegToRad(45.0)) {
    out.warnings.push_back("single_pair: helix angle " + Str(RadToDeg(spec.helix_angle)) +
                           " deg exceeds 45 deg, the range of ISO 6336-1 method B");
  }
  out.q_prime = q_mm_um * kMmUmPerNToSi;
  out.theoretical_single_pair = 1.0 / out.q_prime;

  out.blank_factor = o.blank_factor;
  // One C_R per mesh (ISO 6336-1): the more flexible blank's, its mate being similar or stiffer.
  out.rim_factor = std::min(RimFactor(spec.pinion, "pinion", spec.normal_module, &out.warnings),
                            RimFactor(spec.gear, "gear", spec.normal_module, &out.warnings));
  out.basic_rack_factor = 0.5 * (BasicRackFactor(spec.pinion, spec.normal_pressure_angle) +
                                 BasicRackFactor(spec.gear, spec.normal_pressure_angle));
  if (o.line_load && *o.line_load < kReferenceLineLoad) {
    out.line_load_factor = std::pow(*o.line_load / kReferenceLineLoad, 0.25);
  }
  out.single_pair = out.theoretical_single_pair * out.blank_factor * out.rim_factor *
                    out.basic_rack_factor * std::cos(spec.helix_angle) * out.line_load_factor;

  // Mesh stiffness (ISO 6336-1:2019; c_γ of 2006 = c_γα): valid for ε_α >= 1.2.
  out.mesh_alpha = out.single_pair * (0.75 * g.transverse_contact_ratio + 0.25);
  out.mesh_beta = 0.85 * out.mesh_alpha;
  if (g.transverse_contact_ratio < 1.2) {
    out.warnings.push_back("mesh_alpha: eps_alpha = " + Str(g.transverse_contact_ratio) +
                           " < 1.2; ISO 6336-1 notes c_gamma_alpha may then be up to 10 % lower "
                           "for spur gears");
  }
  return out;
}

}  // namespace geardyn
