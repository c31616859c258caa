/// @file
/// @brief MakeSystemModel: the one builder from a Scene to the SystemModel the analyses read
/// (issue 4; spec 01 §1–§3; architecture §3.2).
///
/// **Bodies.** One rigid 6-DOF body per gear, named like the gear, mass matrix
/// CalcRigidBodyMassMatrix with m = mass, J = inertia (polar) and I_d = transverse_inertia or, when
/// absent, J/2 (the thin-disc value; a disc of width b has J/2 + m b²/12, which the scene can give
/// explicitly). Axis +Z, centre of mass on the centre.
///
/// **Placement.** Gears are placed by a breadth-first walk over the meshes from the operating
/// point's body (default: the first mesh's pinion), which sits at `options.origin`. The k-th mesh
/// reached (k = 0, 1, …, in the walk order, which follows the scene's mesh order at each gear)
/// puts its unplaced member at the centre distance a_w from the placed one along the line of
/// centres γ_k = γ0 + (k mod 2)·π/2 (pinion → gear direction; γ0 = options.line_of_centres_angle),
/// i.e. a train alternates 0°/90° steps (a staircase that cannot fold back onto itself), unless
/// options.mesh_angles names the mesh. A mesh whose two members are both already placed (a closed
/// loop) takes γ from their centres and must match a_w (InvalidInput otherwise). A gear reached
/// only through a bearing between two gears (two gears on one shaft) is placed at the centre of
/// the other (coaxial; the axial offset is not modelled); a gear connected to nothing is placed at
/// the origin.
///
/// **Planetary sets** (Scene::planetaries, planetary.hpp): when the walk reaches any member of a
/// set, the whole set is placed: sun, ring and carrier on one centre c0, planet n at
/// c0 + a_w (cos ψ_n, sin ψ_n, 0); the sun–planet meshes then have γ = ψ_n and the planet–ring
/// meshes γ = ψ_n + π (closed loops; options.mesh_angles cannot name them). The bodies get their
/// BodyRole (sun, ring, carrier, planet) for the planetary mode labels; the planet bearings are
/// ordinary two-body bearings at the planet's centre, so their carrier-side point moves with the
/// carrier's translation and rotation (CalcBearingMatrix). Phase offsets of the planetary meshes:
/// CalcPlanetaryMeshPhases with the sun drive sign PlanetarySunDriveSign.
///
/// **Supports.** A [[bearing]] is the given 6×6 (K, C) acting at the body's centre: to ground
/// directly, or between two bodies through CalcBearingMatrix at the body's centre (relative
/// motion body − other).
///
/// **Meshes.** Frame from the pair geometry, the pinion's centre, γ and the drive sign s of
/// BuildMeshCore (CalcMeshFrame); G = CalcModelLevelJacobian of the mesh's level: the exact
/// CalcMeshJacobian, its θz columns for the torsional level, B–S's projected-arm P T for
/// bs_projected (b = the core's half face width); the core from BuildMeshCore; the equivalent
/// mass for a damping ratio computed by SystemBuilder from the bodies' masses; phase ratio =
/// mesh frequency / first mesh's mesh frequency (Scene::MeshFrequencyHz; 1 when unknown), phase
/// offset 0 except in planetary sets (above).
///
/// **Shafts** (Scene::shafts): one body per shaft node (ShaftDef::nodes), the node at a gear's
/// station being that gear's body (gears first in the body order, then the other nodes, massless,
/// named "<shaft>.n<k>"), and one Timoshenko element "<shaft>.e<k>" (CalcShaftBeamStiffness,
/// CalcShaftBeamMass; ElementKind::kShaft) per pair of consecutive nodes. A shaft is placed
/// coaxially with its first gear reached by the walk (z of a gear = z of the shaft + station);
/// bearings on a shaft act at the node at their station; a bearing between two bodies places the
/// other one coaxially so that the two stations meet. Meshing gears must share one z.
///
/// **System damping** (Scene::damping): AddSystemDamping (system_damping.hpp) on the built model,
/// after the planar restriction, so that modal ratios refer to that model's own modes.
///
/// **Loads.** External moments about +Z (θz): the operating-point torque on its body plus every
/// [[load]] torque on its body; they all add (the scene gives them as applied torques, e.g. an
/// input torque on the pinion and the balancing output torque on the wheel).
///
/// **Mesh preload** (SceneSystemOptions::mesh_preload, issue 19): the model above is solved for
/// its static state under these loads, and every mesh's tangent stiffness K_g(F̄_η)
/// (mesh_preload_stiffness.hpp) is added as an element "<mesh>.preload" between its two bodies,
/// together with the change of the mean mesh stiffness at the deflected geometry: with
/// ∇δ_η(q̄) = G_η + (∇²δ_η q̄)ᵀ the element holds G'ᵀK̄2G' − GᵀK̄2G + F̄_η ∇²δ_η, the consistent
/// first-order tangent of the mean mesh energy (the meshes keep their reference G: the loaded
/// model is for the modes about that state). When the unloaded model has rigid-body modes N
/// that this change touches (the free rotation of a planetary train, whose planets revolve), the
/// change is projected off them, Pᵀ ΔK P with the M-orthogonal P = I − N (NᵀMN)⁻¹NᵀM, the
/// difference added to K0 unowned (SystemModel::WithAddedStiffness): the rotation stays an exact
/// zero mode, the flexible modes keep their first-order shifts. SceneSystem::mesh_preloads
/// reports F̄_η and κ per mesh.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "geardyn/common/eigen_types.hpp"
#include "geardyn/models/scene/scene.hpp"
#include "geardyn/system/system_model.hpp"

