/// @file
/// @brief Builders of the mesh cores (geardyn/system/mesh_core.hpp) per level of the model
/// hierarchy (spec 01 §5), all from the SAME data: a contact-line model (zone of action +
/// stiffness per unit contact length k), optional transmission-error channels, damping and
/// backlash (MeshCoreSource).
///
/// **Stiffness per unit contact length** (spec 01 §4.2), MeshStiffnessSource:
/// * IsoStiffnessSource — ISO 6336-1 c_γα (CalcIsoMeshStiffness). c_γα is a MESH stiffness per
///   unit face width, i.e. the mean of K/B over the mesh cycle, while the contact-line model
///   needs a stiffness per unit contact LENGTH. The conversion keeps the mean:
///   k = c_γα·B / L̄ with L̄ the mean total contact-line length of the zone (exact mean over a
///   mesh period of the model's own L(θ), = ε_α B / cos β_b for the rectangular zone), so that
///   K̄ = k L̄ = c_γα·B exactly; K(θ) keeps the 1↔2-pair (spur) or trapezoidal (helical) shape.
/// * StiffnessPerUnitLength — a given constant k [N/m²].
/// * StiffnessProfile — k(r) along the path of contact (contact_lines.hpp).
///
/// **Levels → forms.** Every linear level's core comes from the same channels; G is the mesh
/// Jacobian the level is assembled with (CalcModelLevelJacobian).
/// * kBlankenshipSingh — LinearMeshCore(kBlankenshipSingh), (K, K·h, K·μ·b²)(θ)
///   (MakeMeshCoefficient) and (ε_η, ε_ζ)(θ); the exact G (CalcMeshJacobian).
/// * kBsProjected — the kBlankenshipSingh core on B–S's G_BS = P T (CalcBsProjectedJacobian).
/// * kFiveDof — the kBlankenshipSingh core with ε_ζ ≡ 0 (MakeScalarTransmissionErrorCore); the
///   exact G.
/// * kCoupling4Dof — LinearMeshCore(kCoupling4Dof), the same channels; the exact G.
/// * kMeanLti — MakeMeanLinearMeshCore of the kBlankenshipSingh core (exact channel means); the
///   exact G.
/// * kTorsional — LinearMeshCore(kTorsional), the same channels; CalcLevelJacobian's θz columns.
/// * kNonlinearSlices — SliceMeshCore from the contact lines cut into σ-bands; the exact G.
///
/// kBsProjected equals kBlankenshipSingh exactly for spur gears with p0 in the centres' plane
/// (G_BS = G, mesh_jacobian.hpp). kFiveDof equals it exactly whenever ε_ζ ≡ 0: no modification
/// or error, or a separation uniform across the face (a spur pair's profile relief, pitch
/// deviations, a runout); a helical pair's tip relief or lead crowning, or a lead slope, gives
/// ε_ζ ≠ 0.
///
/// **Slices** (spec 01 §4.4). The σ range of the zone of action, [σ_min, σ_max] =
/// ContactLineModel::SigmaRange() (width g_α|sin β_b| + B cos β_b), is cut into N equal bands;
/// slice s sits at the band centre σ_s and k_s(θ) = ∫_{lines ∩ band} k dℓ (exact clipped-line
/// integrals, ContactLineModel::CalcIntegrals(θ, σ_a, σ_b)). So Σ_s k_s = K exactly and the
/// moments Σ k_s σ_s, Σ k_s σ_s² are midpoint rules of ∫kσ dℓ, ∫kσ² dℓ: K·h and K·μ·b² are
/// reproduced with an O(N⁻²) error (for spur gears, μ exactly (1 − 1/N²)·μ_exact with h exact).
/// Why bands in σ and not strips of the face: the approach of a contact point depends on its σ
/// only (spec 01 §3), and for helical gears the lines crossing one face strip lie at σ values
/// p_bt sin β_b apart (σ = s(y/cos β_b − x_j sin β_b)), so a face strip has no single σ_s and
/// would not converge to h and μ. For spur gears a band IS a face strip (σ = s·y), and σ is
/// measured from p0 at mid face for both. With transmission-error channels (ε_η, ε_ζ) the slice
/// separations are e_s = ε_η − σ_s ε_ζ (the rigid separation field that has exactly the
/// linear core's ε), an exact linear map of the coefficient.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "geardyn/models/gear/gear_geometry.hpp"
#include "geardyn/models/gear/iso_stiffness.hpp"
#include "geardyn/models/mesh/contact_lines.hpp"
#include "geardyn/models/mesh/mesh_frame.hpp"
#include "geardyn/system/coefficient.hpp"
#include "geardyn/system/mesh_core.hpp"

