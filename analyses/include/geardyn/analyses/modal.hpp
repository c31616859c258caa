/// @file
/// @brief Eigen analysis of the mean (LTI) system, `ComputeModes` (spec 02 "Eigen (LTI)", issue
/// 4): undamped modes K̄ φ = ω² M φ (dense or ARPACK shift-invert), rigid-body modes, damped
/// complex modes, and the energy classification of each mode.
///
/// **Problem.** K̄ is the mean stiffness of the assembled system (AssembleMeanStiffness: the
/// constant part plus every mesh at the mean of its θ-coefficients), M the mass matrix, C the
/// damping matrix (AssembleDamping). Units: λ = ω² [rad²/s²], f = ω/(2π) [Hz].
///
/// **Method selection** (`internal::SelectModalMethod`, architecture §3.4), used in one switch and
/// copied into ModalResult::method_used:
/// | options.method | n = num_dofs | used |
/// |---|---|---|
/// | kDense | any | kDense (all n modes; with vectors and 0 < num_modes < n only those, by the
/// few-modes dense solver of symmetric_eigen_subset.hpp) | | kArpack | n ≥ 3 and num_modes' < n |
/// kArpack (num_modes' = num_modes or 20) | | kArpack | n too small for ARPACK (it needs num_modes
/// < ncv ≤ n) | kDense + a warning | | kAuto | n ≤ dense_max_dofs, num_modes' ≥ n/2, or n too small
/// for ARPACK | kDense | | kAuto | otherwise | kArpack | dense_max_dofs defaults to 199
/// (`kDefaultDenseMaxDofs`, the model's storage hint): there a full dense solve (all modes) costs a
/// few milliseconds; ARPACK is faster for 20 modes from about 100 DOFs on and wins by 10⁴ at 5 000
/// DOFs (docs/benchmarks.md, "Modal analysis"). Forcing either path always works (equivalence
/// tests, paired benchmarks).
///
/// **Rigid-body modes** (spec 02, architecture §3.7): the one criterion of rigid_modes.hpp — an
/// M-normalized pair with |λ| ≤ zero_tol·φᵀ diag(K̄) φ (a null vector of K̄ in the diagonally
/// scaled coordinates, independent of units and masses) — is set to exactly 0, reported as zero
/// frequencies and counted in num_rigid_body_modes with a warning in summary.warnings. Never NaN,
/// never a failure; K̄ is never inverted (the ARPACK shift lies slightly below zero).
///
/// **Energy fractions** (options.compute_energy_fractions; M-normalized φ, ω² = λ):
/// * kinetic, per DofKind k (torsional θz, transverse x/y, axial z, tilt θx/θy):
///   T_k = φ_kᵀ M_kk φ_k / Σ_j φ_jᵀ M_jj φ_j, with M_kk the diagonal block of M on the DOFs of kind
///   k. The cross-kind mass terms (the consistent shaft mass couples translation and tilt) are left
///   out so that every fraction is in [0, 1]; the fractions sum to 1 per mode. The same
///   definition per body gives body_kinetic_fractions.
/// * strain, per mesh and per element (bearing, shaft, coupling, spring):
///   U_e = φ_eᵀ K_e φ_e / φᵀ K̄ φ with K_e the element's constant stiffness and, for a mesh, the
///   mean mesh stiffness Gᵀ K̄2 G (all ≥ 0). The stiffness not owned by any element or mesh, if
///   any, appears as a last entry named "other"; the fractions then sum to 1 per mode. A
///   rigid-body mode has no strain energy: all its strain fractions are 0.
///
/// **Labels.** A rigid-body mode is kRigidBody. Otherwise the dominant kinetic-energy kind gives
/// kRotational (torsional θz), kTranslational (x, y), kAxial (z) or kRocking (θx, θy).
/// The multiplicity groups (modes whose frequencies agree within multiplicity_rel_tol) and the
/// per-body kinetic fractions are always reported.
///
/// **Planetary labels** (planetary_labels; only when the model's DofMap has bodies with
/// BodyRole::kPlanet — the roles are data of the model, set by whoever built it). Lin & Parker
/// 1999 (J. Sound Vib. 228(1) 109–128) show that a planetary set with N equally spaced identical
/// planets and isotropic supports has exactly three kinds of modes: *rotational* (central members
/// — sun, ring, carrier — only rotate, multiplicity 1), *translational* (central members only
/// translate, multiplicity 2) and *planet* modes (central members at rest, multiplicity N − 3,
/// only for N ≥ 4). For the planar model (x, y, θz per body) there are 6 rotational modes, 6
/// pairs of translational modes and 3 planet-mode frequencies. For the 6-DOF model the same
/// cyclic-symmetry argument (central members carry only the harmonics k = 0 and k = ±1 of the
/// planet index) gives 12 rotational(-axial) modes (central members move only along and about the
/// axis: z, θz), 12 translational(-tilting) pairs (central members only x, y, θx, θy) and 6
/// planet-mode frequencies of multiplicity N − 3 when the meshes couple in-plane and axial motion
/// (helical gears); with spur gears the out-of-plane motion decouples and the two in-phase planet
/// tilt modes (k = 0) also leave the central members at rest: 10 rotational modes, 12 pairs,
/// 4 planet frequencies of multiplicity N − 3 and 2 of multiplicity N − 2
/// (tests/analyses/planetary_modes_test.cpp derives this). The label is
/// decided per multiplicity group G from the basis-independent energies E_X = Σ_{k∈G} φ_kᵀ M_XX
/// φ_k over three DOF sets X: the axial/torsional DOFs (z, θz) of every non-planet body, the
/// lateral DOFs (x, y, θx, θy) of every non-planet body, and all planet DOFs (block-diagonal parts
/// of M, as for the kinetic fractions). With E_c = E_axial + E_lateral and
/// t = kPlanetaryEnergyTol: E_c ≤ t·E → kPlanet; else E_lateral ≤ t·E_c → kRotational; else
/// E_axial ≤ t·E_c → kTranslational; else kMixed (the symmetry is broken: unequal spacing,
/// anisotropic supports, a mistuned planet). Bodies with role kOther count as central members (on
/// the axis). The multiplicities are not used to label; a symmetric set has the ones above.
///
/// **Damped modes** (options.compute_damped): the state-space problem of M q̈ + C q̇ + K̄ q = 0
/// with the M-symmetric scaling y = Lᵀ q (M = L Lᵀ), ẋ = A x, x = [y; ẏ/ω_s],
/// A = [[0, ω_s I], [−L⁻¹K̄L⁻ᵀ/ω_s, −L⁻¹CL⁻ᵀ]] (ω_s = √s balances the two blocks), solved densely
/// (Eigen's real Schur). An eigenvalue λ = −ζω_n ± iω_n√(1−ζ²) gives one DampedMode with
/// ω_n = |λ|, ζ = −Re λ/|λ| and damped frequency Im λ/(2π); conjugate pairs appear once
/// (Im λ > 0); a real eigenvalue (overdamped) appears once with frequency 0 and ζ = 1.
/// The damped zeros of rigid-body modes (the state matrix has a defective zero there, found only
/// to √ε·ω_s) are set to exactly 0, up to 2 × num_rigid_body_modes of them. Sorted by ω_n, then
/// by damped frequency. The classification of C is reported in every case
/// (damping_kind): kNone (C = 0), kRayleigh (C = αM + βK̄ within proportional_damping_tol in the
/// Frobenius norm, with α [1/s] and β [s]), kClassical (C M⁻¹K̄ = K̄ M⁻¹C within the tolerance:
/// the undamped modes diagonalize C, e.g. modal damping ratios) or kNonProportional. For a
/// proportional (kNone, kRayleigh, kClassical) damping the modal damping ratios
/// ζ_k = φ_kᵀ C φ_k / (2ω_k) of the undamped modes are exact and given in
/// modal_damping_ratios; the state-space problem is still solved when asked.
///
/// **Thread safety.** ComputeModes is reentrant; the ARPACK path is serialized by the numerics
/// layer (ARPACK's SAVE variables).
#pragma once

