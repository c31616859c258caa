/// @file
/// @brief Mesh cores: the data forms of one gear mesh that every analysis reads (spec 01 §3–§5,
/// spec 02; architecture §3.1, §3.4) — `LinearMeshCore` (the LTV/LTI levels of the model
/// hierarchy), `SliceMeshCore` (the nonlinear, contact-loss-capable slice form) and the virtual
/// `NonlinearMeshCore` escape hatch (spec 03), closed in the variant `MeshCore`.
///
/// A core acts on the two mesh deflections δ = [δ_η, δ_ζ]ᵀ = G q_pair [m, rad] (G the 2×12 mesh
/// Jacobian built by geardyn::models). It holds no gear physics: the θ-coefficients are filled
/// by the builders of geardyn/models/mesh/mesh_cores.hpp from the contact lines, and analyses
/// depend on this header only (architecture §3.1: analyses → core ← models).
///
/// **Energy (spec 01 §3).** Every form discretizes
/// \f[ U(δ, θ) = ½ ∫ k\,[δ_η − σ δ_ζ − e]_+^2\,dℓ. \f]
/// * LinearMeshCore — all contact lines loaded: U = ½ δᵀK2δ − δᵀK2ε + const with
///   K2 = [[K, −K h], [−K h, K μ b²]] (B–S Eqs. 18, 21e, 26b), stored as the three channels
///   (K, K·h, K·μ·b²) [N/m, N, N·m]; ε = (ε_η, ε_ζ) [m, rad] optional.
/// * SliceMeshCore — the σ axis of the contact cut into N slices at σ_s:
///   U = ½ Σ_s k_s(θ) [δ_η − σ_s δ_ζ − e_s(θ)]_+^2 (+ back flank, see SliceMeshCore).
///
/// **Sign conventions.** The generalized mesh force *pair* of a core is F = ∂U/∂δ =
/// [F_η [N], M_ζ [N·m]]: F_η > 0 is compression (the pinion pushes the gear along +η). The force
/// on the pair's coordinates is −Gᵀ F, the tangent stiffness Gᵀ (∂F/∂δ) G. For the linear core
/// F = K2 (δ − ε), i.e. the load vector is f_mesh = Gᵀ K2 ε (spec 01 §3).
///
/// **Levels (spec 01 §5).** A LinearMeshCore carries its MeshCoreLevel (the shape of the 2×2
/// core) and a mean-LTI flag; the level is data, so analyses never branch on gear type
/// (architecture §3.4):
/// | spec level | form | K2 |
/// |---|---|---|
/// | LTV 6-DOF (B–S) | LinearMeshCore, kBlankenshipSingh | [[c0, −c1], [−c1, c2]] |
/// | LTV 4-DOF coupling | LinearMeshCore, kCoupling4Dof | [[c0, 0], [0, 0]] (κ = 0, μ dropped) |
/// | LTI | LinearMeshCore, is_mean_lti() | channels replaced by their means, ε kept |
/// | torsional SDOF | LinearMeshCore, kTorsional | [[c0, 0], [0, 0]] on CalcLevelJacobian's G |
/// | nonlinear slices | SliceMeshCore | piecewise-linear in δ |
/// | nonlinear contact | NonlinearMeshCore | user code (spec 03) |
///
/// **Hot kernels** (EvalStiffnessCore, EvalDampingCore, EvalTransmissionError*,
/// EvalSliceForce, CalcSliceForce) use fixed sizes or caller/workspace buffers only and never
/// allocate; they do not re-validate what the constructors validated.
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "geardyn/common/eigen_types.hpp"
#include "geardyn/system/coefficient.hpp"

