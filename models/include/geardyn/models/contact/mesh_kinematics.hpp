/// @file
/// @brief Mesh kinematics of the contact simulator (spec 03): from the 12 small body coordinates
/// of a pair and the mesh phase θ to the planar pose of each gear in each face slice, and the
/// contact of a tooth pair in a slice with its derivatives with respect to the 12 coordinates.
///
/// **Coordinates.** q_pair = [q_i; q_j], q = [x, y, z, θx, θy, θz] of each body's centre
/// (mesh_jacobian.hpp), small deviations from the nominal rotation: the pinion turns by s θ/z1,
/// the gear by −s θ/z2 (external pair; s = the mesh frame's drive sign). Teeth are numbered as in
/// tooth_modifications.hpp: in mesh cycle n (θ ∈ 2πn + (−π, π]) the pinion tooth n mod z1 meets
/// the gear tooth n mod z2 at the pitch point p0 at θ = 2πn; tooth i+1 trails tooth i.
///
/// **Slices.** The common face B = 2b is cut into N equal slices at y_s = −b + (s + ½) B/N from
/// mid face (z_s = z(p0) + y_s). In slice s gear k's base-circle centre and rotation are
/// \f[ c_k(z_s) = c_k + (x + θ_y Δz,\; y − θ_x Δz),\quad Δz = z_s − z(c_k), \f]
/// \f[ φ_k = φ_k^{nom}(θ) + θ_z + f_k (y_s − w_k(P)),\quad f_k = h_k \tan β_b / r_{bk}, \f]
/// where h_k = ±1 is the member's hand (a right-hand transverse section turns counter-clockwise
/// with z) and w_k(P) = z + θ_x (P_y − c_y) − θ_y (P_x − c_x) the axial displacement of the body's
/// material at the contact point P: an axial shift of a helical gear acts like a rotation. P is
/// the contact point of the same pair evaluated without the axial term (one extra kernel call,
/// helical only; it differs from the final point by second order in the small coordinates). The
/// gradients are exact for the function so defined (P's own dependence on q and θ included).
/// The normal penetration is δ_n = δ_t cos β_b − e (e: FlankModifications).
///
/// **The B–S link.** For every contact, ∂δ_n/∂q_pair = [1, −σ] G with G = CalcMeshJacobian(frame)
/// and σ = (P3 − p0)·σ̂ (P3 = (P, z_s)) at q = 0, for spur and helical pairs (tested): the
/// contact model refines the same interface, contact by contact.
#pragma once

#include <Eigen/Core>
#include <optional>

#include "geardyn/common/eigen_types.hpp"
#include "geardyn/models/contact/contact_presearch.hpp"
#include "geardyn/models/contact/flank_relief.hpp"
#include "geardyn/models/contact/involute_contact.hpp"
#include "geardyn/models/contact/tooth_flank.hpp"
#include "geardyn/models/mesh/mesh_frame.hpp"

namespace geardyn {

/// @brief Planar pose of one gear in one face slice.
struct GearSlicePose {
  Vector2 center = Vector2::Zero();  ///< c_k(z_s) [m]
  double angle = 0.0;                ///< φ_k without the axial term −f_k w_k(P) [rad]
  double helix_factor = 0.0;         ///< f_k [rad/m]
  double axial = 0.0;                ///< body axial displacement z [m]
  Vector2 tilt = Vector2::Zero();    ///< (θx, θy) [rad]
  ToothLayout layout;                ///< tooth 0's world centre line (at the angle above)
  /// @brief φ_k at the contact point P [m] (the axial term included) [rad].
  double AngleAt(const Vector2& point) const;
};

/// @brief A tooth pair's contact in one slice.
struct SliceToothContact {
  FlankContact transverse;   ///< the kernel's result, transverse plane (δ_t, ρ1, ρ2, n)
  double penetration = 0.0;  ///< δ_n = δ_t cos β_b − e [m] (> 0 overlap)
  double separation = 0.0;   ///< e, normal separation of the modifications [m]
  Vector12 d_penetration = Vector12::Zero();  ///< ∂δ_n/∂q_pair [-, m]
  double d_penetration_d_phase = 0.0;         ///< ∂δ_n/∂θ [m/rad]
  double sigma = 0.0;                         ///< σ = (P3 − p0)·σ̂ [m]
  Vector3 point = Vector3::Zero();            ///< P3, contact point (transverse point at z_s) [m]
  double approach_rate = 0.0;                 ///< δ̇_n [m/s] (when rates are given)
  double sliding_rate = 0.0;                  ///< transverse sliding speed (v1 − v2)·J n [m/s]
};

/// @brief Slice poses and tooth-pair contacts of one external pair (see the @file).
class ContactMeshKinematics {
 public:
  /// @param[in] pair derived pair geometry (external).
  /// @param[in] frame mesh frame of the pair (CalcMeshFrame), its centres and drive sign.
  /// @param[in] pinion, gear flank geometries (MakeToothFlankGeometry).
  /// @param[in] num_slices N ≥ 1 face slices (≤ 1000).
  /// @param[in] modifications flank modifications (optional).
  /// @throws InvalidInput naming "num_slices", "pair.internal" or a flank geometry inconsistent
  ///   with the frame ("pinion.base_radius").
  ContactMeshKinematics(const GearPairGeometry& pair, const MeshFrame& frame,
                        const ToothFlankGeometry& pinion, const ToothFlankGeometry& gear,
                        int num_slices = 1,
                        std::optional<FlankModifications> modifications = std::nullopt);

  int num_slices() const { return num_slices_; }
  /// y_s from mid face [m].
  double slice_position(int slice) const;
  /// Width B/N of a slice [m].
  double slice_width() const { return face_width_ / num_slices_; }
  const ToothFlankGeometry& pinion() const { return pinion_; }
  const ToothFlankGeometry& gear() const { return gear_; }
  const MeshFrame& frame() const { return frame_; }
  /// Unwinding sense ε of a side: −s for the drive flanks, +s for the coast flanks.
  int Unwind(FlankSide side) const { return side == FlankSide::kDrive ? -s_ : s_; }

  /// @brief Planar poses of pinion (first) and gear (second) in a slice.
  /// @param[in] q_pair (12) [m, rad]; @param[in] theta mesh phase [rad]; @param[in] slice s.
  std::pair<GearSlicePose, GearSlicePose> SlicePoses(const Vector12& q_pair, double theta,
                                                     int slice) const;

  /// @brief Contact of pinion tooth i1 with gear tooth i2 on one side in one slice, with the
  /// derivatives of the @file. Where the flank–flank point lies beyond a flank's end (ρ > ρ_t),
  /// the tip corner of that tooth against the mate's flank is returned instead
  /// (tip_corner_contact.hpp; transverse.corner = 1 pinion tip, 2 gear tip). Rates are optional
  /// (zero when not given).
  SliceToothContact EvalToothPair(const Vector12& q_pair, double theta, int slice, int tooth1,
                                  int tooth2, FlankSide side, const Vector12* q_rate = nullptr,
                                  double theta_rate = 0.0) const;

 private:
  MeshFrame frame_;
  ToothFlankGeometry pinion_, gear_;
  std::optional<FlankModifications> modifications_;
  int num_slices_ = 1;
  int s_ = 1;
  double face_width_ = 0.0, cos_base_helix_ = 1.0;
  double tooth0_pinion_ = 0.0, tooth0_gear_ = 0.0;  // body centre-line angles of tooth 0 [rad]
};

}  // namespace geardyn