#include <complex>
#include <optional>
#include <string>
#include <vector>

#include "geardyn/common/eigen_types.hpp"
#include "geardyn/common/summary.hpp"
#include "geardyn/numerics/rigid_modes.hpp"
#include "geardyn/system/dof_map.hpp"
#include "geardyn/system/system_model.hpp"

namespace geardyn {

/// Number of DofKind values (torsional, transverse, axial, tilt).
inline constexpr int kNumDofKinds = 4;

/// Default kAuto threshold: dense up to this many DOFs, i.e. exactly where the model's storage
/// hint is kDense (num_dofs < kDenseDofThreshold).
inline constexpr int kDefaultDenseMaxDofs = kDenseDofThreshold - 1;

/// Default number of ARPACK modes when ModalOptions::num_modes is 0.
inline constexpr int kDefaultArpackModes = 20;

/// @brief Eigen solver path of ComputeModes (see the selection table in the file comment).
enum class ModalMethod {
  kAuto,    ///< dense for small systems, ARPACK above dense_max_dofs
  kDense,   ///< all modes of the dense pencil (Cholesky + tridiagonal QR), O(n³)
  kArpack,  ///< lowest modes by ARPACK shift-invert Lanczos on the sparse pencil
};

/// Stable name "auto", "dense", "arpack".
const char* ToString(ModalMethod method);

/// @brief Mode-type label (see the file comment).
enum class ModeType {
  kRigidBody,      ///< zero frequency
  kRotational,     ///< kinetic energy mostly torsional (θz)
  kTranslational,  ///< kinetic energy mostly transverse (x, y)
  kAxial,          ///< kinetic energy mostly axial (z)
  kRocking,        ///< kinetic energy mostly in tilts (θx, θy)
};

/// Stable name "rigid_body", "rotational", "translational", "axial", "rocking".
const char* ToString(ModeType type);

/// Relative energy below which a DOF set counts as at rest for the planetary labels (a
/// kinetic-energy fraction; 1e-8 is an amplitude ratio of 1e-4, far above the round-off of the
/// eigenvectors and far below any physical participation).
inline constexpr double kPlanetaryEnergyTol = 1e-8;

/// @brief Mode type of a planetary set (Lin & Parker 1999; see the file comment).
enum class PlanetaryModeType {
  kRotational,     ///< central members rotate / move axially only; multiplicity 1
  kTranslational,  ///< central members translate / tilt only; multiplicity 2
  kPlanet,         ///< central members at rest; multiplicity N − 3
  kMixed,          ///< none of the above (the cyclic symmetry is broken)
};

/// Stable name "rotational", "translational", "planet", "mixed".
const char* ToString(PlanetaryModeType type);

/// @brief What the damping matrix is, relative to M and K̄ (see the file comment).
enum class DampingKind {
  kNone,             ///< C = 0
  kRayleigh,         ///< C = αM + βK̄
  kClassical,        ///< C M⁻¹ K̄ = K̄ M⁻¹ C (undamped modes diagonalize C)
  kNonProportional,  ///< none of the above: complex modes
};

/// Stable name "none", "rayleigh", "classical", "non_proportional".
const char* ToString(DampingKind kind);

/// Above this size the damping classification tests C on the computed modes instead of the
/// O(n³) commutation test C M⁻¹K̄ = K̄ M⁻¹C, so it needs the mode vectors.
inline constexpr int kDenseDampingTestMaxDofs = 2000;

/// @brief Options of ComputeModes.
struct ModalOptions {
  ModalMethod method = ModalMethod::kAuto;  ///< solver path (kAuto: see the file comment)
  /// Number of modes wanted (the lowest, or the nearest `shift` with ARPACK); 0 → all for the
  /// dense path, kDefaultArpackModes for ARPACK. In [0, n] (n = the model's DOFs; checked by
  /// ComputeModes, which throws InvalidInput above n).
  int num_modes = 0;
  /// Shift σ [rad²/s²]: the num_modes eigenvalues nearest σ (both paths; the dense one ignores
  /// it when num_modes = 0). nullopt → the lowest modes, rigid-body ones first (ARPACK: σ slightly
  /// below 0). Finite.
  std::optional<double> shift;
  /// kAuto: dense when num_dofs ≤ dense_max_dofs. ≥ 1.
  int dense_max_dofs = kDefaultDenseMaxDofs;
  bool compute_shapes = false;           ///< return the mode shapes (n × m)
  bool compute_energy_fractions = true;  ///< kinetic/strain fractions and labels
  bool compute_damped = false;           ///< solve the damped state-space problem (dense)
  /// Modal damping ratios ζ_k = φ_kᵀCφ_k/(2ω_k) when C ≠ 0. They need the mode vectors: with
  /// false (and neither shapes nor energy fractions) a damped model's modes are computed as
  /// eigenvalues only, as an undamped one's, unless the damping classification of a large model
  /// (n > kDenseDampingTestMaxDofs) or its damped modes (n > damped_max_dofs) need them.
  bool compute_damping_ratios = true;
  /// Largest n for the dense state-space problem (O((2n)³)); above it, proportionally damped
  /// systems get their damped modes from the modal damping ratios of the computed modes (exact)
  /// and non-proportional ones none, with a warning. ≥ 1.
  int damped_max_dofs = 2000;
  /// Relative gap |f_i − f_j| ≤ tol·max(f_i, f_j) that groups modes as repeated. In (0, 1).
  double multiplicity_rel_tol = 1e-6;
  /// |λ| ≤ zero_tol·φᵀ diag(K̄) φ (φᵀMφ = 1) is a rigid-body zero (rigid_modes.hpp). In [0, 1).
  double zero_tol = kRigidNullTol;
  /// ARPACK relative accuracy of the Ritz values; 0 → machine ε. In [0, 1).
  double arpack_tol = 1e-12;
  /// Relative Frobenius residual below which C counts as Rayleigh or classical. In (0, 1).
  double proportional_damping_tol = 1e-8;