namespace geardyn {

// ============================================================================ levels

/// @brief The shape of a linear mesh core (spec 01 §5); all levels share the mesh Jacobian G.
///
/// The shape only: the model levels of geardyn::models that differ from B–S's in geometry or in
/// the transmission error ("bs_projected": B–S's projected-arm G; "five_dof": ε_ζ ≡ 0) carry
/// kBlankenshipSingh (MeshModelLevel, mesh_cores.hpp).
///
/// * kBlankenshipSingh — K2 = K [[1, −h], [−h, μ b²]]: five coupled DOF (B–S Eq. 41).
/// * kCoupling4Dof — κ = 0 and the μ term dropped: K2 = K diag(1, 0), rank 1 (Kiyono et al. 1978,
///   Küçükay 1984).
/// * kTorsional — the kCoupling4Dof core on the torsional restriction of G (CalcLevelJacobian):
///   the SDOF k(θ) on a_i θ_i ± a_j θ_j of Kahraman & Singh (1990).
enum class MeshCoreLevel { kBlankenshipSingh, kCoupling4Dof, kTorsional };

/// Short name of a level ("blankenship_singh", "coupling_4dof", "torsional").
const char* ToString(MeshCoreLevel level);

/// @brief G as seen by a level: G itself, or for kTorsional only its θz columns (5 and 11):
/// translations and tilts held by rigid supports, only the rotations about the axes remain.
/// @param[in] level model level.
/// @param[in] G mesh Jacobian (2×12) [-, m].
/// @return the level's Jacobian (2×12) [-, m].
Matrix2x12 CalcLevelJacobian(MeshCoreLevel level, const Matrix2x12& G);

// ============================================================================ damping

/// @brief Mesh damping of B–S Eq. (39): the energy-equivalent viscous damper of the same shape
/// as the stiffness, C2 = (c_m / K) K2, with c_m given or from a damping ratio of the mesh mode.
///
/// A ratio needs the equivalent mass of the mesh mode along η, which only the assembled system
/// knows; ResolveDampingCoefficient converts it once, at build time, with the MEAN mesh stiffness
/// K̄: c_m = 2 ζ_m √(K̄ m_e) (constant in θ).
struct MeshDamping {
  enum class Kind {
    kNone,         ///< no mesh damping
    kCoefficient,  ///< value = c_m ≥ 0 [N·s/m]
    kRatio,        ///< value = ζ_m ≥ 0 [-]
  };
  Kind kind = Kind::kNone;  ///< how `value` is read
  double value = 0.0;       ///< c_m [N·s/m] or ζ_m [-]

  /// No damping.
  static MeshDamping None() { return {}; }
  /// A mesh damping coefficient c_m [N·s/m] along η.
  static MeshDamping FromCoefficient(double c_m) { return {Kind::kCoefficient, c_m}; }
  /// A damping ratio ζ_m [-] of the mesh mode.
  static MeshDamping FromRatio(double zeta_m) { return {Kind::kRatio, zeta_m}; }
  /// False (with the field, value and bound in `why`) unless value is finite and ≥ 0.
  bool IsValid(std::string* why) const;
};

/// @brief c_m [N·s/m] of a damping specification: 0 (kNone), value (kCoefficient), or
/// 2 ζ_m √(K̄ m_e) (kRatio).
/// @param[in] damping the specification.
/// @param[in] mean_stiffness K̄ ≥ 0 [N/m] (used by kRatio only).
/// @param[in] equivalent_mass m_e > 0 [kg] of the mesh mode along η (used by kRatio only).
/// @throws InvalidInput naming damping.value, mean_stiffness or equivalent_mass.
double ResolveDampingCoefficient(const MeshDamping& damping, double mean_stiffness,
                                 double equivalent_mass);

// ============================================================================ sidebands

/// @brief A transmission error given by a few lines over a long period (a sparse Fourier form):
/// \f[ ε_{sb}(θ) = 2\,\mathrm{Re} \sum_i c_i\, e^{i m_i θ / P_s}, \quad m_i ≥ 1, \f]
/// added to a LinearMeshCore's θ-coefficient ε. What a runout gives (once per revolution of each
/// member: m = P_s/z over P_s = lcm(z_1, z_2)) when the hunting period is too long to tabulate
/// (997/991 teeth: P_s = 988 027 mesh cycles); the linear harmonic balance then needs ε only at
/// its kept harmonics, and pointwise evaluation costs O(lines) (docs/design.md).
struct TransmissionErrorSidebands {
  std::int64_t period_meshes = 1;       ///< P_s ≥ 1 [-]: the lines' period is 2π·P_s [rad]
  std::vector<std::int64_t> harmonics;  ///< m_i ≥ 1 [-] (harmonic m of 1/P_s)
  MatrixXc coefficients;                ///< (2 × lines) c_i: [ε_η [m]; ε_ζ [rad]]
  /// Number of lines.
  int size() const { return static_cast<int>(harmonics.size()); }
  /// True without lines.
  bool empty() const { return harmonics.empty(); }
};

// ============================================================================ LinearMeshCore

/// @brief The linear mesh core of spec 01 §3: θ-coefficients (K, K·h, K·μ·b²) and optional
/// (ε_η, ε_ζ), a level, mesh damping and the mean-LTI flag. Immutable, validated once.
///
/// Channels of `stiffness()` (the entries of K2, linear in k, so their Fourier coefficients are
/// the Hill/HB blocks and linear interpolation keeps K2 PSD):
/// c0 = K = ∫k dℓ [N/m], c1 = K·h = ∫kσ dℓ [N], c2 = K·μ·b² = ∫kσ² dℓ [N·m].
/// Channels of `transmission_error()`: ε_η [m], ε_ζ [rad] (spec 01 §3, ε = K2⁻¹[∫ke, −∫kσe]).
class LinearMeshCore {
 public:
  /// Number of stiffness channels (K, K·h, K·μ·b²).
  static constexpr int kNumStiffnessChannels = 3;
  /// Number of transmission-error channels (ε_η, ε_ζ).
  static constexpr int kNumTransmissionErrorChannels = 2;

