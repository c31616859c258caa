/// @file
/// @brief Tooth friction of Kim et al. (2015) Eq. (13), f_f = μ |f_n|, with a regularised sign of
/// the sliding velocity (spec 03 "Contact").
///
/// **Regularisation.** Coulomb's sign(v_s) is replaced by tanh(v_s/ε): smooth, odd, bounded by 1
/// and within e^{−2|v_s|/ε}·2 of sign(v_s) (0.04 % at |v_s| = 4ε). The friction force on the
/// surface that slides with v_s relative to its mate is
/// \f[ f_t = −μ f_n \tanh(v_s/ε) \f]
/// (opposing the sliding), so its power −f_t v_s = μ f_n v_s tanh(v_s/ε) ≥ 0 is always
/// dissipated. **Default ε = 0.01 m/s**: on the Kahraman–Blankenship rig (two 50-tooth gears,
/// r_b = 70.5 mm) at the lowest mesh frequency of Kim's sweep (700 Hz, 88 rad/s per gear) the
/// sliding speed at the ends of the path of contact is (ω_1 + ω_2)·(distance from the pitch
/// point, ≈ 5 mm) ≈ 0.9 m/s, so ε is about 1 % of it; only the passage through the pitch point
/// (where v_s changes sign) is smoothed. A smaller ε is closer to Coulomb and stiffer
/// (∂f_t/∂v_s = μ f_n/ε at v_s = 0).
#pragma once

namespace geardyn {

/// Default regularisation speed ε of the friction sign [m/s] (see the @file).
inline constexpr double kDefaultFrictionSpeed = 0.01;

/// @brief Friction force and its derivatives at one contact.
struct FrictionValue {
  double force = 0.0;             ///< f_t = −μ f_n tanh(v_s/ε) [N] (opposes v_s)
  double d_force_d_normal = 0.0;  ///< ∂f_t/∂f_n = −μ tanh(v_s/ε) [-]
  double d_force_d_speed = 0.0;   ///< ∂f_t/∂v_s = −μ f_n (1 − tanh²)/ε [N·s/m]
  double dissipation = 0.0;       ///< D = −f_t v_s ≥ 0 [W]
};

/// @brief Regularised Coulomb friction (see the @file).
/// @param[in] mu μ ≥ 0 [-]. @param[in] normal_force f_n ≥ 0 [N].
/// @param[in] sliding_speed v_s [m/s]. @param[in] speed_scale ε > 0 [m/s].
/// @pre μ ≥ 0, ε > 0 (validated by the scene reader / ContactMeshDef; not re-checked here).
FrictionValue EvalFriction(double mu, double normal_force, double sliding_speed,
                           double speed_scale);

}  // namespace geardyn