namespace geardyn {

/// @brief k from ISO 6336-1 c_γα, converted so that the mean mesh stiffness is c_γα·B.
struct IsoStiffnessSource {
  IsoStiffnessOptions options;  ///< C_M, line load (iso_stiffness.hpp)
};

/// @brief A given constant stiffness per unit contact length.
struct StiffnessPerUnitLength {
  double k = 0.0;  ///< k ≥ 0 [N/m²]
};

/// @brief Where k comes from (spec 01 §4.2).
using MeshStiffnessSource =
    std::variant<IsoStiffnessSource, StiffnessPerUnitLength, StiffnessProfile>;

/// @brief The data every level is built from.
struct MeshCoreSource {
  ContactLineModel contact_lines;  ///< zone of action + k(r)
  /// (ε_η [m], ε_ζ [rad]), e.g. from transmission_error.hpp; none = no static TE.
  std::optional<Coefficient> transmission_error;
  MeshDamping damping;                ///< B–S Eq. (39) damping of every level
  double backlash = kNoBackFlank;     ///< j [m], normal clearance (slices only)
  std::vector<std::string> warnings;  ///< from the stiffness source (ISO validity notes)
  /// Lines added to ε (MakeRunoutSidebands: a runout over a hunting period too long to tabulate);
  /// linear levels only.
  TransmissionErrorSidebands transmission_error_sidebands;
};

/// @brief Resolves a stiffness source on a zone of action to a profile k(r).
///
/// ISO: k = c_γα·B/L̄ with L̄ the exact mean contact-line length of `zone` (see the @file).
/// @param[in] geometry the pair (ISO needs tooth counts, shifts, …).
/// @param[in] zone the zone of action (MakeZoneOfAction).
/// @param[out] warnings if non-null, ISO validity notes are appended.
/// @throws InvalidInput naming `stiffness.k` (negative or non-finite) or as CalcIsoMeshStiffness.
StiffnessProfile ResolveStiffnessProfile(const MeshStiffnessSource& source,
                                         const GearPairGeometry& geometry, const ZoneOfAction& zone,
                                         std::vector<std::string>* warnings = nullptr);

/// @brief The common data of all levels from the pair geometry: zone of action
/// (MakeZoneOfAction), k (ResolveStiffnessProfile), backlash = geometry.backlash_normal j_bn
/// (0 at the zero-backlash centre distance: a tight mesh, both flanks in contact).
/// @param[in] drive_sign s = ±1, the sign of the pinion's driving torque about +Z.
MeshCoreSource MakeMeshCoreSource(const GearPairGeometry& geometry,
                                  const MeshStiffnessSource& stiffness, int drive_sign = 1);

/// @brief The levels of spec 01 §5 a user can ask for (the linear ones and the slice form).
enum class MeshModelLevel {
  kNonlinearSlices,   ///< SliceMeshCore
  kBlankenshipSingh,  ///< LTV 6-DOF (B–S Eq. 41) on the exact mesh Jacobian G
  /// B–S's own projected-arm form of the LTV 6-DOF model: the kBlankenshipSingh core on
  /// G_BS = P T (B–S Eqs. 22, 24, 25, 41; CalcBsProjectedJacobian): moment arms measured by their
  /// projection on u, which drops G's θ_u terms of a helical pair (mesh_jacobian.hpp).
  kBsProjected,
  /// B–S §5.3's five-DOF form (Eqs. 41, 42): the kBlankenshipSingh core (κ(θ), μ(θ) kept, W
  /// constant, no friction) on the exact G with the scalar transmission error: ε_ζ ≡ 0
  /// (MakeScalarTransmissionErrorCore).
  kFiveDof,
  kCoupling4Dof,  ///< LTV 4-DOF coupling (κ = 0, μ dropped)
  kMeanLti,  ///< LTI: mean K̄2 of the B–S core, ε(θ) kept (for the LTI of another shape, apply
             ///< MakeMeanLinearMeshCore to that level's core)
  kTorsional,  ///< torsional SDOF
  /// Tooth contact with tooth bodies (spec 03; [mesh.contact], contact_mesh_def.hpp): a
  /// NonlinearMeshCore for time-domain analyses only; MakeMeshCore refuses it (BuildMeshCore).
  kContact,
};

/// Name of a level: "slices", "blankenship_singh", "bs_projected", "five_dof", "coupling_4dof",
/// "lti", "torsional", "contact".
const char* ToString(MeshModelLevel level);
/// The level named `name` (as ToString), or nullopt.
std::optional<MeshModelLevel> ParseMeshModelLevel(std::string_view name);

/// @brief The shape of the 2×2 core of a level (lib's MeshCoreLevel): kCoupling4Dof and
/// kTorsional their own, every other level (kBsProjected and kFiveDof included: the same K2)
/// kBlankenshipSingh.
MeshCoreLevel CalcMeshCoreLevel(MeshModelLevel level);

/// @brief The mesh Jacobian G (2×12) a level is assembled with, in `frame`:
/// * kBsProjected — B–S's projected G_BS = P T (CalcBsProjectedJacobian(frame, b));
/// * kTorsional — CalcLevelJacobian(MeshCoreLevel::kTorsional, CalcMeshJacobian(frame));
/// * every other level — the exact CalcMeshJacobian(frame).
/// @param[in] level model level.
/// @param[in] frame mesh frame from CalcMeshFrame [m, -].
/// @param[in] half_face_width b > 0 [m] of the level's core (read for kBsProjected only).
/// @return G (2×12) [-, m].
/// @throws InvalidInput naming half_face_width (kBsProjected, b not positive and finite).
Matrix2x12 CalcModelLevelJacobian(MeshModelLevel level, const MeshFrame& frame,
                                  double half_face_width);

/// @brief The core with B–S's scalar transmission error (B–S Eq. 42, the five-DOF form of §5.3):
/// the ε_ζ channel of the transmission-error coefficient and the ε_ζ row of the sidebands set to
/// zero, the ε_η channel, the stiffness, level, b, damping and mean-LTI flag kept. The load is
/// then Gᵀ K2 [ε_η, 0]ᵀ: the line-of-action error still loads the rocking DOF through −K h.
/// @param[in] core any linear core.
/// @return the same core with ε_ζ ≡ 0 (the core itself when it has no transmission error).
LinearMeshCore MakeScalarTransmissionErrorCore(const LinearMeshCore& core);

/// @brief Options of the slice coefficients k_s(θ) (and e_s(θ)).
struct SliceCoefficientOptions {
  /// kAuto: ConstantCoefficient when every k_s is constant, exact steps for a spur pair with a
  /// piecewise-constant k, else a table. kPiecewiseConstant: exact steps (throws unless spur and
  /// piecewise-constant k). kTable: num_samples exact samples per mesh period, linear
  /// interpolation. kFourier: the trigonometric interpolant of those samples (ToFourier),
  /// num_terms harmonics (0: num_samples/2). The linear interpolation of a table errs by
  /// O((2π/num_samples)²) between samples (μ ≈ 1e-4 relative at 256 samples for a typical
  /// helical pair, docs/benchmarks.md): with many slices raise num_samples so that it stays
  /// below the O(N⁻²) slicing error. The Fourier form may undershoot below 0 near the kinks.
  MeshCoefficientForm form = MeshCoefficientForm::kAuto;
  int num_samples = 256;  ///< samples per mesh period (kTable, kFourier, kAuto's table)
  int num_terms = 0;      ///< harmonics of kFourier, < num_samples/2
  /// False with a message naming the field, its value and the bound.
  bool IsValid(std::string* why) const;
};

/// @brief Options of MakeMeshCore.
struct MeshCoreOptions {
  MeshModelLevel level = MeshModelLevel::kBlankenshipSingh;  ///< requested level
  MeshCoefficientOptions coefficient;  ///< linear levels: representation of (K, K·h, K·μ·b²)
  int num_slices = 20;                 ///< kNonlinearSlices: N ≥ 1
  SliceCoefficientOptions slices;      ///< kNonlinearSlices: representation of k_s, e_s
};

/// @brief A linear core of `level` (not kNonlinearSlices or kContact) from the source.
/// @throws InvalidInput naming `level` (kNonlinearSlices, kContact), `options` fields, or as the
///   core.
LinearMeshCore MakeLinearMeshCore(const MeshCoreSource& source, MeshModelLevel level,
                                  const MeshCoefficientOptions& options = {});

/// @brief The slice core with N = num_slices σ-bands (see the @file).
/// @throws InvalidInput naming `num_slices` (≤ 0), `options` fields, `backlash`, or as the core.
SliceMeshCore MakeSliceMeshCore(const MeshCoreSource& source, int num_slices,
                                const SliceCoefficientOptions& options = {});

/// @brief The slice channels k_s(θ) [N/m] at one θ into out (N): the exact clipped-line
/// stiffness in each of the num_slices σ-bands (what MakeSliceMeshCore samples).
/// @throws InvalidInput naming num_slices or out (size).
void CalcSliceStiffness(const ContactLineModel& model, int num_slices, double theta,
                        Eigen::Ref<VectorX> out);

/// @brief σ_s [m] of the num_slices band centres.
VectorX CalcSliceSigma(const ContactLineModel& model, int num_slices);

/// @brief Any level as the MeshCore variant (architecture §3.4).
MeshCore MakeMeshCore(const MeshCoreSource& source, const MeshCoreOptions& options = {});

}  // namespace geardyn