  /// @param[in] level shape of the core (spec 01 §5).
  /// @param[in] stiffness (3 channels) K [N/m], K·h [N], K·μ·b² [N·m].
  /// @param[in] half_face_width b > 0 [m] (μ = c2/(c0 b²), κ = h/b).
  /// @param[in] transmission_error optional (2 channels) ε_η [m], ε_ζ [rad].
  /// @param[in] damping mesh damping (B–S Eq. 39).
  /// @param[in] mean_lti true marks the spec level "LTI" (the stiffness must then be constant:
  ///   use MakeMeanLinearMeshCore to build it from an LTV core).
  /// @param[in] sidebands optional lines added to ε (TransmissionErrorSidebands); none may fall
  ///   on a harmonic of the stiffness period (m_i·P_K divisible by P_s): those belong in ε.
  /// @throws InvalidInput naming `stiffness` (channel count, or a value that is negative or makes
  ///   K2 indefinite: c0 < 0 or c0·c2 < c1²), `transmission_error` (channel count),
  ///   `half_face_width`, `damping.value` (negative or non-finite) or `mean_lti` (set with
  ///   non-constant stiffness channels), `sidebands` (P_s < 1, sizes, m_i < 1, a non-finite
  ///   coefficient, a line on a stiffness harmonic). K2 is checked at every
  ///   stored value of constant, piecewise-constant and table coefficients (linear interpolation
  ///   keeps it PSD); a Fourier series is checked at its mean only.
  LinearMeshCore(MeshCoreLevel level, Coefficient stiffness, double half_face_width,
                 std::optional<Coefficient> transmission_error = std::nullopt,
                 MeshDamping damping = {}, bool mean_lti = false,
                 TransmissionErrorSidebands sidebands = {});

  /// The level (shape of K2).
  MeshCoreLevel level() const { return level_; }
  /// True for the spec level "LTI" (mean stiffness, ε kept).
  bool is_mean_lti() const { return mean_lti_; }
  /// (K, K·h, K·μ·b²) [N/m, N, N·m].
  const Coefficient& stiffness() const { return stiffness_; }
  /// (ε_η, ε_ζ) [m, rad], if any.
  const std::optional<Coefficient>& transmission_error() const { return transmission_error_; }
  /// Lines added to ε (empty: none).
  const TransmissionErrorSidebands& sidebands() const { return sidebands_; }
  /// True when ε is not identically zero (a coefficient or sidebands).
  bool has_transmission_error() const { return transmission_error_ || !sidebands_.empty(); }
  /// b [m].
  double half_face_width() const { return half_face_width_; }
  /// Mesh damping specification.
  const MeshDamping& damping() const { return damping_; }

