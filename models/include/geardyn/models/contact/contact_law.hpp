/// @file
/// @brief Normal contact force laws of the tooth-contact core (spec 03 "Contact"): Kim et al.
/// (2015) Eq. (12), the linear spring–damper and the line-contact (Johnson) law of two cylinders
/// that Kosenko & Gusev use — each with its derivatives, stored energy and dissipated power.
///
/// **One form.** Every law is an elastic part plus Kim's indentation damping,
/// \f[ f = f_e(δ) + c\,\mathrm{sign}(\dot δ)\,|\dot δ|^{m_2}\,δ^{m_3}, \qquad δ > 0, \f]
/// and f = 0 for δ ≤ 0 (no contact). f_e: Kim k δ^{m_1}; linear k δ (with m_2 = 1, m_3 = 0: the
/// viscous k δ + c δ̇); line: Johnson's compliance (below). **No adhesion**: f is clamped at 0 when
/// a fast separation makes the damping term pull (f_e + f_d < 0).
///
/// **Energy and power.** E(δ) = ∫₀^δ f_e dδ' [J] is the stored energy; every law satisfies
/// f δ̇ = dE/dt + D with the dissipated power D = (f − f_e) δ̇ ≥ 0 [W]: the damping power
/// f_d δ̇ = c |δ̇|^{m_2+1} δ^{m_3} ≥ 0 when f is not clamped, and −f_e δ̇ ≥ 0 when it is (f = 0
/// only while separating, δ̇ < 0: the spring energy released then is lost, as in an impact).
///
/// **Kim's values** (Table 2, in N, mm, s): k = 39.3e6 N/mm^{1.5}, c = 1.0 N·s/mm (read as
/// N·s/mm^{m_2+m_3}, see KimContactLaw), m_1 = 1.5, m_2 = 1, m_3 = 0.25. A quantity whose unit
/// contains mm^{−p} converts to SI as X[SI] = X[mm units]·1000^p.
///
/// **Line contact** (Johnson, Contact Mechanics 1985, §5.6 Eq. (5.39); Kosenko & Gusev's
/// "Johnson contact model for cylindrical bodies"): two cylinders of radii R_1, R_2 (for involute
/// flanks, the radii of curvature = the roll distances of the contact point), length L, pressed by
/// F have the approach
/// \f[ δ(F) = \frac{F}{π L E^*}\left[\ln\frac{4R_1}{a} + \ln\frac{4R_2}{a} − 1\right], \quad
///     a^2 = \frac{4 F R}{π L E^*},\quad \frac1R = \frac1{R_1} + \frac1{R_2}, \f]
/// i.e. δ = A F (ln(B/F) − 1) with A = 1/(π L E*), B = 4π L E*(R_1 + R_2). It is inverted in
/// closed form with the Lambert W function (branch −1): with d = δ/(AB),
/// F = B e^{−1−v}, v = −W_{−1}(−e d), and dF/dδ = 1/(A(v − 1)); E = A F²(ln(B/F) − 3/2)/2.
/// δ(F) is increasing only for ln(B/F) > 2 (d < e^{−2}); beyond v = 2 (d = 2e^{−3}, an approach
/// of 8(R_1 + R_2)/e³ ≈ 0.4(R_1 + R_2), far beyond any tooth contact) the force is continued
/// linearly with the slope there, π L E*, so that the law stays defined and C¹.
#pragma once

#include <string>