namespace geardyn {

/// @brief Options of MakeSystemModel.
struct SceneSystemOptions {
  /// γ0 [rad]: line-of-centres angle of the first mesh (see the @file placement rule).
  double line_of_centres_angle = 0.0;
  /// Per-mesh γ [rad] overriding the rule, by mesh name.
  std::map<std::string, double> mesh_angles;
  /// Centre of the operating point's body [m].
  Vector3 origin = Vector3::Zero();
  /// Keep only x, y and θz of every body (planar literature models): the others held fixed.
  /// Scene::planar (the scene's top-level `planar = true`) does the same.
  bool planar = false;
  /// Build the transmission error ε of the contact-line meshes (modifications, tooth errors).
  /// False for analyses of the homogeneous operator only (modes, floquet, stability-chart): ε
  /// never enters K or C, and with tooth errors it is a table over the whole hunting period
  /// (lcm(z_1, z_2) mesh cycles), the costliest part of the build. Meshes then load nothing through
  /// K2 ε, and SystemModel::period_meshes() is the operator's.
  bool transmission_error = true;
  /// How a runout reaches the linear cores (RunoutForm, mesh_model.hpp): kTable everywhere but
  /// the linear hb, which takes kAuto (sidebands when the hunting period is too long to tabulate,
  /// solved with sparse harmonics). Analyses that sample ε over the hunting period must keep
  /// kTable.
  RunoutForm runout_form = RunoutForm::kTable;
  /// What the model is built for, named by the error when a body lacks `mass` or `inertia`
  /// (optional in a scene): "<file>:<line>: gear.pinion.mass: required by modes (mass matrix)".
  std::string analysis = "the system model";
  /// Build meshes of model = "contact" (a NonlinearMeshCore with tooth coordinates): true only
  /// for time-domain analyses. False: such a mesh is refused with InvalidInput naming the mesh,
  /// `analysis` and the way out (`--set mesh.NAME.model=slices`): the linear and harmonic-balance
  /// analyses, modes and Floquet need a linear or slice core, and a linearisation of the contact
  /// model is not offered (its tangent at one state is not the operator those analyses assume).
  bool allow_contact_meshes = false;
  /// Add the tangent (geometric) stiffness of every preloaded mesh (mesh_preload_stiffness.hpp,
  /// issue 19): the static operating point is solved on the model first (SolveStaticDeflection),
  /// then each mesh's K_g(F̄_η) joins the model as an element "<mesh>.preload"
  /// (ElementKind::kMeshPreload), so that K̄ is the tangent stiffness about the loaded state. For
  /// the analyses of the small motion about that state (modes, campbell); a contact mesh is
  /// refused (it has no static mean force in this sense).
  bool mesh_preload = false;
  /// False (with the field and value in `why`) on a non-finite angle or origin.
  bool IsValid(std::string* why) const;
};

/// @brief One mesh's preload (SceneSystemOptions::mesh_preload).
struct MeshPreload {
  std::string mesh;          ///< the mesh's name (its element is "<mesh>.preload")
  double force = 0.0;        ///< F̄_η [N], the static normal mesh force (> 0 compression)
  double coefficient = 0.0;  ///< κ = −F̄_η cos ψ_b / L_s [N/m] (mesh_preload_stiffness.hpp)
  double line_length = 0.0;  ///< L_s [m], signed (< 0 internal; 0 for a rack: κ = 0)
};

/// @brief The model with what the scene builder decided.
struct SceneSystem {
  SystemModel model;
  std::vector<Vector3> centres;       ///< per gear (scene order = body order) [m]
  std::vector<double> mesh_angles;    ///< γ per scene mesh [rad]
  std::vector<int> drive_signs;       ///< s per scene mesh
  std::vector<std::string> warnings;  ///< from BuildMeshCore (drive-sign fallbacks, ISO notes)
  std::vector<MeshPreload>
      mesh_preloads;  ///< per scene mesh, with SceneSystemOptions::mesh_preload
  /// With the mesh preload: the number of rigid-body modes of the unloaded model the preload was
  /// projected off (0 when it did not touch them; see the @file).
  int mesh_preload_rigid_modes = 0;
};

/// @brief Builds the SystemModel of a scene and reports the placement (see the @file). An
/// oscillator scene (Scene::oscillator) gives MakeOscillatorSystemModel's one-DOF model
/// (oscillator_system.hpp) with empty placement vectors; `options` are then not used beyond
/// their validation (no planar restriction, no gears).
/// @throws InvalidInput on invalid options, an inconsistent closed loop, or as SystemBuilder and
///   BuildMeshCore; SceneError at the body's table when a body has no mass or inertia.
SceneSystem BuildSceneSystem(const Scene& scene, const SceneSystemOptions& options = {});

/// @brief BuildSceneSystem(scene, options).model.
SystemModel MakeSystemModel(const Scene& scene, const SceneSystemOptions& options = {});

}  // namespace geardyn