 private:
  MeshCoreLevel level_;
  Coefficient stiffness_;
  double half_face_width_;
  std::optional<Coefficient> transmission_error_;
  TransmissionErrorSidebands sidebands_;
  MeshDamping damping_;
  bool mean_lti_;
};

/// @brief The spec level "LTI" from an LTV core: the stiffness channels replaced by their exact
/// means (a ConstantCoefficient, so K̄2 is the mean of K2(θ) because K2 is linear in the
/// channels); level, b, damping and the transmission error ε(θ) are kept (spec 01 §5: "mean K̄2,
/// ε independent").
LinearMeshCore MakeMeanLinearMeshCore(const LinearMeshCore& core);

/// @brief K2(θ) of the core's level: B–S [[c0, −c1], [−c1, c2]], otherwise [[c0, 0], [0, 0]].
/// No allocation.
/// @param[in] theta mesh phase [rad], finite.
/// @return (2×2) [N/m, N, N·m], symmetric PSD.
/// @throws InvalidInput if θ is not finite.
Matrix2 EvalStiffnessCore(const LinearMeshCore& core, double theta);

/// @brief K2 of a level from the stiffness channels c = (K, K·h, K·μ·b²), the map
/// EvalStiffnessCore applies: [[K, −Kh], [−Kh, Kμb²]] (B–S Eqs. 18, 21e, 26b), or diag(K, 0)
/// for the reduced levels (κ = 0, μ term dropped; spec 01 §5). Linear in c, so it maps the
/// channels' θ-derivatives to ∂K2/∂θ as well.
Matrix2 StiffnessCoreFromChannels(MeshCoreLevel level, const Vector3& c);

/// @brief C2(θ) = (c_m / K(θ)) K2(θ) (B–S Eq. 39), zero where K(θ) = 0. No allocation.
/// @param[in] theta mesh phase [rad].
/// @param[in] c_m mesh damping coefficient [N·s/m] (ResolveDampingCoefficient).
/// @return (2×2) [N·s/m, N·s, N·m·s].
Matrix2 EvalDampingCore(const LinearMeshCore& core, double theta, double c_m);

/// @brief ε(θ) = (ε_η [m], ε_ζ [rad]): the coefficient plus the sidebands; zero without either.
Vector2 EvalTransmissionError(const LinearMeshCore& core, double theta);

/// @brief The θ-mean of the load K2 ε [N, N·m] over the core's period: the coefficient part
/// from `samples_per_mesh` samples per mesh cycle over its own period (lcm of the stiffness's
/// and ε coefficient's), the sidebands exactly (zero: no line falls on a stiffness harmonic).
/// @throws InvalidInput if samples_per_mesh < 1.
Vector2 CalcMeanTransmissionErrorLoad(const LinearMeshCore& core, int samples_per_mesh);

/// @brief P of the core without its sidebands: lcm of the stiffness's and ε coefficient's periods.
std::int64_t CoefficientPeriodMeshes(const LinearMeshCore& core);

/// @brief The load pair K2(θ) ε(θ) [N, N·m] on δ (f_mesh = Gᵀ K2 ε, spec 01 §3); for the
/// mean-LTI level K̄2 ε(θ). No allocation.
Vector2 EvalTransmissionErrorLoad(const LinearMeshCore& core, double theta);

/// @brief c_m of the core's damping (kRatio uses K̄ = mean of channel K).
/// @param[in] equivalent_mass m_e > 0 [kg] (kRatio only).
double ResolveDampingCoefficient(const LinearMeshCore& core, double equivalent_mass);

/// @brief How the core's operator (K2 and C2) depends on θ: Classify of the stiffness channels
/// (C2 = c_m [[1, −h], [−h, μb²]] changes exactly when they do). kConstant for mean-LTI cores.
TimeDependence Classify(const LinearMeshCore& core);

/// @brief How the load K2 ε depends on θ: the larger of the stiffness's and ε's (kConstant
/// without ε).
TimeDependence ClassifyExcitation(const LinearMeshCore& core);

/// @brief P of the core: lcm of its coefficients' period_meshes() and the sidebands' P_s (period
/// 2π·P [rad]).
std::int64_t PeriodMeshes(const LinearMeshCore& core);

// ============================================================================ SliceMeshCore

/// Backlash value meaning "no back-flank contact" (one-sided contact only).
inline constexpr double kNoBackFlank = std::numeric_limits<double>::infinity();

/// @brief The slice form of the mesh energy (spec 01 §4.4): N slices, each a narrow band of the
/// contact at a fixed σ_s, with a θ-varying stiffness k_s(θ) and unloaded separation e_s(θ).
///
/// **Energy.** With the drive-side approach of slice s, a_s = δ_η − σ_s δ_ζ − e_s(θ) [m],
/// \f[ U = ½ \sum_s k_s(θ) \left( [a_s]_+^2 + [−a_s − j]_+^2 \right), \f]
/// F = ∂U/∂δ = Σ_s k_s g_s [1, −σ_s]ᵀ with the clearance function g(a) = [a]₊ − [−a − j]₊
/// (Kahraman & Singh 1990's g with the dead zone −j ≤ a ≤ 0), and the tangent
/// J = ∂F/∂δ = Σ_s k_s χ_s [[1, −σ_s], [−σ_s, σ_s²]], χ_s = 1 when a_s > 0 or a_s < −j, else 0
/// (a slice at exactly a = 0 or a = −j counts as unloaded: J is the one-sided derivative from
/// the open side).
///
/// **Back flank** (spec 01 §3 "a second energy term of the same form … reached after the
/// backlash is closed"). j [m] is the normal clearance of every slice: the drive flank loses
/// contact at a_s = 0 and the back (coast) flank closes at a_s = −j, with the same stiffness
/// k_s and the same σ_s, expressed in the drive-side deflections δ. This is the clearance law of
/// the torsional models (Kahraman & Singh 1990; Blankenship & Kahraman 1995), exact for the
/// torsional coordinate a_i θ_i ± a_j θ_j; for the transverse/axial coordinates the true coast
/// contact lies on the mirrored plane of action (its own G), which this 2-DOF form does not
/// represent (the drive-side G is used for both flanks). e_s shifts both flanks together (the
/// clearance per slice stays j: a tooth-thickness-preserving error). j = kNoBackFlank (+∞)
/// disables the back flank; j = 0 is a tight (zero-backlash) mesh.
///
/// **Linear limit.** With every slice loaded on the drive side, F = K2_s (δ − ·) with the slice
/// channels (Σk_s, Σk_sσ_s, Σk_sσ_s²) = (K, K·h, K·μ·b²) up to the slicing error (the builder of
/// geardyn/models/mesh/mesh_cores.hpp makes it O(N⁻²)); see EvalSliceChannels.
class SliceMeshCore {
 public:
  /// @param[in] sigma (N ≥ 1) σ_s of each slice [m], along σ̂ from the reference point p0.
  /// @param[in] stiffness (N channels) k_s(θ) ≥ 0 [N/m], the contact-line stiffness in slice s.
  /// @param[in] half_face_width b > 0 [m] (only to report μ; the force does not use it).
  /// @param[in] separation optional (N channels) e_s(θ) [m]; absent = 0.
  /// @param[in] backlash j ≥ 0 [m] (normal clearance), or kNoBackFlank.
  /// @param[in] damping mesh damping (B–S Eq. 39 on the loaded slices, CalcSliceDampingCore).
  /// @throws InvalidInput naming `sigma` (empty, non-finite), `stiffness` (channel count ≠ N, a
  ///   negative stored value or mean), `separation` (channel count), `half_face_width`,
  ///   `backlash` (negative or NaN) or `damping.value`.
  SliceMeshCore(VectorX sigma, Coefficient stiffness, double half_face_width,
                std::optional<Coefficient> separation = std::nullopt,
                double backlash = kNoBackFlank, MeshDamping damping = {});

