/// @file
/// @brief ContactMeshCore: the tooth-contact mesh core of spec 03 (model = "contact") — the
/// NonlinearMeshCore that maps the 12 body coordinates, the tooth-body coordinates and the mesh
/// phase to tooth-pair contacts (pre-search, then the closed-form involute / tip-corner kernel of
/// mesh_kinematics.hpp per candidate pair, flank and face slice), applies the contact law
/// (contact_law.hpp), friction (friction.hpp) and the tooth joints (tooth_body.hpp), and returns
/// the generalized forces, their Jacobians, energy, dissipation and phase power.
///
/// **Coordinates** x = [q_i (6); q_j (6); pinion teeth; gear teeth]: tooth k of a member owns
/// ToothDofs(type) consecutive coordinates (revolute: φ; bushing: u_r, u_t, φ; rotation
/// counter-clockwise about +Z, translations along the tooth's undeflected radial and
/// counter-clockwise tangential axes, tooth_pose.hpp), relative to the trunk.
///
/// **Face slices.** The law's k and c (kim, linear) are those of a contact over the whole face
/// width; each of the N face slices carries k/N and c/N (the line law takes the slice length L
/// in its own formula), so the slice count refines the load distribution, not the stiffness.
///
/// **Per contact** (normal penetration δ(x, θ) with gradient g = ∂δ/∂x, g_θ = ∂δ/∂θ; rate
/// δ̇ = g·v + g_θ θ̇; law f(δ, δ̇) ≥ 0): generalized force −f g; stiffness ∂f/∂δ g gᵀ; damping
/// ∂f/∂δ̇ g gᵀ; energy E(δ); dissipation D of the law; phase power P = f g_θ θ̇. With friction
/// (spur pairs): sliding speed v_s = w·v + w_θ θ̇ (w = ∂v_s/∂v, exact: v_s is linear in the
/// rates), force f_t w with f_t = −μ f tanh(v_s/ε), its Jacobians through f and v_s, D += −f_t v_s,
/// P += −f_t w_θ θ̇. So the power identity of mesh_core.hpp holds exactly at every state.
/// Tooth joints: ½ k q² springs and c q̇ dampers on each tooth coordinate.
///
/// **Omitted from the Jacobians** (not from the forces): the geometric terms f ∂²δ/∂x² and the
/// dependence of g and w on x in the rate terms. Their size relative to the contact stiffness is
/// f/(k_c L) (L the common-tangent length, tens of mm): ≈ 1e-5 on the rig at 100 N·m, so a Newton
/// iteration with these Jacobians still converges quadratically to within that factor.
///
/// **Switching functions** (NonlinearMeshCoreOutput::switching): for each face slice s, side
/// (drive 0, coast 1) and pinion tooth k, index (s·2 + side)·z1 + k: −δ of the valid contact of
/// that tooth (the largest δ among its candidate mates), or +π r_b1/z1 (half a base pitch) when
/// it has none. g ≤ 0 is contact.
///
/// **Channels** (names with units): per pinion tooth then per gear tooth the normal force summed
/// over slices and flanks [N]; per pinion tooth the status (+1 drive, −1 coast, 0 open, the
/// larger force wins); per tooth of each member its coordinates (rotation [rad], radial and
/// tangential [m]).
///
/// **Biarc profile** (def.profile = "biarc", spur pairs, every tooth type): each flank is replaced
/// by Kim's N biarcs (biarc_profile.hpp) placed at the exact flank's (deflected) pose. The exact
/// kernel's rolls (involute, or tip corner beyond ρ_t) locate the arcs in O(1); the biarc contact
/// of those arcs and their neighbours (CalcBiarcContactNear) then gives δ, n, the point and the
/// rolls with closed-form pose gradients, through the same chain rule. The line law keeps the
/// involute rolls of the touching points as radii of curvature (the arcs' radii are an artefact of
/// the fit, within O(h) of them).
///
/// **Scope of this build.** Flexible teeth, friction and the biarc profile need a spur pair (the
/// helical chain of mesh_kinematics.hpp is used for rigid, frictionless, exact teeth only);
/// external pairs only.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "geardyn/models/contact/biarc_profile.hpp"
#include "geardyn/models/contact/contact_mesh_def.hpp"
#include "geardyn/models/contact/flank_relief.hpp"
#include "geardyn/models/contact/mesh_kinematics.hpp"
#include "geardyn/models/contact/tooth_body.hpp"
#include "geardyn/system/mesh_core.hpp"

