/// @file
/// @brief Tip-corner contact (spec 03: large deflections, contact off the line of action): the
/// rounded tip corner of one tooth (a circle of radius ρ_a ≥ 0; ρ_a = 0 is the sharp corner)
/// against the involute flank of the mating tooth, in closed form, with the same output as the
/// flank–flank kernel (involute_contact.hpp) and a continuous hand-over to it.
///
/// **Corner.** The corner circle is tangent to the flank at ρ_t = ToothFlankGeometry::corner_roll()
/// (= the corner flank's roll_max) and to the tip circle; its centre is
/// Q = c_A + r_bA e(t_A) + (ρ_t − ρ_a) n_A(t_A), t_A = β_A + ε_A ρ_t / r_bA.
///
/// **Closest point on the mate, no iteration.** Every normal of an involute is a tangent of its
/// base circle, so the foot of Q on the mating flank B (c_B, r_bB, β_B, ε_B) lies on the tangent
/// from Q to B's base circle on the side of B's unwinding sense: with d = Q − c_B, D = |d|,
/// \f[ t = ∠d + ε_B \arccos(r_{bB}/D),\quad λ = \sqrt{D^2 − r_{bB}^2},\quad
///     σ = ε_B r_{bB}\,\mathrm{wrap}(t − β_B), \f]
/// Q lies at λ − σ outside flank B along its outward normal n_B(t), and the penetration is
/// \f[ δ = ρ_a + σ − λ. \f]
/// (A Newton iteration on σ, as the brief of issue 14 suggested, is not needed.) The contact
/// normal (outward from the corner, force direction on the mate) is −n_B(t).
///
/// **Derivatives** with respect to (c_A, β_A, c_B, β_B): ∂δ/∂c_A = −n_B, ∂δ/∂β_A = −n_B·J(Q − c_A),
/// ∂δ/∂c_B = n_B, ∂δ/∂β_B = −ε_B r_bB; ∂σ from ∂t/∂d = J d̂/D + ε_B r_bB d̂/(D λ).
///
/// **Validity.** The corner touches only within its arc: −n_B must lie between the flank normal
/// n_A(t_A) and the tip radial direction (Q − c_A)/|Q − c_A|; σ within the mate's [ρ_F, ρ_t] and
/// |δ| ≤ max_depth. At the arc's flank end the corner and the involute share point and tangent,
/// so δ equals the flank–flank δ there (continuous hand-over, tested).
#pragma once

#include "geardyn/models/contact/involute_contact.hpp"
#include "geardyn/models/contact/tooth_flank.hpp"

namespace geardyn {

/// @brief The tip corner of `corner_flank`'s tooth against the flank `mate` (the @file).
/// Body 1 of the result is the corner's tooth (corner = 1): derivatives are ordered
/// (c_A, β_A, c_B, β_B), roll1 = ρ_t, roll2 = σ. Never allocates, never iterates.
/// @param[in] corner_flank pose of the flank whose tip corner touches (roll_max = ρ_t).
/// @param[in] corner_radius ρ_a ≥ 0 [m] (the geometry's tip_corner_radius).
/// @param[in] mate pose of the mating flank (same unwinding sense for an external pair).
FlankContact CalcTipCornerContact(const InvoluteFlankPose& corner_flank, double corner_radius,
                                  const InvoluteFlankPose& mate);

/// @brief The same contact seen with the bodies swapped: pose blocks exchanged, rolls and points
/// exchanged, normal reversed, corner 1 ↔ 2.
FlankContact SwapBodies(const FlankContact& contact);

}  // namespace geardyn