  /// N [-].
  int num_slices() const { return static_cast<int>(sigma_.size()); }
  /// (N) σ_s [m].
  const VectorX& sigma() const { return sigma_; }
  /// (N channels) k_s(θ) [N/m].
  const Coefficient& stiffness() const { return stiffness_; }
  /// (N channels) e_s(θ) [m], if any.
  const std::optional<Coefficient>& separation() const { return separation_; }
  /// b [m].
  double half_face_width() const { return half_face_width_; }
  /// j [m] (kNoBackFlank = +∞ when there is no back flank).
  double backlash() const { return backlash_; }
  /// True when j is finite.
  bool has_back_flank() const { return backlash_ < kNoBackFlank; }
  /// Mesh damping specification.
  const MeshDamping& damping() const { return damping_; }
  /// Identity shared by copies (the data is immutable); workspaces cache per id.
  std::uint64_t id() const { return id_; }

 private:
  VectorX sigma_;
  Coefficient stiffness_;
  double half_face_width_;
  std::optional<Coefficient> separation_;
  double backlash_;
  MeshDamping damping_;
  std::uint64_t id_;
};

/// @brief Scratch of one SliceMeshCore for one thread: the slice values at the last θ.
///
/// Built once (allocates N-vectors); the kernels then never allocate. The values are cached per
/// (core id, θ), so Newton iterations at a fixed θ evaluate the coefficients once.
struct SliceMeshWorkspace {
  explicit SliceMeshWorkspace(const SliceMeshCore& core);
  /// True when the buffers fit `core` (same N).
  bool IsCompatibleWith(const SliceMeshCore& core) const;

