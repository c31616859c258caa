/// @file
/// @brief Kim et al.'s option (spec 03): the involute flank between the form and the corner roll
/// approximated by N tangent-continuous biarcs, and the contact of two such flanks (arc–arc, and
/// arc–point for the sharp tip corners), with the same output as the exact kernel
/// (involute_contact.hpp) so that the two can be compared.
///
/// **Fit.** The roll range [ρ_F, ρ_t] is cut into N equal segments; on each, the biarc with equal
/// tangent lengths d (a standard choice, equivalent in accuracy to Bolton's) joins the involute's
/// end points P0, P1 with its unit tangents T0, T1:
/// \f[ d = \frac{−v·t + \sqrt{(v·t)^2 + 2(1 − T_0·T_1)|v|^2}}{2(1 − T_0·T_1)},\quad
///     v = P_1 − P_0,\ t = T_0 + T_1, \f]
/// junction J = ½(P0 + d T0 + P1 − d T1); each arc is the circle through its end point tangent to
/// the involute there and through J. Position and tangent are interpolated, so the deviation
/// falls as O(h³) with the segment length h (tested: observed order ≈ 3). max_deviation() is the
/// largest distance of the involute from the biarcs over 64 samples per segment.
///
/// **Contact.** Convex arcs (A: centre C_A, radius r_A; B likewise) touch along C_A C_B:
/// δ = r_A + r_B − |C_B − C_A|, normal n = (C_B − C_A)/|C_B − C_A| (the force direction on B),
/// valid when the touching points lie within both arcs' spans and |δ| ≤ max_depth. The tip corner
/// is one more arc of each flank: the corner circle (centre Q, radius ρ_a ≥ 0; tip_corner_contact
/// .hpp) spanning the directions from the flank normal at ρ_t to the tip radial of Q, so a sharp
/// corner (ρ_a = 0) is the point Q. The largest valid δ is returned.
///
/// **Lookup.** CalcBiarcContact tries all arc pairs (O(N²)); it is the reference.
/// CalcBiarcContactNear tries only the arcs around given roll distances (the arc of a roll is found
/// in O(1): equal roll segments, one junction roll each) and their neighbours, plus the corners
/// when the last arc is among them: O(1). The core passes the exact kernel's rolls, which lie
/// within O(h²) of the biarc contact's (tested equal to the all-pairs result).
///
/// **Derivatives** (closed form, pose order (c1, β1, c2, β2)): arc centres move rigidly with their
/// flank pose, ∂C/∂(c, β) = [I, J(C − c)]; ∂δ = n·∂C_A − n·∂C_B; ∂n = (I − nnᵀ)(∂C_B − ∂C_A)/|d|;
/// P1 = C_A + r_A n, P2 = C_B − r_B n; roll1/roll2 are the involute rolls √(|P − c|² − r_b²) of the
/// touching points (for relief lookups; ρ_t on a corner, as the exact corner kernel reports), with
/// ∂ρ = (P − c)·(∂P − ∂c)/ρ; d_point = ½(∂P1 + ∂P2).
#pragma once

#include <vector>

#include "geardyn/common/eigen_types.hpp"
#include "geardyn/models/contact/involute_contact.hpp"
#include "geardyn/models/contact/tooth_flank.hpp"

namespace geardyn {

/// @brief One circular arc of a biarc flank, in the flank's canonical frame (c = 0, β = 0).
struct FlankArc {
  Vector2 center = Vector2::Zero();  ///< C [m]
  double radius = 0.0;               ///< r > 0 [m]
  Vector2 start = Vector2::UnitX();  ///< unit direction from C to the arc's first point [-]
  Vector2 end = Vector2::UnitX();    ///< unit direction from C to the arc's last point [-]
};

/// @brief The biarc approximation of one flank shape (see the @file).
class BiarcFlank {
 public:
  /// @param[in] geometry flank geometry (r_b, ρ_F, ρ_t).
  /// @param[in] unwind ε = ±1 of the flank.
  /// @param[in] num_biarcs N ∈ [1, 1000].
  /// @throws InvalidInput naming "num_biarcs" or "unwind".
  BiarcFlank(const ToothFlankGeometry& geometry, int unwind, int num_biarcs);

  /// The 2N arcs from the form circle to the corner, canonical frame.
  const std::vector<FlankArc>& arcs() const { return arcs_; }
  /// Largest distance between the involute and the biarcs [m].
  double max_deviation() const { return max_deviation_; }
  /// Base radius r_b [m].
  double base_radius() const { return base_radius_; }
  /// The tip corner as an arc (canonical frame): centre Q, radius ρ_a ≥ 0, from the flank normal at
  /// ρ_t to the tip radial direction of Q.
  const FlankArc& corner() const { return corner_; }
  /// Index of the arc holding the flank point of roll distance ρ [m] (clamped to the flank), O(1).
  int ArcIndex(double roll) const;

 private:
  std::vector<FlankArc> arcs_;
  std::vector<double> junction_roll_;  // involute roll of each biarc's junction [m]
  FlankArc corner_;
  double max_deviation_ = 0.0, base_radius_ = 0.0, form_roll_ = 0.0, segment_ = 0.0;
};

/// @brief Contact of two biarc flanks placed at the poses of their exact flanks (the @file).
/// @param[in] a, pose_a flank of body 1: its biarcs and its pose (centre, β, max_depth).
/// @param[in] b, pose_b flank of body 2.
FlankContact CalcBiarcContact(const BiarcFlank& a, const InvoluteFlankPose& pose_a,
                              const BiarcFlank& b, const InvoluteFlankPose& pose_b);

/// @brief The same contact searched only near given roll distances (the @file's lookup): the arcs
/// of roll_a on a and roll_b on b and their neighbours (3 × 3 pairs), and the corners when a last
/// arc is among them. Never allocates, O(1) in N.
/// @param[in] roll_a, roll_b roll distances [m] near the contact on each flank (e.g. the exact
///   kernel's ρ1, ρ2; ρ_t for a tip corner).
FlankContact CalcBiarcContactNear(const BiarcFlank& a, const InvoluteFlankPose& pose_a,
                                  double roll_a, const BiarcFlank& b,
                                  const InvoluteFlankPose& pose_b, double roll_b);

}  // namespace geardyn
