/// @file
/// @brief Linear harmonic balance of an assembled gear system: the steady-state periodic
/// response of the LTV (or LTI) model and its DTE, mesh forces and bearing forces, at one mesh
/// frequency (`SolveHarmonicBalance`, `HarmonicBalanceSolver`) or over a list of them
/// (`SweepHarmonicBalance`) — spec 02 "Harmonic balance", issue 6 (linear half).
///
/// **Equation.** M q̈ + C(θ) q̇ + K(θ) q = f(θ) (system_model.hpp) with θ = ω_m t, ω_m = 2π f_m
/// [rad/s] (f_m the tooth-mesh frequency [Hz]). The system is periodic in θ with period 2πP
/// (P = SystemModel::period_meshes()), so the fundamental is Ω = ω_m / P [rad/s].
///
/// **Harmonic conventions** (shared with the nonlinear engine; system_harmonics.hpp):
/// * K(θ) = Σ_m K_m e^{imθ/P}, C(θ) = Σ_m C_m e^{imθ/P}, f(θ) = Σ_m f_m e^{imθ/P}, X_{−m} =
///   conj(X_m) (ExpandSystemHarmonics / ExpandMeshHarmonics);
/// * q(t) = Σ_k Q_k e^{ikΩt} over the kept harmonics k (see "Harmonic set"), Q_{−k} = conj(Q_k)
///   (real response). The amplitude of harmonic k ≥ 1 is 2|Q_k| and q = Q_0 + 2 Σ_{k≥1} (Re Q_k
///   cos kΩt − Im Q_k sin kΩt);
/// * harmonic k of the equation (C(θ) q̇ couples with the velocity of the harmonic it acts on):
///   \f[ −k²Ω² M Q_k + \sum_{j=−H}^{H} \big(K_{k−j} + i jΩ\, C_{k−j}\big) Q_j = F_k,
///       \quad k = 0 … H; \f]
/// * real layout of the unknowns and equations (LinearHbSystem, MakeLinearHbSystem):
///   x = [Re Q_0; Re Q_1; Im Q_1; …; Re Q_H; Im Q_H] ((2H+1)·n reals), rows in the same order
///   (real part of equation 0, then real and imaginary parts of equations 1 … H).
///
/// **Harmonic set** (why H counts mesh orders, not harmonics of Ω). K(θ) and C(θ) repeat every
/// P_K meshes (the lcm of the stiffness channels' periods, usually 1); only the forcing K2 ε
/// repeats over the hunting period P (pitch errors, runout). So K_m = C_m = 0 unless q = P/P_K
/// divides m, and the equation of harmonic k couples only harmonics j ≡ k (mod q): the harmonics
/// split into classes c = ±k mod q, each solved on its own. HbOptions::harmonics = H counts
/// harmonics of the operator frequency ω_m/P_K (mesh orders when P_K = 1); the kept one-sided
/// harmonics are k = jq ± c, j = 0 … H, for c = 0 (the mean and the mesh orders, always) and for
/// every class c ∈ (0, q/2] whose load harmonics up to Hq + q/2 exceed 1e-12 of the largest (a
/// runout of a z-tooth gear: c = P/z, its sidebands; pitch errors: many classes). Within its class
/// a kept harmonic couples through every K_{jq}, |j| ≤ 2H+1, exactly as the P = 1 problem does, so
/// the truncation error is that of H mesh orders, whatever P. (The former count, H harmonics of
/// ω_m/P, dropped the mesh frequency itself whenever H < P.) HbResult::kept_harmonics lists
/// them, highest_harmonic is the largest. The working memory grows with (2H+1)·q; an H over a
/// long hunting period that would need more than 2 GB is refused (the constructor) or ends the
/// tolerance search (kToleranceNotMet), unless sparse harmonics apply ("Long hunting periods").
///
/// **Long hunting periods** (sparse harmonics). Coprime tooth counts with a runout (997/991:
/// P = 988 027) make q = P/P_K so large that nothing indexed up to k_max ≈ Hq fits (the dense
/// estimate is refused above 2 GB). When every core is linear and its ε is a short-period
/// coefficient plus a few lines (TransmissionErrorSidebands: the runout), the solver keeps only
/// the kept harmonics (HbOptions::harmonic_storage: kAuto → sparse above the dense limit, or
/// forced): the operator at the harmonics jq and the load K2 ε at the kept k come from
/// ExpandMeshHarmonicsSparse (exact convolution of K2's harmonics with ε's lines), the classes
/// are those the lines reach, each solved as before. Outputs (HbClassSampler): every output is
/// Σ_c e^{icθ/P} E_c(θ) with an envelope E_c of one operator period, so the mean (class 0) and
/// the RMS (Parseval over classes, orthogonal over the hunting period) are exact for the DTE
/// (band-limited) and sampled over one operator period like the dense path for forces;
/// dte_amplitudes are exact at the kept harmonics; the peak-to-peak values are sampled over
/// min(q, 4096) operator periods spread over the hunting period (exact samples, but a window:
/// a lower bound of the true value when q > 4096). kDirect is not available there.
///
/// **Rigid-body modes.** A free gear train (no support about the axes) has K̄ r = 0; since K(θ) is
/// PSD, K(θ) r = 0 for every θ and the mean part of Q_0 along r is undetermined. The solver fixes
/// it as SolveStaticDeflection does: Q_0 orthogonal to the null space of K̄ in the coordinates
/// scaled by √diag(K̄) (penalty W = D^{1/2} V Vᵀ D^{1/2} added to the k = 0 block), and the part of
/// F_0 along it (a torque the supports cannot react) is removed with a warning. DTE, mesh and
/// bearing forces do not depend on this choice.
///
/// **Methods** (HbMethod; kAuto picks one, reported in HbResult::method_used):
/// | method | when (kAuto) | cost per frequency |
/// |---|---|---|
/// | kDecoupled | K and C constant in θ (LTI, e.g. mean-LTI cores): each harmonic alone, (−k²Ω²M +
/// ikΩC̄ + K̄) Q_k = F_k | (H+1) n×n solves | | kCondensed | any LTV model: the θ-varying part is Σ
/// Gᵀ ΔK2(θ) G of rank r ≤ 2·meshes; the block-diagonal LTI harmonics are solved (dense or sparse
/// LU per harmonic, pattern analysed once) and the coupling is solved on the mesh deflections only
/// (Woodbury: (I + R T) D = D⁰, R_k = G A_k⁻¹ Gᵀ, T the block Toeplitz of ΔK2_m, ΔC2_m), in the
/// real layout | (H+1) LU of n×n + one dense LU of r(2H+1) | | kDirect | never (reference) | the
/// full dense real system of MakeLinearHbSystem, ((2H+1)n)³ | All three are exact solutions of the
/// same truncated equations (tests compare them).
///
/// **Accuracy knob.** HbOptions::harmonics = H, or 0 and a tolerance: H = min_harmonics,
/// 2·min_harmonics, … until the change of the RMS DTE (max over meshes, relative to the largest
/// RMS DTE) between H/2 and H is at most `tolerance`; the result reports H and that change as
/// summary.error_estimate. With a fixed H the estimate is the RMS of the DTE harmonics above
/// the mesh order ⌊3H/4⌋ (with their sidebands) relative to the largest RMS DTE (the size of the
/// content near the truncation). Both are estimates, not bounds. H ≤ kMaxHbHarmonics.
///
/// **Diagnostics** (Summary): every LU's reciprocal condition number is estimated (dense:
/// Eigen's rcond(); sparse: Hager–Higham 1-norm estimate with A and Aᴴ solves); the smallest is
/// HbResult::reciprocal_condition; below 1e-14 the status is kNumericalIssue, below 1e-10 a
/// warning gives the digits lost. **Undamped modes:** the modes of the mean system (K̄, M)
/// (dense, n ≤ 3000) whose modal damping ratio φᵀC̄φ/(2ω) is below 1e-6 are found once; when
/// one of them carries more than 10 % of the alternating response (Σ_{k≥1} |φᵀMQ_k|² over
/// Σ_{k≥1} Q_kᴴMQ_k) a warning names it: such a response is bounded only by the truncation and
/// the LTV coupling, not by damping (e.g. the undamped bearing modes of the built-in rig).
///
/// **Outputs** (from S time samples of the synthesized response per system period, FFTW c2r):
/// per mesh DTE (probes.hpp: δ_η − ε_η) mean, RMS of the alternating part, peak-to-peak and the
/// amplitudes of its harmonics 0 … highest_harmonic of Ω (FFT of the samples), the mesh force F_η =
/// row η of K2(δ − ε) + C2 δ̇ (mean, RMS, peak-to-peak); per element the mean and RMS (alternating)
/// of the six force components on its first body's coordinates (CalcElementForce).
///
/// **Slice cores** are used through their all-loaded linearization (workspace.hpp), with a
/// warning; a NonlinearMeshCore is rejected (use the nonlinear engine). Reentrant; one
/// HarmonicBalanceSolver per thread (it owns FFTW plans and factorizations; construct solvers
/// from one thread at a time: FFTW planning is not thread-safe). Never prints.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "geardyn/common/eigen_types.hpp"
#include "geardyn/common/summary.hpp"
#include "geardyn/system/system_model.hpp"