  VectorX stiffness;   ///< (N) k_s(θ) [N/m] at `theta`
  VectorX separation;  ///< (N) e_s(θ) [m] at `theta` (zeros without separation channels)
  double theta = std::numeric_limits<double>::quiet_NaN();  ///< θ of the cached values [rad]
  std::uint64_t core_id = 0;  ///< id of the core the cache belongs to (0: none)
};

/// @brief Generalized force pair of a slice core and its tangent (see SliceMeshCore).
struct SliceForce {
  Vector2 force = Vector2::Zero();     ///< F = ∂U/∂δ = [F_η [N], M_ζ [N·m]]
  Matrix2 jacobian = Matrix2::Zero();  ///< J = ∂F/∂δ [N/m, N, N·m], symmetric PSD
  double energy = 0.0;                 ///< U [J]
  int num_loaded = 0;                  ///< slices with k_s > 0 in drive-flank contact (a_s > 0)
  int num_back_loaded = 0;             ///< slices with k_s > 0 in back-flank contact (a_s < −j)
};

/// @brief Fills ws.stiffness and ws.separation at θ (cached: no work when θ and the core are
/// those of the last call). No allocation.
/// @throws InvalidInput if the workspace does not fit the core or θ is not finite.
void EvalSliceValues(const SliceMeshCore& core, SliceMeshWorkspace& ws, double theta);

/// @brief The slice force at (θ, δ): EvalSliceValues then CalcSliceForce. No allocation.
/// @param[in] theta mesh phase [rad].
/// @param[in] delta_eta δ_η [m] (positive: approach). @param[in] delta_zeta δ_ζ [rad].
SliceForce EvalSliceForce(const SliceMeshCore& core, SliceMeshWorkspace& ws, double theta,
                          double delta_eta, double delta_zeta);

/// @brief The slice force from given slice values (e.g. precomputed at all AFT time samples,
/// since k_s(θ), e_s(θ) do not depend on the state). No allocation when the arguments are
/// VectorX objects or contiguous columns (an expression would be evaluated into a temporary).
/// @param[in] stiffness (N) k_s [N/m]. @param[in] separation (N) e_s [m], or size 0 for none.
/// @throws InvalidInput (debug builds: assertion) on size mismatch.
SliceForce CalcSliceForce(const SliceMeshCore& core, const Eigen::Ref<const VectorX>& stiffness,
                          const Eigen::Ref<const VectorX>& separation, double delta_eta,
                          double delta_zeta);

/// @brief The linear-limit channels (Σk_s, Σk_s σ_s, Σk_s σ_s²) [N/m, N, N·m] at θ: what the
/// slice core reduces to with every slice loaded (compare with LinearMeshCore's stiffness).
Vector3 EvalSliceChannels(const SliceMeshCore& core, SliceMeshWorkspace& ws, double theta);

/// @brief C2 = (c_m / J₀₀) J of the loaded slices (B–S Eq. 39 restricted to the contact): equal
/// to the linear C2 with every slice loaded, zero without contact.
/// @param[in] c_m mesh damping coefficient [N·s/m].
Matrix2 CalcSliceDampingCore(const SliceForce& force, double c_m);

/// @brief c_m of the slice core's damping (kRatio uses K̄ = Σ_s mean k_s).
double ResolveDampingCoefficient(const SliceMeshCore& core, double equivalent_mass);

/// @brief kNonlinear (the slice force is piecewise linear in δ).
TimeDependence Classify(const SliceMeshCore& core);

/// @brief P: lcm of the stiffness's and separation's period_meshes().
std::int64_t PeriodMeshes(const SliceMeshCore& core);

// ============================================================================ NonlinearMeshCore

/// @brief Per-thread scratch of a NonlinearMeshCore (derive from it; made by MakeWorkspace()).
class NonlinearMeshCoreWorkspace {
 public:
  virtual ~NonlinearMeshCoreWorkspace() = default;
};

/// @brief Output of NonlinearMeshCore::CalcForces, sized by NonlinearMeshCore::MakeOutput().
///
/// **Power identity** (what time integration's energy balance rests on). With E the core's
/// stored energy, D ≥ 0 the power it dissipates and P the power that the prescribed mesh motion
/// (the nominal rotation θ(t), which no coordinate carries) feeds into it, every core satisfies at
/// every state
/// \f[ \mathrm{force}^T v = -\frac{dE}{dt} + P - D, \qquad
///     \frac{dE}{dt} = \frac{\partial E}{\partial x} v + \frac{\partial E}{\partial θ}\dot θ. \f]
/// For a conservative core P = ∂E/∂θ·θ̇ and D = 0; a viscous or friction element adds to D what it
/// dissipates, and the part of the friction work done by the nominal sliding to P (as a negative
/// contribution). The system's balance is then d(T + V₀ + ΣE)/dt = f₀ᵀv + ΣP − vᵀC₀v − ΣD.
struct NonlinearMeshCoreOutput {
  VectorX force;        ///< (n) generalized force on the core's coordinates [N, N·m]
  MatrixX stiffness;    ///< (n×n) −∂force/∂x, filled when requested [N/m, N, N·m]
  MatrixX damping;      ///< (n×n) −∂force/∂v, filled when requested [N·s/m, …]
  double energy = 0.0;  ///< E: energy stored in the core (contacts + internal springs) [J]
  double dissipation_power = 0.0;  ///< D ≥ 0: power dissipated by the core [W]
  double phase_power = 0.0;        ///< P: power fed in by the prescribed mesh motion [W]
  int num_contacts = 0;            ///< active contacts (diagnostics)
  /// (num_switching_functions()) signed switching functions g_k(x, θ) [m]: a zero crossing is a
  /// contact event (g > 0 open, g ≤ 0 closed: e.g. the signed gap of each candidate tooth-pair
  /// flank and slice). Time integrators locate their crossings instead of stepping over them.
  VectorX switching;
  /// (channel_names().size()) the core's own diagnostics at this state (e.g. per-tooth contact
  /// forces [N], contact status [-], tooth deflections [rad, m]); units in the names.
  VectorX channels;
  /// Optional sparse form of the Jacobians (additive to the dense contract above). A caller that
  /// accepts it sets `want_triplets` before CalcForces(with_jacobians = true); a core that
  /// supports it then appends the nonzeros of −∂force/∂x and −∂force/∂v (core coordinate indices;
  /// duplicates are to be summed) to the two lists instead of filling `stiffness` and `damping`
  /// (left untouched, not zeroed), and sets `has_triplets`. A core that does not support it fills
  /// the dense matrices and `has_triplets` stays false. CalcForces clears both lists and the flag.
  bool want_triplets = false;
  bool has_triplets = false;  ///< set by the core: the lists hold the Jacobians
  std::vector<Eigen::Triplet<double>> stiffness_triplets;  ///< [N/m, N, N·m]
  std::vector<Eigen::Triplet<double>> damping_triplets;    ///< [N·s/m, …]
};

/// @brief The escape hatch for nonlinear mesh cores that are not data (spec 03 tooth-contact
/// core with its tooth bodies, involute contact search, Kim's contact law).
///
/// **Contract.** The core acts on n = num_coordinates() = 12 + num_internal_coordinates()
/// coordinates x = [q_i; q_j; x_int]: the 12 of the two gear bodies (the system builder maps them
/// through the mesh's DOF indices) followed by the core's internal coordinates (e.g. the tooth
/// bodies of spec 03: rotations/translations of each tooth relative to its trunk [rad, m]). The
/// internal coordinates are not DOFs of the SystemModel: only time-domain analyses integrate
/// them (appended after the system DOFs, mesh by mesh), with the mass InternalMass() adds;
/// analyses that need a linear operator (modes, Floquet, harmonic balance) refuse such cores.
///
/// The core is called ONCE per state evaluation with all its teeth batched (architecture §3.4:
/// no virtual call per tooth, θ-sample or harmonic), from one thread per workspace. CalcForces
/// checks the sizes, then calls DoCalcForces; the implementation must not allocate after
/// MakeWorkspace()/MakeOutput().
///
/// **Mesh phase.** θ [rad] advances by 2π per mesh cycle; θ̇ [rad/s] is its rate (the mesh
/// frequency in rad/s at constant speed). The nominal rotation of the pinion is θ/z_i, of the
/// gear ∓θ/z_j (the core knows its tooth counts); the coordinates x are deviations from it.
class NonlinearMeshCore {
 public:
  NonlinearMeshCore() = default;
  virtual ~NonlinearMeshCore() = default;
  NonlinearMeshCore(const NonlinearMeshCore&) = delete;
  NonlinearMeshCore& operator=(const NonlinearMeshCore&) = delete;

