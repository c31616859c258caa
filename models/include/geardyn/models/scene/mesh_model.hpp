/// @file
/// @brief The mesh model a scene asks for, per [[mesh]] (spec 01 §4, §5): the level of the model
/// hierarchy, where K, h, μ, ε come from (contact lines with ISO 6336-1 or a given stiffness per
/// unit length, tooth modifications and errors, or user tables / Fourier series), damping and
/// coefficient options — and BuildMeshCore, the one builder from a scene mesh to its MeshCore.
///
/// **Same data, every level.** BuildMeshCore makes one MeshCoreSource (MakeMeshCoreSource) per
/// mesh and builds the requested level from it, so switching `model` in the scene file (or with
/// `--set mesh.NAME.model=...`) changes only the shape of the core (spec 01 §5: "selectable per
/// mesh in the scene, all built from the same data") — and, for "bs_projected", the mesh
/// Jacobian the system assembles it with (B–S's projected-arm G_BS, CalcModelLevelJacobian),
/// and for "five_dof" the transmission error (ε_η only, B–S Eq. 42).
///
/// **Drive sign** s = ±1 (spec 01 §2: the sign of the pinion's driving torque about +Z) from the
/// operating point (reference gear r, torque T_r, speed ratio ρ_p = Ω_pinion/Ω_r):
/// the mean torque the pinion transmits into the mesh is T_p = ±T_r/ρ_p, with + when r is on the
/// pinion's side of the mesh (r = pinion, or r reaches the pinion without crossing this mesh:
/// the power T_r Ω_r flows from the pinion into the gear) and − when r is on the gear's side.
/// s = sign(T_p), i.e. s = ±sign(T_r)·sign(ρ_p). When it cannot be decided (T_r = 0, the mesh
/// in a closed loop that joins both sides, or not connected to r) s = +1 and a warning says why.
/// The scene's tooth modifications and errors describe the flanks loaded for that s.
///
/// Scene keys: docs/scene-format.md, section "Mesh model".
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "geardyn/models/contact/contact_mesh_def.hpp"
#include "geardyn/models/mesh/contact_lines.hpp"
#include "geardyn/models/mesh/mesh_cores.hpp"
#include "geardyn/models/mesh/tooth_modifications.hpp"
#include "geardyn/system/coefficient.hpp"
#include "geardyn/system/mesh_core.hpp"