namespace geardyn {

/// @brief The tooth-contact mesh core (see the @file).
class ContactMeshCore final : public NonlinearMeshCore {
 public:
  /// @param[in] pair the pair geometry (external).
  /// @param[in] frame the mesh frame of the placed pair (CalcMeshFrame).
  /// @param[in] def the [mesh.contact] settings.
  /// @param[in] modifications the drive flanks' modifications (none: unmodified).
  /// @throws InvalidInput naming `def.teeth` or `def.friction_coefficient` on a helical pair,
  ///   `def.profile` ("biarc" on a helical pair), `def.arcs` (outside [1, 1000]), `def.law`
  ///   (invalid), or as the geometry.
  ContactMeshCore(const GearPairGeometry& pair, const MeshFrame& frame, const ContactMeshDef& def,
                  const ToothModifications& modifications = {});

  int num_coordinates() const override { return 12 + num_internal_; }
  int num_internal_coordinates() const override { return num_internal_; }
  std::int64_t period_meshes() const override { return period_; }
  /// 1: the teeth of a member are identical (tooth errors are refused with model = "contact"),
  /// so one mesh cycle later tooth k + 1 of each member plays the role tooth k had
  /// (mesh_kinematics.hpp numbering: in mesh cycle n pinion tooth n mod z1 meets gear tooth
  /// n mod z2). Rigid teeth: P = 1 and nothing to shift.
  std::int64_t symmetry_period_meshes() const override { return 1; }
  /// S of one mesh cycle: per member, the coordinates of tooth k move to tooth k + 1 (mod z),
  /// i.e. (S y)_{k+1} = y_k — the steady response has x_{k+1}(θ + 2π) = x_k(θ).
  void ApplySymmetryShift(Eigen::Ref<VectorX> internal) const override;
  std::unique_ptr<NonlinearMeshCoreWorkspace> MakeWorkspace() const override;
  MatrixX InternalMass() const override;
  int num_switching_functions() const override;
  std::vector<std::string> channel_names() const override;

  /// The kinematics (slice poses, tooth-pair contacts of rigid teeth).
  const ContactMeshKinematics& kinematics() const { return kinematics_; }
  /// The tooth sets of the pinion (first) and the gear.
  const ToothSet& pinion_teeth() const { return teeth_[0]; }
  const ToothSet& gear_teeth() const { return teeth_[1]; }
  const ContactMeshDef& def() const { return def_; }

 protected:
  void DoCalcForces(NonlinearMeshCoreWorkspace& ws, double theta, double theta_rate,
                    const Eigen::Ref<const VectorX>& x, const Eigen::Ref<const VectorX>& v,
                    bool with_jacobians, NonlinearMeshCoreOutput* out) const override;

 private:
  struct Contact;
  // The contact of pinion tooth i1 and gear tooth i2 on one side in one slice (poses of that
  // slice given): false when there is none; its gap δ; when δ > 0 its gradients on the local
  // coordinates (see the .cpp).
  bool EvalContact(const Eigen::Ref<const VectorX>& x, const Eigen::Ref<const VectorX>& v,
                   double theta, double theta_rate, int slice,
                   const std::pair<GearSlicePose, GearSlicePose>& slice_poses, int i1, int i2,
                   FlankSide side, Contact* c) const;
  int ToothOffset(int member, int tooth) const;

  GearPairGeometry pair_;
  ContactMeshDef def_;
  ContactLaw slice_law_;  // the law of one face slice (k/N, c/N; the line law as given)
  ContactMeshKinematics kinematics_;
  std::optional<FlankModifications> modifications_;
  ToothSet teeth_[2];
  BushingJoint joints_[2];
  int dofs_[2] = {0, 0};
  int num_internal_ = 0;
  std::int64_t period_ = 1;
  bool spur_ = true;
  /// Biarc flanks (profile = "biarc"): [member][ε = −1, +1]; empty for the exact involute.
  std::vector<BiarcFlank> biarcs_;
};

}  // namespace geardyn