  /// @brief True when every field is in range; otherwise `why` names the field, value and bound.
  bool IsValid(std::string* why) const;
};

/// @brief One damped complex mode: λ = −ζω_n ± iω_d.
struct DampedMode {
  double frequency_hz = 0.0;          ///< damped frequency ω_d/(2π) = Im λ/(2π) ≥ 0 [Hz]
  double natural_frequency_hz = 0.0;  ///< ω_n/(2π) = |λ|/(2π) [Hz]
  double damping_ratio = 0.0;         ///< ζ = −Re λ/|λ| [-] (0 for a zero eigenvalue)
  std::complex<double> eigenvalue;    ///< λ with Im λ ≥ 0 [1/s]
};

/// @brief Modes of the mean system, their classification and the solver report.
struct ModalResult {
  /// (m) f_k = √λ_k/(2π), ascending [Hz]; exactly 0 for rigid-body modes.
  VectorX frequencies_hz;
  /// (m) λ_k = ω_k², ascending [rad²/s²].
  VectorX eigenvalues;
  /// (n × m) M-orthonormal mode shapes [m, rad per √(kg·m²)]; empty unless compute_shapes.
  MatrixX shapes;
  /// Number of modes whose frequency was set to zero [-].
  int num_rigid_body_modes = 0;

