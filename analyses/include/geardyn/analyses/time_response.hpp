/// @file
/// @brief Time integration of an assembled gear system (issue 14, spec 03 "Outputs and runs"):
/// one speed to steady state, stepped up/down sweeps over mesh frequency, independent speeds in
/// parallel, and the static equilibrium to start from — the engine of `geardyn simulate`.
///
/// **Equation** (the model harmonic balance solves, with the internal coordinates of nonlinear
/// cores appended). State y = [x; v], x = [q (num_dofs); x_int (Σ internal coordinates, mesh by
/// mesh)], θ = θ₀ + ω_m t, θ_k = r_k θ + φ_k:
/// \f[ M\ddot x + C_0 \dot x + K_0 x + \sum_k f_k(x, \dot x, θ_k, \dot θ_k) = f_0 + f_h(θ), \f]
/// f_h(θ) = Σ_l Re(F_l e^{i m_l θ}) the harmonic loads (SystemHarmonicLoad),
/// with M = system mass + every core's InternalMass() and, per mesh core form,
/// * LinearMeshCore: f_k = P_kᵀ G_kᵀ [K2(θ_k)(δ − ε(θ_k)) + C2(θ_k) δ̇] (B–S Eq. 39) — the LTV
///   model the linear HB solves (workspace.hpp kernels);
/// * SliceMeshCore: f_k = P_kᵀ G_kᵀ F_slice(δ, θ_k) + P_kᵀ C̄2_k P_k δ̇ with C̄2_k the θ-mean of
///   the all-loaded mesh damping — exactly the nonlinear HB's equation (system_nonlinear_hb.hpp:
///   the mesh damper acts also while the teeth separate);
/// * NonlinearMeshCore: −force of CalcForces on [q_i; q_j; x_int].
///
/// **Integrators** (TimeIntegrator; the selection rule of kAuto is in TimeIntegrationOptions):
/// * kGeneralizedAlpha — Chung & Hulbert (1993) generalized-α with spectral radius ρ∞, Newton
///   with the analytic tangent (dense LU below `sparse_threshold` coordinates, SparseLU above),
///   adaptive step from the local error estimate of Zienkiewicz & Xie (1991); second order;
/// * kRungeKutta — GSL gsl_odeiv2 rk8pd (Prince–Dormand 8(7)) single steps with this module's
///   step control.
/// Both locate contact switches: the switching functions (the cores' `switching`, and for slice
/// cores the slice gaps a_s and a_s + j where k_s > 0) are watched at every accepted step; a sign
/// change inside a step is located by Illinois regula falsi on re-steps to
/// `event_time_tolerance` and the integration restarts there. Jumps of piecewise-constant
/// coefficients and the nodes of table coefficients are phase events: steps end there (the
/// energy jump of a stepwise stiffness is booked as phase work).
///
/// **Energy balance** per integrated period: input work W = f₀ᵀΔx + ∫(ΣP_k + f_hᵀv) dt, stored
/// change ΔS = Δ(T + V₀ + ΣE_k), dissipation D = ∫(vᵀC₀v + ΣD_k) dt (D_k, P_k of the mesh forces:
/// for linear/slice cores the damper power and the phase power ∂E_k/∂θ·θ̇), integrated with the
/// solution (two extra ODE states on the Runge–Kutta path; on the generalized-α path the rule on
/// the nodes 0, α-point, 1 exact for quadratics). Relative error |W − ΔS − D| / max(|W|, D, |ΔS|,
/// 1e-3·G, 1e-9·|S|), G the gross flow: the energy the period's steps moved (Σ |phase work| + D
/// of each step, + |jump| at each break). The quadrature errs by a small fraction of G, not of
/// the net flows; at quasi-static speeds W ≈ D ≈ 3e-8·G per period, and a quadrature error of
/// 2e-9·G read as 7 % of D (issue 16). The floor 1e-3·G sets the check's resolution (a warning
/// at 1e-4 of the scale: 1e-7 of G); in dynamic runs D ≫ 1e-3·G (the pair near resonance with a
/// 20 % stiffness variation under load: G ≈ 47 D) and the floor is inactive. It measures the
/// integration error: ≲ 1e-9 for rk8pd, O(tol^{2/3}) for generalized-α (its numerical damping
/// included for ρ∞ < 1); a summary warning above 1e-4.
///
/// **Quasi-static run** (SimulateQuasiStatic): the static equilibrium at every θ sample with the
/// loaded static TE, the tangent mesh stiffness (K, K·h, K·μ·b²), the mesh force pair and the LTV
/// transmission error per mesh — what `[mesh.parameters]` needs — sampled on the system phase or
/// on each mesh's own cycle, with a continuation where the flanks start apart.
///
/// **Results.** Every run returns what it computed so far even when it fails or is cancelled
/// (Summary status + message; the library never prints). No verdict (steady) without a clean
/// status: `steady` is three-valued through SteadyVerdict.
///
/// Reentrant; the speeds of SimulateSpeeds run in parallel with OpenMP (one workspace per
/// thread).
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "geardyn/common/eigen_types.hpp"
#include "geardyn/common/summary.hpp"
#include "geardyn/system/system_model.hpp"

