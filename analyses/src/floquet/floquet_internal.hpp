/// @file
/// @brief Internal pieces of the Floquet engine (analyses/src/floquet): the scaled first-order
/// system, the monodromy kernels of each method and the multiplier post-processing.
#pragma once

#include <chrono>
#include <complex>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "geardyn/analyses/floquet.hpp"
#include "geardyn/analyses/floquet_system.hpp"
#include "geardyn/common/eigen_types.hpp"
#include "geardyn/system/system_model.hpp"
#include "geardyn/system/system_steps.hpp"

namespace geardyn::internal {

/// @brief A matrix carried as exp(log_scale)·matrix so that long products neither overflow nor
/// underflow (the normalized matrix has max-abs entry 1 after Normalize()).
struct ScaledMatrix {
  MatrixX matrix;
  double log_scale = 0.0;
  /// Divides by the max-abs entry (if nonzero and finite) and adds its log to log_scale.
  void Normalize();
};

/// @brief Φ^power by binary powering with normalization after every product (the hunting
/// period made of identical cycles: O(log power) products).
ScaledMatrix ScaledPower(const ScaledMatrix& base, std::int64_t power, long* products);

/// @brief The scaled, rigid-deflated first-order system ż = A(t) z of a PeriodicSecondOrderSystem
/// (floquet_system.hpp, steps 1–2).
struct StateSystem {
  int num_dofs = 0;       ///< n of the original system
  int num_rigid = 0;      ///< r deflated rigid-body modes
  int dim = 0;            ///< 2(n − r)
  double period_s = 0.0;  ///< T [s]
  double omega_s = 1.0;   ///< ω_s [1/s]
  MatrixX basis;          ///< B = F L⁻ᵀ (n × (n−r)): q = R a + B y
  MatrixX rigid;          ///< R (n × r)
  MatrixX rigid_inverse;  ///< (RᵀMR)⁻¹RᵀM (r × n): a = rigid_inverse · q
  MatrixX basis_inverse;  ///< L⁻¹FᵀM ((n−r) × n): y = basis_inverse · q

  std::vector<double> step_durations;  ///< piecewise form: Δt_k [s]
  std::vector<MatrixX> step_matrices;  ///< A_k (dim × dim)
  /// Sparse copies of step_matrices (same order) when the change of variables is diagonal (M
  /// diagonal, no rigid mode) and the A_k have ≤ 25 % nonzeros; else empty (kArpackMonodromy's
  /// matrix-free expm action).
  std::vector<SparseMatrix> sparse_step_matrices;
  /// A(t) into *A (dim × dim, sized by the caller); empty when the system has no callback/steps.
  std::function<void(double t, MatrixX* A)> evaluate;
  /// True when every A(t) of `evaluate` has MakeStateSystem's companion form [[0, ω_s I], [X, Y]]
  /// exactly (zero and ω_s·I upper blocks): the Magnus commutators then go by blocks (magnus.cpp).
  bool companion = false;
  /// True when `evaluate` is a verified trigonometric polynomial in t with no kinks
  /// (PreparedFloquet): A(t) is entire, so the Magnus method's asymptotic order is its nominal
  /// one and MagnusMonodromyMeasured skips the order-measuring runs (magnus.cpp).
  bool analytic = false;
  /// Where A(t) is not smooth [s]: sorted, distinct, in (0, T) (0 and T are always step ends);
  /// from PeriodicSecondOrderSystem::kinks_s and the step starts (MagnusGrid).
  std::vector<double> kinks;
  /// Hill: A_m, m = 0 … N (dim × dim), A(t) = Σ A_m e^{imΩt}.
  std::vector<MatrixXc> harmonics;
  std::vector<std::string> warnings;