  /// (m × kNumDofKinds) kinetic-energy fraction per DofKind, column = static_cast<int>(kind);
  /// empty unless compute_energy_fractions.
  MatrixX kinetic_fractions;
  /// (m × num_bodies) kinetic-energy fraction per body; empty unless compute_energy_fractions.
  MatrixX body_kinetic_fractions;
  /// Names of the strain-energy owners, in column order: "mesh:<name>", "element:<name>", and
  /// "other" when some stiffness belongs to neither.
  std::vector<std::string> strain_names;
  /// (m × strain_names.size()) strain-energy fractions; empty unless compute_energy_fractions.
  MatrixX strain_fractions;
  /// (num_bodies) body names, the columns of body_kinetic_fractions.
  std::vector<std::string> body_names;
  /// (n) DOF names "<body>.<component>", the rows of shapes; empty unless compute_shapes.
  std::vector<std::string> dof_names;
  /// (m) mode types; empty unless compute_energy_fractions.
  std::vector<ModeType> labels;
  /// (m) planetary mode types (file comment); empty unless compute_energy_fractions and the
  /// model has bodies with BodyRole::kPlanet.
  std::vector<PlanetaryModeType> planetary_labels;
  /// Groups of mode indices (ascending) whose frequencies agree within multiplicity_rel_tol,
  /// one group per distinct frequency (singletons included), in frequency order.
  std::vector<std::vector<int>> multiplicity_groups;