namespace geardyn {

/// Number of coordinates (system DOF + internal) from which the implicit integrator uses sparse
/// factorizations.
inline constexpr int kSparseStateThreshold = 200;

/// kAuto's quasi-static threshold on ω_max·Δt_acc (TimeIntegrationOptions::integrator).
inline constexpr double kAutoQuasiStaticStiffness = 1e4;

/// @brief The integration method.
enum class TimeIntegrator {
  kAuto,              ///< chosen per run by the stiffness rule (TimeIntegrationOptions)
  kGeneralizedAlpha,  ///< implicit, Chung–Hulbert generalized-α, Newton, adaptive step
  kRungeKutta,        ///< explicit, GSL rk8pd, adaptive step
};
/// "auto", "generalized_alpha", "runge_kutta".
const char* ToString(TimeIntegrator integrator);
/// Parses ToString's names; false on an unknown name.
bool ParseTimeIntegrator(const std::string& name, TimeIntegrator* out);

/// @brief Options of one integration (shared by every run kind).
struct TimeIntegrationOptions {
  /// Method. kAuto: with ω_max the highest undamped natural frequency of the mean linear system
  /// [rad/s] and Δt_acc = mesh period / samples_per_period, the explicit kRungeKutta when
  /// ω_max·Δt_acc < auto_stiffness_limit (its stable step is not far below the accuracy step),
  /// otherwise kGeneralizedAlpha (stiff: tooth bodies, stiff bearings). Beyond
  /// ω_max·Δt_acc > kAutoQuasiStaticStiffness (quasi-static speeds: the highest mode is not
  /// resolved by many orders) kAuto runs generalized-α with ρ∞ = 0 instead of spectral_radius:
  /// with ρ∞ near 1 the spurious root of the unresolved modes decays only by ρ∞ per step and its
  /// acceleration swamps the local error estimate (issue 16: 1e-3 Hz on a 4.6 kHz pair took
  /// 7e5 steps per period and never settled; with ρ∞ = 0, 1.2e4). Counter "auto_rho_zero".
  TimeIntegrator integrator = TimeIntegrator::kAuto;
  double auto_stiffness_limit = 50.0;  ///< kAuto threshold on ω_max·Δt_acc [-], in (0, 1e6]
  /// Local relative error tolerance per step [-], in [1e-14, 1e-2].
  double relative_tolerance = 1e-8;
  /// Absolute error scale of coordinates, as a fraction of max |static deflection| (or of 1e-6
  /// m when that is zero) [-], in [1e-14, 1].
  double absolute_tolerance = 1e-8;
  double spectral_radius = 0.9;  ///< ρ∞ of generalized-α [-], in [0, 1]
  /// Newton of generalized-α stops when its update, measured in units of the local error
  /// tolerance (the step-control scale), is below this [-], in [1e-10, 0.5].
  double newton_tolerance = 1e-3;
  int max_newton_iterations = 12;  ///< per step, in [1, 100]
  /// Largest step as a fraction of the mesh period [-], in (0, 1].
  double max_step_fraction = 0.05;
  /// Limit on the steps of one run (all periods), in [1, 1e9]; exceeded → kNotConverged.
  long max_steps = 100000000;
  bool locate_events = true;  ///< locate switching-function zeros (false: step over them)
  /// Time tolerance of event location, as a fraction of the mesh period [-], in [1e-14, 1e-2].
  double event_time_tolerance = 1e-9;
  /// Output samples per mesh period of the recorded periods, in [4, 65536].
  int samples_per_period = 64;
  /// Keep every `channel_decimation`-th sample of the cores' channel histories, in [1, 65536].
  int channel_decimation = 1;
  bool record_element_forces = true;  ///< per-element force histories
  /// Coordinates (system DOF + internal) from which generalized-α factors its iteration matrix
  /// with Eigen's SparseLU instead of a dense LU, in [1, 1e7].
  int sparse_threshold = kSparseStateThreshold;
  /// False (with the field, value and bound in `why`) on an invalid value.
  bool IsValid(std::string* why) const;
};

/// @brief Steady-state detection: the response is steady when, for `consecutive_periods`
/// periods in a row, the change from one period to the next of the state at the period start
/// (max-norm, rigid-body motion projected out: ‖Δx‖/‖x‖ and ‖Δv‖/max(‖v‖, ω_m‖x‖)) and of the
/// DTE RMS of every mesh (relative to max(RMS, 1e-6·|mean DTE|)) is below `tolerance`. A
/// response whose max |DTE| grows beyond 1e4 × its first period's ends the run (kNotConverged,
/// "grows without bound").
///
/// **Period** (TimeResponse::period_meshes): period_multiple × P_S mesh cycles. P_S is the
/// symmetry period of the cores (NonlinearMeshCore::symmetry_period_meshes; with identical tooth
/// bodies 1 instead of the hunting period lcm(z1, z2)) and Δx = x(end) − S x(start) with S the
/// cores' relabelling of their internal coordinates over the period (tooth k → k + 1): the steady
/// response satisfies x(t + T) = S x(t). Several meshes: P_S is the smallest multiple of the
/// cores' symmetry periods that is a whole number of each mesh's own (phase ratios r_k), below
/// the model's period P; otherwise (or with use_symmetry false) P with S the identity.
struct SteadyStateOptions {
  double tolerance = 1e-6;      ///< relative period-to-period change [-], in [1e-14, 1]
  int consecutive_periods = 3;  ///< k, in [1, 1000]
  int min_periods = 2;          ///< periods always integrated before a test, in [0, 1e7]
  int max_periods = 3000;       ///< limit: ends with kNotConverged, in [1, 1e7]
  /// The period is period_multiple × P mesh cycles (P the model's hunting period), in [1, 1000]
  /// (2 for a period-doubled response).
  int period_multiple = 1;
  int record_periods = 1;  ///< periods recorded after steady state, in [1, 1000]
  /// Use the cores' symmetry (period P_S with the shift S); false: the full period P, S = I.
  bool use_symmetry = true;
  /// False (with the field, value and bound in `why`) on an invalid value.
  bool IsValid(std::string* why) const;
};

/// Three-valued steady-state verdict: kUndetermined whenever the run failed or ended without
/// meeting the criterion (status kNotConverged); kNotSteady is reserved (not produced yet).
enum class SteadyVerdict { kSteady, kNotSteady, kUndetermined };
/// "steady", "not_steady", "undetermined".
const char* ToString(SteadyVerdict verdict);

/// @brief Progress of a run: fraction in [0, 1] and a short note; called from the calling thread
/// only (SimulateSpeeds: from the thread that started it, between speeds).
using TimeProgress = std::function<void(double fraction, const std::string& note)>;

/// @brief Energy balance of one period (see the @file).
struct EnergyBalancePeriod {
  double input_work = 0.0;     ///< W [J]
  double stored_change = 0.0;  ///< ΔS [J]
  double dissipated = 0.0;     ///< D [J]
  /// G: the energy the steps moved, Σ(|∫P dt| + ∫D dt) over the steps + |jumps| at breaks [J]
  double gross_flow = 0.0;
  double relative_error = 0.0;  ///< |W − ΔS − D| / max(|W|, |ΔS|, D, 1e-3·G, 1e-9·|S|) [-]
};

/// @brief Histories and statistics of one mesh over the recorded periods.
struct MeshTimeHistory {
  std::string name;
  VectorX dte;                    ///< (samples) DTE = δ_η − ε_η (probes.hpp) [m]
  VectorX force;                  ///< (samples) F_η (elastic + damping) [N]; empty for nonlinear
  double mean_dte = 0.0;          ///< [m]
  double rms_dte = 0.0;           ///< RMS of DTE − mean [m]
  double peak_to_peak_dte = 0.0;  ///< [m]
  /// Fraction of the samples without drive-flank contact (slice: no slice loaded; nonlinear:
  /// num_contacts == 0; linear: 0).
  double contact_loss_fraction = 0.0;
  std::vector<std::string> channel_names;  ///< nonlinear cores' channel names (with units)
  MatrixX channels;  ///< (channels × decimated samples), nonlinear cores only
};

/// @brief The response at one mesh frequency.
struct TimeResponse {
  double mesh_frequency_hz = 0.0;  ///< f_m [Hz]
  TimeIntegrator integrator_used = TimeIntegrator::kAuto;
  VectorX time;                         ///< (samples) of the recorded periods [s]
  std::vector<MeshTimeHistory> meshes;  ///< per mesh, in model order
  /// Per element, (6 or 12 × samples) f_e = K_e q_e + C_e q̇_e (probes.hpp convention) [N, N·m];
  /// empty unless record_element_forces.
  std::vector<MatrixX> element_forces;
  std::vector<EnergyBalancePeriod> energy;  ///< one per integrated period (transient included)
  double max_energy_error = 0.0;            ///< max relative_error over `energy` [-]
  int periods = 0;                          ///< periods integrated before recording
  /// Mesh cycles per period (steady test, energy balance, recording): period_multiple × P_S
  /// (SteadyStateOptions). With identical tooth bodies 1: the recorded mesh cycle shows each
  /// tooth channel once, at that tooth's place in the cycle; tooth k's history over the full
  /// hunting period is the recorded cycle's history of tooth k − n at cycle n (the steady
  /// response repeats with the shift S).
  std::int64_t period_meshes = 0;
  SteadyVerdict steady = SteadyVerdict::kUndetermined;
  long steps = 0;   ///< accepted steps
  long events = 0;  ///< located switching events
  /// Final state [x; v] (2·(num_dofs + internal)) and phase θ [rad] to continue from.
  VectorX final_state;
  double final_phase = 0.0;
  /// True when the run failed or was cancelled during the transient and `time` / meshes[k].dte
  /// (and their statistics) are those of the last complete integrated period — not a steady
  /// state (force, channels and element forces empty). Added in session 25 ("qs").
  bool history_from_transient = false;
  /// A run that ended unsteady at max_periods with a decaying transient: the decay factor of the
  /// period-to-period change per period, measured from its maxima over the last two quarters of
  /// the run (in (0, 1); the message estimates the periods needed). 0 otherwise (issue 16).
  double transient_decay_per_period = 0.0;
  Summary summary;
};

/// @brief Options of one run to steady state.
struct TimeResponseOptions {
  TimeIntegrationOptions integration;
  SteadyStateOptions steady;
  /// Start from the static equilibrium at θ₀ (SolveTimeDomainStatic) at rest; otherwise from
  /// `initial_state` (size 2·(num_dofs + internal)).
  bool start_from_static = true;
  /// With start_from_static and only linear meshes (no nonlinear core): start from the periodic
  /// solution of the linear harmonic balance at θ₀ (position and velocity) instead of the static
  /// equilibrium at rest; the static start when the HB fails or the mean system has an
  /// undamped mode (no attracting periodic orbit to start on). A lightly damped mode far below
  /// the mesh frequency decays over ln(1/tolerance)/(ζ ω_n T) periods (≈ 1.3e4 at 1e6 Hz on a
  /// 4.6 kHz pair with ζ = 0.05, issue 16): from the HB state there is (almost) nothing to
  /// decay, and the steady test still checks the integrated periods.
  /// Off by default: on a parametrically unstable LTV system the HB's periodic solution is an
  /// unstable orbit, and a run started exactly on it stays there for hundreds of periods and
  /// passes the steady test — a "steady" verdict on a response that grows without bound
  /// (TimeResponse.ParametricInstabilityEndsWithoutVerdict). Turn it on only where the Floquet
  /// verdict of the system is stable.
  bool start_from_linear_steady_state = false;
  VectorX initial_state;
  double initial_phase = 0.0;  ///< θ₀ [rad]
  /// False (with the field, value and bound in `why`) on an invalid value.
  bool IsValid(std::string* why) const;
};

/// @brief Integrates at mesh frequency f_m [Hz] until steady (see SteadyStateOptions), then
/// records `record_periods` periods.
/// @param[in] cancel optional flag: when it becomes true the run stops with kInterrupted and
///   the message "cancelled", keeping what it has.
/// @throws InvalidInput on f_m ≤ 0 or non-finite, invalid options, a wrong initial-state size,
///   or a model without meshes.
TimeResponse SimulateSteadyState(const SystemModel& model, double mesh_frequency_hz,
                                 const TimeResponseOptions& options,
                                 const TimeProgress& progress = {},
                                 const std::atomic<bool>* cancel = nullptr);

/// @brief Sweep branch.
enum class SweepBranch { kUp, kDown };
/// "up", "down".
const char* ToString(SweepBranch branch);

/// @brief One point of a stepped sweep (statistics of the recorded periods).
struct TimeSweepPoint {
  double mesh_frequency_hz = 0.0;
  SweepBranch branch = SweepBranch::kUp;
  std::vector<double> rms_dte;                ///< per mesh [m]
  std::vector<double> mean_dte;               ///< per mesh [m]
  std::vector<double> peak_to_peak_dte;       ///< per mesh [m]
  std::vector<double> contact_loss_fraction;  ///< per mesh [-]
  int periods = 0;
  SteadyVerdict steady = SteadyVerdict::kUndetermined;
  double max_energy_error = 0.0;
  Status status = Status::kSuccess;
  std::string message;
};

/// @brief Options of a stepped sweep.
struct TimeSweepOptions {
  TimeResponseOptions response;  ///< per point (initial_state/phase: the first point only)
  bool up = true;                ///< run the increasing-frequency branch
  bool down = true;              ///< run the decreasing-frequency branch
  /// False (with the field, value and bound in `why`) on an invalid value.
  bool IsValid(std::string* why) const;
};

/// @brief Result of a stepped sweep: the points of the up branch (increasing f) then of the down
/// branch (decreasing f). A point that is not steady within max_periods is kept with its status
/// (kNotConverged, verdict kUndetermined) and the branch goes on from its last state; a numerical
/// failure ends its branch (the point kept, with its status) and the other branch starts afresh;
/// cancellation ends the sweep. The summary has the worst status and one warning per such point.
struct TimeSweep {
  std::vector<TimeSweepPoint> points;
  Summary summary;  ///< worst status of the points; counters: steps, events, points
};

/// @brief Stepped sweep: each point starts from the final state and phase of the previous one
/// (carried across the speed change), so both branches of a jump are found.
/// @param[in] frequencies_hz mesh frequencies [Hz], each > 0, strictly increasing.
/// @throws InvalidInput on bad frequencies or options.
TimeSweep SimulateSweep(const SystemModel& model, const std::vector<double>& frequencies_hz,
                        const TimeSweepOptions& options, const TimeProgress& progress = {},
                        const std::atomic<bool>* cancel = nullptr);

/// @brief Independent runs at several mesh frequencies, in parallel (OpenMP, at most `threads`
/// threads; 0 = OpenMP's default). Each starts as `options` says.
/// @throws InvalidInput on bad frequencies (each > 0, finite) or options, threads < 0.
std::vector<TimeResponse> SimulateSpeeds(const SystemModel& model,
                                         const std::vector<double>& frequencies_hz,
                                         const TimeResponseOptions& options, int threads = 0,
                                         const TimeProgress& progress = {},
                                         const std::atomic<bool>* cancel = nullptr);

/// @brief The static equilibrium at phase θ₀: K0 x + Σ f_k(x, 0, θ_k) = f0 by Newton with the
/// cores' tangents; rigid-body modes of the mean stiffness handled as SolveStaticDeflection
/// (minimum-norm solution, the unbalanced part of f0 removed with a warning).
struct TimeDomainStatic {
  VectorX state;  ///< x = [q; x_int] [m, rad]
  int iterations = 0;
  Summary summary;
};
/// @throws InvalidInput on a non-finite θ₀ or a model without meshes.
TimeDomainStatic SolveTimeDomainStatic(const SystemModel& model, double theta0 = 0.0);

/// @brief How the quasi-static run samples the phase.
enum class QuasiStaticSampling {
  /// One roll of the system phase θ over period_multiple × P mesh periods, θ_s = 2πPs/S_tot,
  /// shared by every mesh (mesh k at its own phase θ_k = r_k θ_s + φ_k).
  kSystemPhase,
  /// One roll per mesh k over one cycle of its OWN phase, θ_k,s = 2πs/S (system phase
  /// θ = (θ_k,s − φ_k)/r_k): what a `[mesh.parameters]` table of mesh k holds (period_multiple
  /// is not used). Costs S static solves per mesh.
  kMeshCycle,
};

/// @brief Options of the quasi-static (slow-roll) run.
struct QuasiStaticOptions {
  int samples_per_mesh = 64;  ///< θ samples per mesh period, in [1, 65536]
  /// Samples span period_multiple × P mesh periods (P the model's hunting period), in [1, 1000].
  int period_multiple = 1;
  QuasiStaticSampling sampling = QuasiStaticSampling::kSystemPhase;
  /// kMeshCycle: for a mesh whose core has P > 1 (e.g. a contact core counting its teeth apart),
  /// one more static solve one mesh cycle later (θ_k = 2π), compared with the first sample
  /// (QuasiStaticMesh::next_cycle_change).
  bool check_next_cycle = true;
  /// False (with the field, value and bound in `why`) on an invalid value.
  bool IsValid(std::string* why) const;
};

/// @brief The quasi-static quantities of one mesh along θ.
struct QuasiStaticMesh {
  std::string name;
  VectorX loaded_te;  ///< (samples) δ_η at the static equilibrium: the loaded static TE [m]
  VectorX dte;        ///< (samples) δ_η − ε_η (probes.hpp) [m]
  VectorX force;      ///< (samples) F_η [N] (a NonlinearMeshCore: row 0 of force_pair)
  /// (3 × samples) tangent mesh stiffness channels (K, K·h, K·μ·b²) [N/m, N, N·m] with
  /// K2 = [[K, −K·h], [−K·h, K·μ·b²]] = ∂F/∂δ (mesh_core.hpp), for a NonlinearMeshCore its
  /// internal coordinates condensed out and K2 = G⁺ᵀ K₁₂ G⁺ (G⁺ the pseudo-inverse of G) —
  /// what an LTV mesh's [mesh.parameters] tables hold.
  MatrixX stiffness;
  // ---- Added for the [mesh.parameters] export (additive, session 25 "qs"). ----
  VectorX theta;       ///< (samples) system phase θ of each sample [rad]
  VectorX mesh_phase;  ///< (samples) the mesh's own phase θ_k = r_k θ + φ_k [rad]
  /// (2 × samples) the static mesh force pair F = [F_η; M_ζ] [N; N·m] for every core form:
  /// linear and slice cores their own F (EvalMeshProbe / EvalSliceForce at v = 0); a
  /// NonlinearMeshCore the generalized force it puts on the 12 body coordinates, f₁₂, projected
  /// on the mesh deflections, F = −A f₁₂ with A = (G Gᵀ)⁻¹ G — exact when the core acts through
  /// δ = G q (f₁₂ = −Gᵀ F), and statically F_η = T/r_b for a pinion of base radius r_b held by
  /// the mesh alone under torque T (torque balance about its axis). `force` row 0 equals F_η.
  MatrixX force_pair;
  /// (samples) ε_η = δ_η − (K2⁺ F)_η with K2 the symmetric tangent of `stiffness`: the
  /// transmission error of an LTV mesh whose static deflection ε + K2⁻¹F reproduces the loaded
  /// TE at this load (mesh_parameters_export.hpp) [m]; 0 where K2 = 0 (no contact: δ − 0).
  VectorX transmission_error;
  /// (samples) contacts at the static state: loaded slices / the core's num_contacts; −1 for a
  /// linear core (always in contact).
  Eigen::VectorXi contacts;
  /// kMeshCycle with check_next_cycle and P > 1: max(|ΔK|/K, |ΔSTE|/|STE|) between the first
  /// sample and the same mesh phase one cycle later [-] (0 for identical teeth, up to round-off);
  /// NaN when not computed.
  double next_cycle_change = std::numeric_limits<double>::quiet_NaN();
};

/// @brief Result of SimulateQuasiStatic.
struct QuasiStaticResult {
  /// (samples) system phase θ [rad] of the shared roll (kSystemPhase); kMeshCycle: the mesh-phase
  /// grid θ_k,s = 2πs/S common to every mesh (each mesh's system phases in its `theta`).
  VectorX theta;
  std::vector<QuasiStaticMesh> meshes;
  /// A failed static solve ends the run (samples so far kept; never a NaN; kMeshCycle: the
  /// failing mesh keeps its samples so far, the meshes after it have none). Counters:
  /// "samples", "static_solves", "regularised_starts" (solves that needed the regularised
  /// start: flanks apart at the starting point), "free_play_samples" (equilibria with a mesh
  /// out of contact under no net mesh load: the position in the backlash is not unique, the
  /// start is kept; a warning says so).
  Summary summary;
};

/// @brief Slow roll under load: the static equilibrium (SolveTimeDomainStatic) at every θ
/// sample, each started from the previous one, with the loaded TE, tangent mesh stiffness, mesh
/// force pair and the LTV transmission error ε_η per mesh (see QuasiStaticMesh).
///
/// **Flanks apart.** Where Newton's tangent is singular (a mesh out of contact: zero torque in
/// the backlash, or a start where no tooth pair touches) the solve restarts with a regularised
/// continuation (Levenberg–Marquardt: (K_t + λ K_s) dx = r with K_s the mean stiffness with
/// stand-in mesh springs, λ from 1 down by ×0.1 per successful step to 0, then plain Newton),
/// which walks the flanks into contact under the load. An equilibrium with no mesh force at all
/// is accepted as free play (the start kept, K = 0, a warning); no contact found → status
/// kNotConverged with "flanks apart" in the message (never a NaN).
/// @throws InvalidInput on invalid options or a model without meshes.
QuasiStaticResult SimulateQuasiStatic(const SystemModel& model, const QuasiStaticOptions& options,
                                      const TimeProgress& progress = {},
                                      const std::atomic<bool>* cancel = nullptr);

/// @brief What a run at mesh frequency f_m will have to do, estimated before it starts (the
/// `geardyn simulate` warnings on very low / very high speeds and absurd loads). Added in session
/// 25 ("qs"); implemented in time_domain/quasi_static.cpp (it needs the static state).
struct TimeRunEstimate {
  /// Highest undamped natural frequency of the linear system at the static state at θ₀ (K0 plus
  /// every mesh's tangent there; power iteration as kAuto's rule) [Hz].
  double highest_frequency_hz = 0.0;
  /// Per mesh δ_η at the static state at θ₀ [m] (the static deflection under the load).
  std::vector<double> static_deflection;
  /// The fewest periods a run to steady state integrates: the steady test compares consecutive
  /// periods from max(2, min_periods) on, so max(2, min_periods) + consecutive_periods − 1, plus
  /// record_periods [-] (each of period_multiple × P mesh cycles, P the steady test's period:
  /// the symmetry period of identical tooth bodies unless steady.use_symmetry is false).
  long min_periods = 0;
  double min_simulated_time_s = 0.0;  ///< min_periods × P × period_multiple / f_m [s]
  /// Oscillations of the highest mode within min_simulated_time_s [-]: the work of a
  /// time integration that follows them (its steps grow with this number).
  double highest_mode_cycles = 0.0;
  Summary summary;  ///< the static solve's status (values 0 when it failed)
};
/// @throws InvalidInput as SimulateSteadyState (f_m, options, model).
TimeRunEstimate EstimateTimeRun(const SystemModel& model, double mesh_frequency_hz,
                                const TimeResponseOptions& options);

}  // namespace geardyn