namespace geardyn {

/// @brief How the harmonics are stored (@file "Long hunting periods").
/// * kAuto — dense unless its memory estimate exceeds 2 GB and the sparse form is possible.
/// * kDense — every harmonic 0 … k_max of the hunting period indexed (mesh harmonics, response,
///   output samples over the hunting period).
/// * kSparse — only the kept harmonics; outputs from the class envelopes.
enum class HbHarmonicStorage { kAuto, kDense, kSparse };

/// @brief How the linear harmonic-balance equations are solved (see the @file table).
enum class HbMethod { kAuto, kDecoupled, kCondensed, kDirect };
/// "auto", "decoupled", "condensed", "direct".
const char* ToString(HbMethod method);

/// Largest H (harmonics, max_harmonics) of HbOptions: the condensed coupling of one mesh in one
/// forcing class alone takes (2(2H+1))² complex entries, 1.1 GB at H = 2048.
inline constexpr int kMaxHbHarmonics = 2048;

/// Operator periods over which sparse harmonics sample the peak-to-peak values (all of them when
/// the hunting period holds fewer; @file "Long hunting periods").
inline constexpr int kHbPeakWindowPeriods = 4096;

/// @brief Options of the linear harmonic balance.
struct HbOptions {
  HbMethod method = HbMethod::kAuto;
  /// H ≥ 1: harmonics of the operator frequency ω_m/P_K kept (mesh orders when P_K = 1), each
  /// with its forcing sidebands (@file "Harmonic set"); 0 = chosen from `tolerance`.
  int harmonics = 0;
  /// With harmonics = 0: accepted relative change of the RMS DTE between H/2 and H [-], > 0.
  /// Not used with harmonics > 0.
  double tolerance = 1e-4;
  /// First H of the tolerance search (≥ 1).
  int min_harmonics = 8;
  /// Largest H of the tolerance search (≥ min_harmonics); reaching it gives kToleranceNotMet.
  int max_harmonics = 512;
  /// S time samples per system period for the outputs; 0 = the smallest q·2^j ≥ max(256,
  /// 8(k_max+1)), k_max = highest_harmonic, q = P/P_K (a power of two for error-free pairs).
  /// Must exceed 2·k_max when given.
  int time_samples = 0;
  /// Compute mesh forces and element forces (DTE always).
  bool compute_forces = true;
  /// Keep Q_k (n × (H+1)) and the DTE samples in the result.
  bool keep_harmonics = false;
  /// Dense or sparse harmonic storage (@file "Long hunting periods"); kAuto picks.
  HbHarmonicStorage harmonic_storage = HbHarmonicStorage::kAuto;
  /// Optional cancel flag (e.g. set by a SIGINT handler), polled between the points of
  /// SweepHarmonicBalance: once true the sweep returns the points solved so far with
  /// Status::kInterrupted. Not owned; must outlive the sweep.
  const std::atomic<bool>* cancel = nullptr;
  /// False (with the field, value and bound in `why`) on an invalid value.
  bool IsValid(std::string* why) const;
};

/// @brief Steady-state outputs of one mesh.
struct HbMeshOutput {
  std::string name;
  double mean_dte = 0.0;  ///< θ-mean of the DTE [m]
  double rms_dte = 0.0;   ///< RMS of DTE − mean [m]
  /// max − min of the DTE samples [m] (sparse harmonics: over a window of the hunting period,
  /// a lower bound; @file "Long hunting periods")
  double peak_to_peak_dte = 0.0;
  /// (k_max+1) |mean|, then 2|Y_k| of harmonic k of Ω = ω_m/P [m]; with sparse harmonics one
  /// per kept harmonic, in the order of HbResult::kept_harmonics.
  VectorX dte_amplitudes;
  double mean_force = 0.0;          ///< θ-mean of F_η [N] (> 0: compression)
  double rms_force = 0.0;           ///< RMS of F_η − mean [N]
  double peak_to_peak_force = 0.0;  ///< [N]
};

/// @brief Steady-state force of one element on its first body's six coordinates.
struct HbElementOutput {
  std::string name;
  Vector6 mean_force = Vector6::Zero();  ///< [N, N·m] (CalcElementForce, components 0–5)
  Vector6 rms_force = Vector6::Zero();   ///< RMS of the alternating part [N, N·m]
};

/// @brief Result at one mesh frequency.
struct HbResult {
  Summary summary;  ///< status, message, error_estimate (see @file), counters, warnings, time
  HbMethod method_used = HbMethod::kAuto;
  double mesh_frequency_hz = 0.0;     ///< f_m [Hz]
  std::int64_t period_meshes = 1;     ///< P [-]
  int harmonics = 0;                  ///< H used (mesh orders when P_K = 1)
  int highest_harmonic = 0;           ///< k_max: the largest kept harmonic of Ω = ω_m/P
  std::vector<int> kept_harmonics;    ///< the kept one-sided k (of Ω), ascending
  bool sparse_harmonics = false;      ///< the sparse storage was used (@file)
  double reciprocal_condition = 1.0;  ///< smallest estimated 1/cond of the LU solves
  int time_samples = 0;  ///< S used (sparse harmonics: per operator period of the envelopes)
  std::vector<HbMeshOutput> meshes;       ///< per mesh, model order
  std::vector<HbElementOutput> elements;  ///< per element (empty unless compute_forces)
  /// (n × (k_max+1)) Q_k [m, rad] when keep_harmonics (0 if not kept); with sparse harmonics
  /// (n × kept) in the order of kept_harmonics.
  MatrixXc response_harmonics;
  /// (meshes × S) DTE at θ_s = 2πP s/S [m] when keep_harmonics (empty with sparse harmonics).
  MatrixX dte_samples;
};

/// @brief The full linear HB system in the real layout (see the @file): A x = b.
struct LinearHbSystem {
  MatrixX matrix;  ///< ((2H+1)n)² [N/m, …], rigid-body penalty included in the k = 0 block
  VectorX rhs;     ///< ((2H+1)n) [N, N·m], unbalanced part of F_0 removed
};

/// @brief Assembles the dense LinearHbSystem at one mesh frequency (the kDirect path; the
/// linear part of a nonlinear HB Jacobian).
/// @throws InvalidInput on H < 1, f_m ≤ 0, a nonlinear core, or more than 6000 unknowns.
LinearHbSystem MakeLinearHbSystem(const SystemModel& model, int harmonics,
                                  double mesh_frequency_hz);

/// Progress of a sweep: called after each point with (points done, total).
using HbProgress = std::function<void(int done, int total)>;

/// @brief A solver reusing its setup (harmonics of the model, rigid-body modes, probes, FFTW
/// plans, sparse patterns) across frequencies (architecture §3.3 "solver object").
class HarmonicBalanceSolver {
 public:
  /// @throws InvalidInput on invalid options, a NonlinearMeshCore, meshes at different
  ///   frequencies (CheckSingleMeshFrequency), or an H whose working memory over the model's
  ///   hunting period would exceed 2 GB (the message gives the estimate).
  HarmonicBalanceSolver(const SystemModel& model, const HbOptions& options);
  ~HarmonicBalanceSolver();
  HarmonicBalanceSolver(const HarmonicBalanceSolver&) = delete;
  HarmonicBalanceSolver& operator=(const HarmonicBalanceSolver&) = delete;

  /// @brief The steady state at mesh frequency f_m [Hz] > 0.
  /// @throws InvalidInput on a non-finite or non-positive f_m.
  HbResult Solve(double mesh_frequency_hz);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// @brief HarmonicBalanceSolver(model, options).Solve(f_m).
HbResult SolveHarmonicBalance(const SystemModel& model, const HbOptions& options,
                              double mesh_frequency_hz);

/// @brief Results of a frequency sweep.
struct HbSweepResult {
  std::vector<HbResult> points;  ///< one per frequency, in the given order
  Summary summary;  ///< worst status of the points, counters summed, error_estimate = max
};

/// @brief One solver over every mesh frequency [Hz] (each > 0), calling `progress` after each.
HbSweepResult SweepHarmonicBalance(const SystemModel& model,
                                   const std::vector<double>& mesh_frequencies_hz,
                                   const HbOptions& options, const HbProgress& progress = {});

}  // namespace geardyn