  /// n = 12 + num_internal_coordinates(), the number of coordinates the core reads and loads.
  virtual int num_coordinates() const = 0;
  /// Number of internal coordinates (after the 12 of the two bodies); 0 by default.
  virtual int num_internal_coordinates() const { return 0; }
  /// P: the core's forces are periodic in θ with period 2π·P (1 unless teeth differ).
  virtual std::int64_t period_meshes() const { return 1; }
  /// @brief P_S: the symmetry period [mesh cycles], a divisor of period_meshes(). The core's
  /// equations are equivariant under advancing θ by 2π·P_S together with the relabelling S of
  /// the internal coordinates (ApplySymmetryShift): f(S x, S v, θ + 2π P_S) = S f(x, v, θ) on
  /// the internal block, the 12 body forces unchanged, and S keeps InternalMass() (Sᵀ M S = M).
  /// A steady periodic response then satisfies x_int(θ + 2π P_S) = S x_int(θ), so a steady-state
  /// test may compare the state after P_S mesh cycles with the shifted state before them instead
  /// of waiting for the full period P (e.g. identical tooth bodies: P = lcm(z1, z2), P_S = 1, S
  /// "tooth k → k + 1"). Default: P_S = P with S the identity (no symmetry claimed).
  virtual std::int64_t symmetry_period_meshes() const { return period_meshes(); }
  /// @brief Applies S of one symmetry period in place to the internal coordinates (or their
  /// rates) y = x_int (num_internal_coordinates()): y ← S y, where S maps the state at θ to the
  /// state the steady response has at θ + 2π·P_S. S must be a permutation of the coordinates (an
  /// orthogonal map; applied count times for count symmetry periods). Identity by default.
  /// No allocation.
  virtual void ApplySymmetryShift(Eigen::Ref<VectorX> internal) const { (void)internal; }
  /// A fresh per-thread workspace.
  virtual std::unique_ptr<NonlinearMeshCoreWorkspace> MakeWorkspace() const = 0;
  /// @brief The mass the core adds on its coordinates x (n×n, symmetric) [kg, kg·m, kg·m²]: the
  /// internal block and its coupling to the 12 body coordinates (and, when the core takes mass
  /// out of a body, e.g. the teeth out of a gear trunk, a negative correction of the 12×12 block).
  /// The system mass plus this stays positive definite. Zero by default.
  virtual MatrixX InternalMass() const {
    return MatrixX::Zero(num_coordinates(), num_coordinates());
  }
  /// Number of switching functions (NonlinearMeshCoreOutput::switching); 0 by default.
  virtual int num_switching_functions() const { return 0; }
  /// Names (with units) of the diagnostic channels CalcForces writes to out->channels; none by
  /// default.
  virtual std::vector<std::string> channel_names() const { return {}; }