namespace geardyn {

struct Scene;      // scene.hpp (which includes this header: MeshDef holds a MeshModelDef)
struct MeshFrame;  // mesh_frame.hpp
struct MeshDef;    // scene.hpp

/// @brief Mesh parameters given by the user (spec 01 §4.3: tables or Fourier series from a
/// loaded tooth contact analysis or a measurement), replacing the contact-line model.
struct UserMeshParameters {
  /// (3 channels) K [N/m], K·h [N], K·μ·b² [N·m] over one mesh cycle (period_meshes = 1); b is
  /// the half common face width. K2 = [[c0, −c1], [−c1, c2]] is PSD at every stored value.
  Coefficient stiffness = ConstantCoefficient(VectorX::Zero(3));
  /// (2 channels) ε_η [m], ε_ζ [rad] over one mesh cycle; none = no static transmission error.
  std::optional<Coefficient> transmission_error;
};

/// @brief How BuildMeshCore gives a runout to a linear core (docs/design.md "Long hunting
/// periods"). Sidebands apply only to linear levels without pitch deviations (the runout is then
/// two lines over the hunting period, MakeRunoutSidebands, and ε otherwise mesh-periodic); else the
/// table.
enum class RunoutForm {
  kTable,      ///< in the ε table over the hunting period (refused above the sample limit)
  kAuto,       ///< as sidebands when that table would exceed kMaxTransmissionErrorSamples
  kSidebands,  ///< as sidebands whenever they apply
};

/// @brief The mesh model of one scene mesh: level, data sources and options (all SI).
struct MeshModelDef {
  /// Level of the model hierarchy (spec 01 §5). It overrides core_options.level.
  MeshModelLevel level = MeshModelLevel::kBlankenshipSingh;
  /// k [N/m²], constant stiffness per unit contact length; nullopt → ISO 6336-1 c_γα converted
  /// so that the mean mesh stiffness is c_γα·B (IsoStiffnessSource, line load from MeshLineLoad).
  std::optional<double> stiffness_per_length;
  /// Coefficient form, Fourier terms / tolerance, table samples, number of slices (the level is
  /// taken from `level`).
  MeshCoreOptions core_options;
  /// Whether the scene gave fourier_terms / fourier_tolerance / table_samples (BuildMeshCore
  /// warns when a given key has no effect on the built core).
  bool fourier_keys_given = false;
  bool table_samples_given = false;
  /// Flank modifications of the loaded flanks (tooth_modifications.hpp) [m].
  ToothModifications modifications;
  /// Tooth-to-tooth errors; pinion_teeth/gear_teeth are filled by the scene reader (BuildMeshCore
  /// fills them from the gears when 0).
  ToothErrors errors;
  /// B–S Eq. (39) mesh damping (none, c_m [N·s/m] or ζ_m [-]).
  MeshDamping damping;
  /// User K, h, μ (and ε): replaces the contact-line model when set; not with kNonlinearSlices
  /// (the slices need the contact lines), nor with modifications/errors/stiffness_per_length.
  std::optional<UserMeshParameters> parameters;
  /// The [mesh.contact] table (tooth contact, spec 03), if given. It is read and checked with any
  /// level (so that `--set mesh.NAME.model=...` switches levels without editing the file) and used
  /// by kContact only, which takes the defaults of ContactMeshDef without it.
  std::optional<ContactMeshDef> contact;
};

/// @brief The core of one scene mesh with what it was built from.
struct BuiltMeshCore {
  MeshCore core;  ///< the requested level (LinearMeshCore or SliceMeshCore)
  /// The contact-line model (zone of action + k) every level was built from; none for user
  /// parameters.
  std::optional<ContactLineModel> contact_lines;
  int drive_sign = 1;                 ///< s = ±1 (see the @file)
  std::vector<std::string> warnings;  ///< drive-sign fallbacks, ISO validity notes
};

/// @brief ISO 6336-1 line load F_t K_A / b [N/m] of `mesh` from the operating point.
///
/// ISO 6336-1's stiffness for F_t K_A / b < 100 N/mm is scaled with the line load; the load is
/// known when the operating point's body is one of the mesh's gears: K_A = 1 and F_t = |T|/r at
/// that gear's reference radius r, b = the common face width. A mesh of a planetary set carries
/// F_t = |T_s| / (N r_s), T_s the sun torque equivalent to the operating point's torque on a
/// central member (planetary.hpp). Otherwise (a gear further down a
/// train) nullopt, and ISO's stiffness is used unscaled (as for line loads ≥ 100 N/mm). Also
/// nullopt for a zero operating torque (the scaling would give a zero stiffness; an unloaded
/// mesh is modelled with the unscaled value).
/// @param[in] scene a validated scene; @param[in] mesh one of its meshes.
std::optional<double> MeshLineLoad(const Scene& scene, const MeshDef& mesh);

/// @brief The drive sign s = ±1 of `mesh` from the operating point (rule in the @file).
/// @param[in] scene a validated scene; @param[in] mesh one of its meshes.
/// @param[out] warnings if non-null, the reason is appended when s = +1 is a fallback.
int MeshDriveSign(const Scene& scene, const MeshDef& mesh,
                  std::vector<std::string>* warnings = nullptr);

/// @brief The MeshCore of `mesh.model.level` for a scene mesh.
///
/// * Contact lines (no user parameters): MakeMeshCoreSource(geometry, k, s) with k =
///   stiffness_per_length or ISO 6336-1 (line load MeshLineLoad), s = MeshDriveSign; the mesh
///   damping; with any modification or error, ε from TransmissionErrorModel: a table of
///   core_options.coefficient.num_samples samples per mesh cycle over the period P
///   (MakeTransmissionErrorTableCoefficient), or for form kFourier its Fourier series with
///   H·P terms, H = num_terms if > 0 else ⌈num_samples/2⌉ − 1
///   (MakeTransmissionErrorFourierCoefficient). P = lcm(z_1, z_2) with pitch errors or runout,
///   else 1. Then MakeMeshCore with core_options (level = mesh.model.level).
/// * User parameters: a LinearMeshCore of the level on those channels, b = face_width/2,
///   the damping; kMeanLti via MakeMeanLinearMeshCore, kFiveDof via
///   MakeScalarTransmissionErrorCore (te_zeta dropped).
/// @param[in] scene a validated scene (operating point, gears, meshes, bearings).
/// @param[in] mesh one of its meshes (its `model` says what to build).
/// @return the core, the contact-line model it came from, s and the warnings.
/// @throws InvalidInput (message starting "mesh.NAME") for an inconsistent MeshModelDef (user
///   parameters with slices, modifications, errors or stiffness_per_length), or as the builders.
/// @param[in] transmission_error false: no ε from the contact lines (modifications and tooth
///   errors ignored: for analyses of the mean operator only; SceneSystemOptions).
/// @param[in] runout how a runout reaches a linear core (RunoutForm).
/// @throws InvalidInput for model = "contact" (BuildContactMeshCore needs the placed frame; the
///   message names the mesh and the way out, `--set mesh.NAME.model=slices`).
BuiltMeshCore BuildMeshCore(const Scene& scene, const MeshDef& mesh, bool transmission_error = true,
                            RunoutForm runout = RunoutForm::kTable);

/// @brief The tooth-contact core (contact_mesh_core.hpp) of a mesh of model = "contact", placed
/// in `frame` (its centres, line of centres and drive sign: CalcMeshFrame), with the settings of
/// [mesh.contact] (ContactMeshDef defaults without the table) and [mesh.modifications]. The
/// gears' trunks must keep a positive inertia and mass (CheckTrunkInertia) when the scene gives
/// them.
/// @throws InvalidInput starting "mesh.NAME" (as ContactMeshCore or CheckTrunkInertia).
std::shared_ptr<const NonlinearMeshCore> BuildContactMeshCore(const Scene& scene,
                                                              const MeshDef& mesh,
                                                              const MeshFrame& frame);

}  // namespace geardyn
