/// @file
/// @brief The contact of two involute flanks of an external pair (the kernel of the contact
/// simulator, spec 03; Kosenko & Gusev): penetration in closed form from the two roll distances on
/// the common tangent of the base circles, no iteration, with its exact derivatives.
///
/// **Geometry.** Flank 1 (base circle c1, r1; tooth_flank.hpp) and flank 2 (c2, r2) with the same
/// unwinding sense ε (the only case in which they can touch on an external pair). With
/// D = c2 − c1, C = |D|, ê = D/C, R = r1 + r2 < C, the two internal common tangents of the base
/// circles touch circle 1 at T1 = c1 + r1 m and circle 2 at T2 = c2 − r2 m with
/// \f[ m = \cos α\, ê + ω \sin α\, ê^⊥,\quad \cos α = R/C,\quad L = |T1T2| = \sqrt{C^2 − R^2}. \f]
/// The direction from T1 to T2 is n = −ω J m, and a flank can lie on this line with its outward
/// normal pointing at the mate only if −ε J m = n, i.e. **ω = ε** (and ε2 = ε1). The flanks meet
/// the line at the roll distances (measured from T1, T2 towards each other)
/// \f[ ρ_1 = ε r_1\, \mathrm{wrap}(t_1 − β_1),\quad ρ_2 = ε r_2\, \mathrm{wrap}(t_2 − β_2),\quad
///     t_1 = ∠m,\ t_2 = t_1 + π, \f]
/// (wrap to (−π, π]), and since both flanks are normal to this line the penetration along it is
/// \f[ δ = ρ_1 + ρ_2 − L \quad (> 0: overlap,\ < 0: gap). \f]
/// For the pair's drive flanks (ε = −s) this line is the mesh frame's line of action: m = u,
/// n = v (mesh_frame.hpp). For helical gears δ is the transverse penetration of one face slice;
/// the normal one is δ cos β_b.
///
/// **Derivatives** (closed form, with respect to (c1x, c1y, β1, c2x, c2y, β2); a rigid rotation φ
/// of a gear or a tooth enters as β = φ + const):
/// \f[ ∂δ/∂c_1 = n,\ ∂δ/∂c_2 = −n,\ ∂δ/∂β_1 = −ε r_1,\ ∂δ/∂β_2 = −ε r_2, \f]
/// \f[ ∂ρ_k/∂c_2 = −∂ρ_k/∂c_1 = ε r_k (ê^⊥/C + ω R ê/(C L)),\ ∂ρ_k/∂β_k = −ε r_k. \f]
/// The force of a compressive contact acts along +n on body 2 and −n on body 1.
///
/// **Velocity.** With pose rates (ċ_k, φ̇_k), the material velocities at the contact are
/// v_k = ċ_k + φ̇_k J(P − c_k); the approach rate is δ̇ = (v1 − v2)·n and the sliding velocity
/// (v1 − v2)·(J n), positive when body 1 slides along J n relative to body 2.
#pragma once

#include <Eigen/Core>

#include "geardyn/common/eigen_types.hpp"
#include "geardyn/models/contact/tooth_flank.hpp"

namespace geardyn {

/// Row vector (1×6) of derivatives with respect to (c1x, c1y, β1, c2x, c2y, β2).
using PoseGradient = Eigen::Matrix<double, 1, 6>;

/// @brief Result of one flank–flank (or tip-corner–flank) contact evaluation.
struct FlankContact {
  /// False when the flanks cannot touch on a common tangent (unwinding senses differ, or the
  /// base circles overlap, C ≤ r1 + r2); all other fields are then unset.
  bool found = false;
  /// True when both roll distances lie within [ρ_F, ρ_a] of their flanks (the contact point is
  /// on the usable involute of both teeth) and |δ| ≤ min(max_depth) (the flanks face each
  /// other, not a tooth k pitches away).
  bool valid = false;
  /// 0: flank–flank contact; 1 or 2: the tip corner of body 1 or 2 against the other's flank
  /// (tip_corner_contact.hpp); the radius of curvature at the corner is its corner radius ρ_a.
  int corner = 0;
  double penetration = 0.0;           ///< δ [m] along n (> 0 overlap)
  Vector2 point = Vector2::Zero();    ///< contact point, midway between the flank points [m]
  Vector2 point1 = Vector2::Zero();   ///< P1(ρ1) on flank 1 [m]
  Vector2 point2 = Vector2::Zero();   ///< P2(ρ2) on flank 2 [m]
  Vector2 normal = Vector2::UnitX();  ///< n, outward normal of flank 1 = force direction on 2 [-]
  double roll1 = 0.0;                 ///< ρ1 [m] (= radius of curvature of flank 1 at P1)
  double roll2 = 0.0;                 ///< ρ2 [m]
  double tangent_length = 0.0;        ///< L = |T1T2| [m]
  PoseGradient d_penetration = PoseGradient::Zero();  ///< ∂δ/∂pose [-, m]
  PoseGradient d_roll1 = PoseGradient::Zero();        ///< ∂ρ1/∂pose [-, m]
  PoseGradient d_roll2 = PoseGradient::Zero();        ///< ∂ρ2/∂pose [-, m]
  /// ∂(point)/∂pose (2×6) [-, m]: from P1 = c1 + r1 m + ρ1 n, P2 = c2 − r2 m − ρ2 n with
  /// ∂m = J m ∂t1, ∂n = ε m ∂t1.
  Eigen::Matrix<double, 2, 6> d_point = Eigen::Matrix<double, 2, 6>::Zero();
};

/// @brief Kinematic rates at a contact.
struct ContactRates {
  double approach = 0.0;  ///< δ̇ [m/s]
  double sliding = 0.0;   ///< (v1 − v2)·J n [m/s]
};

/// @brief The contact of two involute flanks (the @file). Never allocates, never iterates.
/// @param[in] flank1 pose of the flank of body 1 (the pinion's, by convention).
/// @param[in] flank2 pose of the flank of body 2.
FlankContact CalcInvoluteContact(const InvoluteFlankPose& flank1, const InvoluteFlankPose& flank2);

/// @brief Approach and sliding rates at a contact from the pose rates of the two bodies.
/// @param[in] contact a found contact.
/// @param[in] center1, center2 body centres c_k [m] (of the effective base circles).
/// @param[in] rate1, rate2 (ċx, ċy, φ̇) of each body [m/s, rad/s].
ContactRates CalcContactRates(const FlankContact& contact, const Vector2& center1,
                              const Vector3& rate1, const Vector2& center2, const Vector3& rate2);

}  // namespace geardyn