  /// Classification of C (always computed; cheap next to the eigen solve for dense systems).
  DampingKind damping_kind = DampingKind::kNone;
  double rayleigh_alpha = 0.0;  ///< α of C ≈ αM + βK̄ [1/s] (kRayleigh, kNone)
  double rayleigh_beta = 0.0;   ///< β of C ≈ αM + βK̄ [s] (kRayleigh, kNone)
  /// (m) ζ_k = φ_kᵀCφ_k/(2ω_k) [-], exact when damping_kind ≠ kNonProportional (0 for rigid
  /// modes); empty without damping (C = 0) or without vectors (ARPACK/dense run with neither
  /// shapes nor energy fractions on an undamped model, or with compute_damping_ratios = false).
  VectorX modal_damping_ratios;
  /// Damped modes, sorted by natural frequency; empty unless compute_damped.
  std::vector<DampedMode> damped_modes;

  ModalMethod method_used = ModalMethod::kAuto;  ///< kDense or kArpack (never kAuto)
  /// Status and message; counters of the solver ("factorizations", "operator_applications",
  /// "iterations", "num_dofs", "num_modes"); warnings: rigid-body modes, kAuto fallbacks,
  /// non-proportional damping. error_estimate: max over modes of ‖K̄φ − λMφ‖/‖K̄φ‖ (relative
  /// residual; ‖Mφ‖λ-scaled for rigid modes) when vectors were computed, else 0.
  Summary summary;
};

namespace internal {
/// @brief The method ComputeModes runs for `model` and `options` (never kAuto); see the table in
/// the file comment. `why` (optional) receives the fallback reason, if any.
ModalMethod SelectModalMethod(int num_dofs, const ModalOptions& options, std::string* why);
}  // namespace internal

/// @brief Modes of the mean (LTI) system of `model` (see the file comment).
/// @param[in] model the assembled system (M, C, K̄ = constant K + mean mesh stiffness).
/// @param[in] options see ModalOptions.
/// @return frequencies, eigenvalues, optional shapes, energy classification, damped modes and the
/// Summary. Numerical outcomes (K̄ not PSD, ARPACK not converged) are statuses, not exceptions.
/// @throws InvalidInput if !options.IsValid(&why) (message = why), or the model is empty.
ModalResult ComputeModes(const SystemModel& model, const ModalOptions& options = {});

/// @brief The result as JSON: {"method_used", "status", "message", "warnings",
/// "frequencies_hz", "num_rigid_body_modes", "damping_kind", "modes": [{"index",
/// "frequency_hz", "eigenvalue", "label", "multiplicity", "kinetic": {kind: fraction},
/// "strain": {name: fraction}, "modal_damping_ratio"}], "damped_modes": [{"frequency_hz",
/// "natural_frequency_hz", "damping_ratio"}], and "dof_names" and "shapes" (one array per mode)
/// when present}. Numbers are printed with 17 significant digits; non-finite numbers (never
/// produced by ComputeModes) as null.
/// @param[in] result a ComputeModes result.
std::string ModalResultToJson(const ModalResult& result);

/// @brief The per-mode table as CSV, one row per mode: mode, frequency_hz, eigenvalue, label,
/// multiplicity, the kinetic fractions (kinetic_<kind>), the strain fractions (strain_<name>).
std::string ModalResultToCsv(const ModalResult& result);

}  // namespace geardyn