namespace geardyn {

/// @brief Force, derivatives, energy and power of one contact at one (δ, δ̇).
struct ContactLawValue {
  double force = 0.0;           ///< f ≥ 0 [N]
  double d_force_d_gap = 0.0;   ///< ∂f/∂δ [N/m]
  double d_force_d_rate = 0.0;  ///< ∂f/∂δ̇ [N·s/m]
  double energy = 0.0;          ///< E = ∫₀^δ f_e dδ' [J]
  double dissipation = 0.0;     ///< D = (f − f_e) δ̇ ≥ 0 [W]
  bool clamped = false;         ///< f_e + f_d < 0 was clamped to 0 (separating fast)
};

/// @brief Which elastic part f_e(δ) a ContactLaw has.
enum class ContactLawKind {
  kKim,     ///< f_e = k δ^{m_1} (Kim et al. 2015 Eq. 12)
  kLinear,  ///< f_e = k δ, damping c δ̇ (m_2 = 1, m_3 = 0)
  kLine,    ///< Johnson's line contact of two cylinders (see the @file)
};

/// Name of a kind: "kim", "linear", "line".
const char* ToString(ContactLawKind kind);

/// @brief A normal contact law (see the @file); all values SI.
struct ContactLaw {
  ContactLawKind kind = ContactLawKind::kKim;
  /// k: kKim [N/m^{m_1}], kLinear [N/m]; unused by kLine.
  double stiffness = 0.0;
  /// m_1 > 0 [-] (kKim; 1 for kLinear).
  double stiffness_exponent = 1.0;
  /// c ≥ 0 [N·s^{m_2}/m^{m_2+m_3}] (kLinear: N·s/m).
  double damping = 0.0;
  /// m_2 ≥ 1 [-]: below 1, ∂f/∂δ̇ ∝ |δ̇|^{m_2−1} is unbounded at δ̇ = 0 (kLinear: 1).
  double damping_exponent = 1.0;
  /// m_3 ≥ 0 [-] (indentation exponent; kLinear: 0).
  double indentation_exponent = 0.0;
  /// E* > 0 [Pa] (kLine): 1/E* = (1 − ν_1²)/E_1 + (1 − ν_2²)/E_2.
  double contact_modulus = 0.0;

  /// False (with the field, value and bound in `why`) on a value out of range.
  bool IsValid(std::string* why) const;
};

/// @brief Kim et al. (2015) Table 2 in SI: k = 39.3e6·1000^{1.5} N/m^{1.5}, m_1 = 1.5,
/// c = 1.0·1000^{1.25} N·s/m^{1.25}, m_2 = 1, m_3 = 0.25.
///
/// **Reading of c = "1.0 N·s/mm".** With m_2 = 1 and m_3 = 0.25, f = c δ̇ δ^{0.25} makes c a
/// N·s/mm^{1.25} in Kim's N–mm–s model (RecurDyn works in those units and the table drops the
/// fractional power, as it does for k's N/mm^{1.5}). Reading δ^{0.25} in mm as a dimensionless
/// factor gives the same number, c·(1000 δ̇)(1000 δ)^{0.25}; only reading c as 1000 N·s/m with δ
/// in metres differs (by 1000^{0.25} = 5.6), and it would mix unit systems within one formula.
ContactLaw KimContactLaw();

/// @brief The linear law k δ + c δ̇.
/// @param[in] stiffness k > 0 [N/m]; @param[in] damping c ≥ 0 [N·s/m].
ContactLaw LinearContactLaw(double stiffness, double damping);

/// @brief E* [Pa] of two bodies of the same material: E / (2 (1 − ν²)).
/// @param[in] young_modulus E > 0 [Pa]; @param[in] poisson ν ∈ [0, 0.5).
/// @throws InvalidInput naming young_modulus or poisson.
double ContactModulusSameMaterial(double young_modulus, double poisson);

/// @brief Geometry of one line contact (kLine): the two radii of curvature and the length.
struct LineContactGeometry {
  double radius1 = 0.0;  ///< R_1 > 0 [m]
  double radius2 = 0.0;  ///< R_2 > 0 [m]
  double length = 0.0;   ///< L > 0 [m] (the face slice)
};

/// @brief The law at (δ, δ̇). kLine needs `line` (R_1, R_2, L > 0); the other kinds ignore it.
/// Never throws in the hot path; a non-finite input gives non-finite outputs.
/// @param[in] gap δ [m] (> 0: penetration). @param[in] gap_rate δ̇ [m/s].
ContactLawValue EvalContactLaw(const ContactLaw& law, double gap, double gap_rate,
                               const LineContactGeometry& line = {});

/// @brief Johnson's approach δ(F) [m] of two cylinders (the inverse of kLine's elastic force), on
/// the increasing branch F ≤ B e^{−3} (no continuation). For tests and the docs.
double LineContactApproach(double force, double contact_modulus, const LineContactGeometry& line);

}  // namespace geardyn