  /// An output sized for this core (force n, stiffness and damping n×n, channels, zero).
  NonlinearMeshCoreOutput MakeOutput() const;

  /// @brief Forces (and optionally their Jacobians) at one state.
  /// @param[in,out] ws workspace from MakeWorkspace().
  /// @param[in] theta mesh phase θ [rad]. @param[in] theta_rate θ̇ [rad/s].
  /// @param[in] x (n) coordinates [m, rad]. @param[in] v (n) velocities [m/s, rad/s].
  /// @param[in] with_jacobians fill out->stiffness and out->damping too.
  /// @param[out] out from MakeOutput() (not resized).
  /// @throws InvalidInput naming theta, theta_rate, x, v or out when non-finite or a size
  ///   differs from n.
  void CalcForces(NonlinearMeshCoreWorkspace& ws, double theta, double theta_rate,
                  const Eigen::Ref<const VectorX>& x, const Eigen::Ref<const VectorX>& v,
                  bool with_jacobians, NonlinearMeshCoreOutput* out) const;

 protected:
  /// Implementation of CalcForces; sizes already checked.
  virtual void DoCalcForces(NonlinearMeshCoreWorkspace& ws, double theta, double theta_rate,
                            const Eigen::Ref<const VectorX>& x, const Eigen::Ref<const VectorX>& v,
                            bool with_jacobians, NonlinearMeshCoreOutput* out) const = 0;
};

// ============================================================================ MeshCore

/// @brief A mesh core: the closed set of data forms plus the virtual escape hatch (architecture
/// §3.4). Visit it with overloaded lambdas and no catch-all.
using MeshCore =
    std::variant<LinearMeshCore, SliceMeshCore, std::shared_ptr<const NonlinearMeshCore>>;

/// @brief Classify of a linear core; kNonlinear for the slice and nonlinear cores.
TimeDependence Classify(const MeshCore& core);

/// @brief P of any core (period 2π·P [rad]).
/// @throws InvalidInput for a null NonlinearMeshCore pointer.
std::int64_t PeriodMeshes(const MeshCore& core);

/// @brief P_K of any core: the period of its operator (K2, C2) only, which divides PeriodMeshes.
/// ε (and a slice core's separations, in its all-loaded linearization) enter the load, not the
/// operator: tooth errors give them a hunting period that forces the system without exciting it
/// parametrically. A linear core's stiffness channels' period (1 for a mean-LTI core); a slice
/// core's stiffness period; a NonlinearMeshCore's own period (nothing finer is known).
/// @throws InvalidInput for a null NonlinearMeshCore pointer.
std::int64_t OperatorPeriodMeshes(const MeshCore& core);

}  // namespace geardyn