  /// Maps a monodromy of z to the monodromy of x = [q; q̇] (2n × 2n), rigid block included.
  MatrixX ToOriginalMonodromy(const MatrixX& phi_z) const;
};

/// @brief Builds the StateSystem (validates the system; throws InvalidInput).
StateSystem MakeStateSystem(const PeriodicSecondOrderSystem& system, bool deflate_rigid);

/// Longest common period of meshes at different frequencies Floquet integrates over [mesh
/// cycles of the first mesh]: the monodromy's cost grows with it.
inline constexpr std::int64_t kMaxFloquetCommonPeriodMeshes = 10000;

/// @brief The period of the Floquet problem [mesh cycles]: the operator period P_K
/// (OperatorPeriodMeshes) with one mesh frequency; with several (a two-stage train), the common
/// period over which every mesh's phase returns (FindCommonPeriodMeshes, common_period.hpp:
/// r = 7/40 → 40 cycles), 0 when there is none up to kMaxFloquetCommonPeriodMeshes (the model is
/// then refused by CheckFloquetModel). A period of the full coefficients: with tooth errors it may
/// be a multiple of the operator's own, which changes the work but not the verdict.
std::int64_t FloquetPeriodMeshes(const SystemModel& model);

/// @brief ComputeFloquet's answer for incommensurate frequencies (floquet.hpp): the last three
/// approximants within options.max_approximant_period_meshes, each an ordinary ComputeFloquet.
/// `ratios_text` names the meshes and ratios for the messages.
/// @throws InvalidInput when fewer than two approximants fit the bound.
FloquetResult ComputeApproximantFloquet(const SystemModel& model, const FloquetOptions& options,
                                        const std::string& ratios_text);

/// @brief The step structure of K and C over one operator period 2π·P_K (CollectSystemSteps
/// truncated to [0, 2π·P_K)).
SystemSteps OperatorSteps(const SystemModel& model, std::int64_t operator_period);

/// @brief The automatic kModalProjection basis (model_floquet.cpp): the modes of the mean system
/// below 2.25 f_m, those with ≥ 5 % of their strain energy in a mesh, and those that decay over
/// one period no faster than the slowest-decaying of these (an undamped mode anywhere), in
/// frequency order, then the others in frequency order (the enlarged bases of the estimate).
struct MeshDrivenBasis {
  MatrixX modes;           ///< (n × m) M-orthonormal, priority modes first
  VectorX frequencies_hz;  ///< (m) natural frequency of each column of `modes` [Hz]
  int num_priority = 0;    ///< the first basis size m₀ (at least min(12, m))
};
inline constexpr int kMaxBasisModes = 1500;        ///< modes computed for the selection
inline constexpr double kBasisResonanceOrder = 3;  ///< k_max of f_m = 2 f_p / k
inline constexpr double kBasisFrequencyMargin = 1.5;
inline constexpr double kMeshStrainShare = 0.05;
MeshDrivenBasis SelectMeshDrivenBasis(const SystemModel& model, double mesh_frequency_hz);

/// @brief The next basis size of the modal projection's estimate: ⌈1.5m⌉ (at least m + 1), at
/// most n.
int NextBasisSize(int m, int num_dofs);

/// @brief kAuto's cost model (model_floquet.cpp): the work of one Magnus run on `dofs` DOFs
/// whose highest natural frequency is f_max [Hz] over the period T [s]: steps × (2·dofs)³ with
/// steps = max(8, 2·2π f_max T) (h‖A‖ ≤ 1, ‖A‖ ≈ 2ω_max in the scaled modal state) [flop-like
/// units; only ratios are used].
double MagnusWork(double f_max_hz, double period_s, int dofs);
/// kAuto projects when the three bases of the estimate cost less than 1/kProjectionWorkMargin of
/// the full Magnus run (room for one widening of the basis, ≈ 3.4× the work, and the modes).
inline constexpr double kProjectionWorkMargin = 4.0;

/// @brief kAuto's method for `model` (see floquet.hpp); when it is kModalProjection and `basis`
/// is not null, *basis receives the automatic basis (computed for the decision anyway).
FloquetMethod SelectFloquetMethod(const SystemModel& model, const FloquetOptions& options,
                                  MeshDrivenBasis* basis);

/// @brief The method SelectFloquetMethod returns whatever the mesh frequency, or nullopt when
/// kAuto decides by the frequency-dependent cost of a modal projection (model_floquet.cpp).
std::optional<FloquetMethod> FrequencyIndependentMethod(const SystemModel& model,
                                                        const FloquetOptions& options);

/// @brief The model (projected on V if nonempty) as a generic system over the operator period
/// with the forms `method` needs (steps, coefficients callback, Hill harmonics) at ω_m [rad/s].
PeriodicSecondOrderSystem MakeModelSystem(const SystemModel& model, double omega_m,
                                          FloquetMethod method, int hill_harmonics,
                                          const MatrixX& V);

/// @brief One block (or the whole model) of ComputeFloquet(model): the method selection, then
/// the generic engine (model_floquet.cpp).
FloquetResult ComputeModelFloquet(const SystemModel& model, const FloquetOptions& options);

/// @brief ComputeFloquet(model)'s merge of the results of the decoupled DOF blocks
/// (parts[b] of model.RestrictToBlock(b), every block): the union of the multipliers, the
/// largest estimate, the summed counters, the combined verdict.
FloquetResult CombineBlockResults(const SystemModel& model, const FloquetOptions& options,
                                  const std::vector<FloquetResult>& parts);

/// @brief ComputeFloquet(model)'s checks of the options and the model (throws InvalidInput);
/// returns the model's warnings (slice cores linearized).
/// "mesh 'sun-planet_1' and 5 more at 0.175; …": the meshes at a ratio other than 1, one entry
/// per distinct ratio (at most four), for messages.
std::string MeshRatiosText(const SystemModel& model);
std::vector<std::string> CheckFloquetModel(const SystemModel& model, const FloquetOptions& options);

/// @brief ComputeFloquet(model)'s last step: the undamped-mode list of a marginal verdict, the
/// warnings, P_K, T and the wall time since `start`.
void FinishModelFloquet(const SystemModel& model, const FloquetOptions& options,
                        const std::vector<std::string>& warnings,
                        const std::chrono::steady_clock::time_point& start, FloquetResult* result);

/// At most this many modes are searched for UndampedModes [-].
inline constexpr int kMaxUndampedModesListed = 60;
/// @brief The modes of the mean system with ζ = φᵀC̄φ/(2ω) < 1e-9 (rigid modes excluded), for a
/// marginal verdict (model_floquet.cpp). Empty when the modal analysis fails.
std::vector<UndampedMode> UndampedModes(const SystemModel& model);

/// Largest Hill matrix dim·(2H+1) [-]: a complex eigen solve with vectors of this size takes
/// ≈ 1 s (docs/benchmarks.md "Floquet").
inline constexpr long kMaxHillSize = 800;
/// @brief Throws InvalidInput naming hill_harmonics (requested H) or the method, with the size,
/// memory and flop count, when dim·(2H+1) > kMaxHillSize.
void CheckHillSize(int dim, int harmonics, bool requested);

/// @brief What a monodromy kernel returns.
struct MonodromyOutcome {
  ScaledMatrix phi;  ///< Φ(T) of z
  /// Estimated relative error of Φ (‖δΦ‖/‖Φ‖, Frobenius) from truncation; the multiplier error
  /// follows from it in SpectrumOf.
  double truncation_error = 0.0;
  double num_factors = 0.0;  ///< products/steps for the round-off estimate
  long evaluations = 0;      ///< A(t) evaluations
  long steps = 0;            ///< expm factors or accepted ODE steps
  bool converged = true;
  std::string message;
};

/// @brief The steps of `sys` with consecutive equal step matrices merged: durations dt, the
/// matrices A (pointers into sys.step_matrices) and the index of each merged step's first step.
struct MergedSteps {
  std::vector<double> dt;
  std::vector<const MatrixX*> A;
  std::vector<int> index;
};
MergedSteps MergeEqualSteps(const StateSystem& sys);
/// @brief Round-off of the step product Π_{k<d} expm(A_k Δt_k), in units of ε‖Φ‖ (the num_factors
/// of SpectrumOf): d products plus Σ_k ‖A_k Δt_k‖₁, since scaling and squaring loses about
/// ε‖AΔt‖ per exponential (2^s squarings with ‖AΔt‖/2^s ≈ 5.4). At low speed ‖A‖T reaches 10⁵–10⁶
/// and that term dominates (issue 12: the rig at f_m = 0.2 Hz read max|λ| = 1 + 6e-12 against an
/// estimate of 1.5e-13 and said "unstable"; the extended-precision product gives 1 + 1e-14).
double StepProductFactors(const MergedSteps& merged, int d);

/// @brief kExactSteps: Π expm(A_k Δt_k), consecutive equal steps merged, a repeating pattern
/// raised to its power by squaring.
MonodromyOutcome ExactStepsMonodromy(const StateSystem& sys);
/// @brief The step ends t_1 < … < t_N = T (t_0 = 0 implied) of a Magnus run of about `steps`
/// steps: equal steps T/steps while they are fewer than the smooth pieces between sys.kinks (each
/// step then spans kinks anyway); else every piece [k_j, k_{j+1}) gets max(1, round(steps·w_j/T))
/// equal steps, so that no step straddles a kink and the nominal order holds (issue 12: a
/// 256-sample table stiffness at low speed had observed order 1 and hit the step cap).
std::vector<double> MagnusGrid(const StateSystem& sys, int steps);
/// @brief kMagnus: Gauss–Legendre Magnus of `order` (4, 6) on the MagnusGrid of about `steps`
/// steps (out.steps: the actual count).
MonodromyOutcome MagnusMonodromyFixed(const StateSystem& sys, int order, int steps);
/// @brief One Magnus step exponential expm(Ω) over [t0, t0 + h] (order 4 or 6); adds the A(t)
/// evaluations to *evaluations.
MatrixX MagnusStepPropagator(const StateSystem& sys, int order, double t0, double h,
                             long* evaluations);
/// @brief Smallest d dividing the number of steps with step[i] == step[i + d] for all i (the
/// repeating pattern of a hunting period made of identical mesh cycles).
int RepeatingStepPeriod(const std::vector<double>& dt, const std::vector<const MatrixX*>& A,
                        double period_s);
/// Magnus step counts: at most kMaxMagnusSteps per period, at least kMinMagnusSteps, and h‖A‖₁
/// ≤ kMagnusStepNorm at the start (MagnusStartSteps).
inline constexpr int kMaxMagnusSteps = 1 << 16;
inline constexpr int kMinMagnusSteps = 8;
inline constexpr double kMagnusStepNorm = 1.0;
/// @brief T·max_t ‖A(t)‖₁ [-] (`samples` midpoints of the callback, or every step matrix); adds
/// the evaluations to *evaluations (may be null). NaN when A has NaN entries.
double MaxOperatorNormTimesPeriod(const StateSystem& sys, long* evaluations, int samples = 64);
/// @brief The first Magnus step count: ⌈‖A‖T / kMagnusStepNorm⌉, at least kMinMagnusSteps;
/// kMaxMagnusSteps + 1 when that is above the cap or ‖A‖T is not finite (see magnus.cpp).
int MagnusStartSteps(double norm_times_period);
/// @brief kMagnus with the step count chosen from `tolerance` (Richardson on Φ), starting from
/// MagnusStartSteps and refining past non-finite estimates; not converged (NaN Φ) when the start
/// count exceeds the cap.
MonodromyOutcome MagnusMonodromy(const StateSystem& sys, int order, double tolerance);
/// @brief kMagnus with the measured-order step control (FloquetOptions::magnus_measured_order;
/// magnus.cpp has the rules): counts from ⌈‖A‖T/2π⌉ (at least kMinMeasuredSteps), the estimate
/// with the order of the last three runs, accepted only inside the series' radius.
MonodromyOutcome MagnusMonodromyMeasured(const StateSystem& sys, int order, double tolerance);
/// Smallest first count of MagnusMonodromyMeasured [-].
inline constexpr int kMinMeasuredSteps = 2;
/// @brief The observed convergence order [-] from the differences d₀ (runs N₀, N₁) and d₁ (N₁,
/// N₂), clamped to [1, order]; 1 when d₀ is unknown (first comparison) or not usable.
double ObservedOrder(double previous_difference, double difference, int n0, int n1, int order);
/// @brief The observed order [-] from three runs n0 < n1 < n2 (any ratios): d01 = ‖Φ(n1) −
/// Φ(n0)‖, d12 = ‖Φ(n2) − Φ(n1)‖, fitted to e(N) = C N^−q, clamped to [1, order]; 1 when a
/// difference is not positive or the counts are not increasing.
double ObservedOrderOfThree(double d01, double d12, long n0, long n1, long n2, int order);
/// @brief kOdeStepper: GSL rk8pd on the fundamental matrix, two tolerances.
MonodromyOutcome OdeMonodromy(const StateSystem& sys, double tolerance);

/// @brief Multipliers and their estimated absolute errors from a scaled monodromy.
struct Spectrum {
  VectorXc multipliers;  ///< sorted by |λ| descending (finite unless they overflow double)
  VectorXc exponents;    ///< μ = ln(λ)/T [1/s]
  double roundoff = 0.0;
  std::string failure;  ///< non-empty when Φ was not finite or the eigen solver failed (NaN λ)
};
/// @brief Eigenvalues of phi with the round-off estimate (see floquet_system.hpp).
/// `matrix_error`: relative truncation error of Φ added to the round-off δ.
Spectrum SpectrumOf(const ScaledMatrix& phi, double period_s, double num_factors,
                    double matrix_error = 0.0);
/// ‖a − b‖/‖b‖ of two scaled matrices (Frobenius).
double RelativeDifference(const ScaledMatrix& a, const ScaledMatrix& b);

/// @brief kHill result on the StateSystem (selected exponents, error estimate H vs 3H/2).
struct HillOutcome {
  VectorXc exponents;  ///< selected μ (dim) [1/s]
  double truncation_error = 0.0;
  int harmonics = 0;
  bool converged = true;
  std::string message;
};
HillOutcome HillExponents(const StateSystem& sys, int harmonics, double tolerance);

/// @brief Greatest distance between matched multipliers (greedy nearest matching of each of a
/// to a distinct one of b; a.size() ≤ b.size()).
double MatchedDistance(const VectorXc& a, const VectorXc& b);

/// @brief Sorts λ by |λ| descending (ties by argument) and fills exponents.
void SortSpectrum(VectorXc* multipliers, VectorXc* exponents);

/// max(a, b), NaN when either is NaN (std::max drops a NaN second argument).
double MaxPropagatingNaN(double a, double b);
/// max|v_i| with NaN propagated (0 for an empty vector).
double MaxAbsOf(const VectorXc& values);

/// |λ| within this of 1 (or the error estimate, if larger) counts as on the unit circle [-].
inline constexpr double kMarginalFloor = 1e-12;

/// @brief The verdict rules of FloquetVerdict (floquet.hpp) for these multipliers, exponents and
/// summary (status, error_estimate); `why` (optional) says why it is undetermined.
FloquetVerdict DecideVerdict(const Summary& summary, const VectorXc& multipliers,
                             const VectorXc& exponents, std::string* why);
/// The verdict of decoupled blocks: unstable if one is, else undetermined if one is, else stable.
FloquetVerdict CombineVerdicts(FloquetVerdict a, FloquetVerdict b);
/// The multipliers other than exactly 1 + 0i (the rigid-body ones appended by FinishResult).
VectorXc WithoutRigid(const VectorXc& multipliers);
/// Stable with a flexible multiplier within max(error_estimate, kMarginalFloor) of |λ| = 1.
bool IsMarginal(FloquetVerdict verdict, const VectorXc& flexible, double error_estimate);
/// @brief Re-decides the verdict (with a warning when undetermined) and the marginal flag of a
/// finished result after its summary changed (the modal projections' tolerance decisions).
void RedecideVerdict(FloquetResult* result);
/// @brief Floquet of a modally reduced system by the generic engine (the method SelectGenericMethod
/// picks), its method recorded in summary.counters["inner_method"].
FloquetResult ComputeReducedFloquet(const PeriodicSecondOrderSystem& reduced,
                                    const FloquetOptions& inner);

/// @brief Fills max|λ| (NaN-propagating), margin, verdict and the marginal flag from the
/// multipliers, exponents and summary, after appending the 2r rigid multipliers 1 (sorted); the
/// marginal flag looks at the flexible multipliers only (a rigid mode is neutral by nature).
void FinishResult(int num_rigid, double tolerance, FloquetResult* result);

/// @brief The generic engine on a StateSystem (no modal projection, no block split).
FloquetResult ComputeFloquetState(const StateSystem& sys, const FloquetOptions& options,
                                  FloquetMethod method);

/// @brief kArpackMonodromy on a StateSystem (floquet.hpp): the arpack_nev largest-|λ|
/// multipliers of the matrix-free monodromy operator.
FloquetResult ArpackMonodromyFloquet(const StateSystem& sys, const FloquetOptions& options);

/// @brief kAuto on a generic system (see floquet_system.hpp).
FloquetMethod SelectGenericMethod(const PeriodicSecondOrderSystem& system,
                                  const FloquetOptions& options);

/// @brief Projects a generic system on the M-orthonormal basis V (n × m): M_r = VᵀMV, K_r, C_r.
PeriodicSecondOrderSystem ProjectSystem(const PeriodicSecondOrderSystem& system, const MatrixX& V);

/// @brief kModalProjection; `modes(m)` returns the first m M-orthonormal modes (n × m') of the
/// basis of the mean system. Runs m, ⌈1.5m⌉ and ⌈2.25m⌉ modes (see modal_projection.cpp for the
/// estimate); m = options.num_modes, else `initial_modes`, else 12.
FloquetResult ModalProjectionFloquet(
    const std::function<MatrixX(int)>& modes, int num_dofs,
    const std::function<PeriodicSecondOrderSystem(const MatrixX&)>& project,
    const FloquetOptions& options, int initial_modes = 0);

/// kAuto accepts a modal projection whose estimate e of max|λ| is above the tolerance when
/// e ≤ kAutoProjectionMaxEstimate and |1 − max|λ_flex|| > kAutoVerdictSafety·e: the verdict is
/// the same for every value within ten estimates. The cap: the difference-based truncation
/// estimate (factor 4, modal_projection.cpp) was calibrated on changes of 1e-4 and below.
inline constexpr double kAutoProjectionMaxEstimate = 1e-4;
inline constexpr double kAutoVerdictSafety = 10.0;
/// The inner (Magnus) error target of kAuto's projection runs is kAutoInnerToleranceFactor ·
/// max(tolerance, kAutoProjectionAccuracy) on Φ [-]: 1e-8 for the CLI's 1e-10 and the charts'
/// 1e-6, well below the truncation estimates (1e-7 … 1e-5 on builtin:geared-shafts).
inline constexpr double kAutoProjectionAccuracy = 1e-6;
inline constexpr double kAutoInnerToleranceFactor = 1e-2;

/// @brief kAuto's modal projection (auto_projection.cpp): bases m, ⌈1.5m⌉, ⌈2.25m⌉ widened until
/// the estimate e of max|λ| (truncation: 4× the largest change of the flexible max|λ| between the
/// bases; plus the inner method's) meets the tolerance, or e ≤ kAutoProjectionMaxEstimate and
/// |1 − max|λ_flex|| > kAutoVerdictSafety·e; `full()` (the unprojected system) when the check basis
/// would hold all n modes. `modes`/`project` as for ModalProjectionFloquet.
FloquetResult AutoModalProjectionFloquet(
    const std::function<MatrixX(int)>& modes, int num_dofs,
    const std::function<PeriodicSecondOrderSystem(const MatrixX&)>& project,
    const std::function<FloquetResult()>& full, const FloquetOptions& options, int initial_modes);

/// `value` with 3 significant digits ("1.23e-09", "inf", "nan") for messages (std::to_string
/// prints 1e-9 as "0.000000").
std::string FormatEstimate(double value);

/// Seconds since `start` (steady clock).
double SecondsSince(const std::chrono::steady_clock::time_point& start);

}  // namespace geardyn::internal
