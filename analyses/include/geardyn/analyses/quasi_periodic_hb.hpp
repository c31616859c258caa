/// @file
/// @brief Linear harmonic balance of a gear system whose meshes run at several frequencies (a
/// planetary stage and a parallel stage, a two-stage train): the steady quasi-periodic response
/// of the LTV model on the torus of its independent mesh frequencies (issue 18, spec 02
/// "Harmonic balance").
///
/// **Equation** (the model of harmonic_balance.hpp): M q̈ + C(t) q̇ + K(t) q = f(t) with
/// K(t) = K0 + Σ_k P_kᵀ G_kᵀ K2_k(θ_k) G_k P_k, θ_k = r_k ω_m t + φ_k (SystemMesh::MeshPhase),
/// likewise C(t), and the mesh loads K2_k ε_k(θ_k).
///
/// **Bases.** Meshes whose phase ratios r_k agree (relative ratio_tolerance) share one base
/// frequency; base b has Ω_b = r_b ω_m / P_b [rad/s] with P_b the lcm of its cores' periods
/// (mesh cycles; 1 without long-period tooth errors), so its meshes are 2π/Ω_b-periodic. With d
/// bases the response lives on the d-torus ψ = (ψ_1, …, ψ_d), ψ_b = Ω_b t:
/// \f[ q(t) = \sum_{κ ∈ S} Q_κ e^{i κ·ψ}, \quad S = \{κ ∈ \mathbb{Z}^d : |κ|_1 ≤ H\}, \f]
/// Q_{−κ} = conj(Q_κ) (real response), frequency w_κ = κ·Ω. H (total_order) truncates by total
/// order: harmonic a of base 1 with harmonic c of base 2 has order |a| + |c|. The mesh k of
/// base b has K2_k = Σ_n K2_{k,n} e^{inθ_k'/P_k} (θ_k' = θ_k − φ_k, ExpandOwnPhaseMeshHarmonics,
/// offset factor included) = Σ_n K2_{k,n} e^{i n u_k ψ_b}, u_k = P_b/P_k, so it couples κ only
/// with κ − n u_k e_b: the equations are, for every κ ∈ S,
/// \f[ (−w_κ^2 M + i w_κ C_0 + K_0) Q_κ + \sum_k \sum_n P_kᵀ G_kᵀ (K2_{k,n} + i w_{κ'} C2_{k,n})
///     G_k P_k Q_{κ'} = F_κ, \quad κ' = κ − n u_k e_b ∈ S. \f]
/// F_κ holds f0 (κ = 0), the mesh loads (K2 ε)_{k,n} at κ = n u_k e_b and the harmonic loads
/// Re(F e^{imθ}) (θ the phase of ratio 1) at κ = ±m P_b e_b of the base with r_b = 1.
/// **Exact limits:** with one base (every ratio equal) S is {−H … H} and the equations are those
/// of SolveHarmonicBalance with H harmonics (P = 1): the same answer to round-off. Meshes that do
/// not couple (two separate pairs) give each pair's single-frequency answer.
///
/// **Solve.** The (n·|S|)² complex system is sparse (each block row couples along the d axes
/// through S) and is factored once by Eigen's SparseLU; its reciprocal condition number is
/// estimated (Hager–Higham); below 1e-14 the status is kNumericalIssue. Rigid-body modes of the
/// mean stiffness are fixed as in harmonic_balance.hpp (penalty on the κ = 0 block, unbalanced
/// part of F_0 removed with a warning).
///
/// **Outputs** per mesh: the mesh force F_η = Λ_η (the unknowns of the solve, see the source)
/// and the DTE coefficients D_κ = g_k Q_κ − ε_{η,κ} (probes.hpp); mean = D_0,
/// RMS = (Σ_{κ≠0} |D_κ|²)^{1/2} — the time RMS along any line of incommensurate frequencies (the
/// torus average; for commensurate frequencies the line average differs only through pairs κ, κ'
/// of equal frequency, which need |κ − κ'|_1 beyond the ratio's numerator + denominator);
/// peak-to-peak = max − min of the DTE on a torus grid (FFTW multi-dimensional c2c transform,
/// samples_per_base per axis), the sup over a dense line; the spectral lines (κ, |w_κ|, 2|D_κ|).
/// **Error estimate** (summary.error_estimate): the RMS of the DTE lines with |κ|_1 > 3H/4
/// relative to the largest RMS DTE (the content near the truncation; an estimate, not a bound).
///
/// **Memory.** The LU's memory is estimated from the block pattern (EstimateQuasiPeriodicHbBytes,
/// with a fill factor); an H above memory_limit_bytes is refused with InvalidInput naming
/// total_order, the estimate and the limit.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "geardyn/common/eigen_types.hpp"
#include "geardyn/common/summary.hpp"
#include "geardyn/system/system_model.hpp"

namespace geardyn {

/// Largest total order H of the quasi-periodic harmonic balance.
inline constexpr int kMaxQuasiPeriodicOrder = 256;

/// @brief Options of SolveQuasiPeriodicHb.
struct QuasiPeriodicHbOptions {
  int total_order = 8;  ///< H ≥ 1, ≤ kMaxQuasiPeriodicOrder: keep |κ|_1 ≤ H
  /// Meshes whose phase ratios differ by at most this fraction of the larger share a base [-],
  /// in [0, 1e-3].
  double ratio_tolerance = 1e-9;
  /// Torus grid points per base axis for the peak-to-peak values; 0 = the smallest power of two
  /// ≥ max(16, 4H + 4) (capped so that the grid has at most 2^22 points). Must exceed 2H.
  int samples_per_base = 0;
  /// Refuse an H whose estimated LU memory exceeds this [bytes], in [1e6, 1e12].
  double memory_limit_bytes = 2e9;
  /// False (with the field, value and bound in `why`) on an invalid value.
  bool IsValid(std::string* why) const;
};

/// @brief One independent base frequency.
struct QuasiPeriodicBase {
  double phase_ratio = 1.0;        ///< r_b (mesh frequency / the first mesh's) [-]
  std::int64_t period_meshes = 1;  ///< P_b (lcm of its cores' periods) [mesh cycles]
  double frequency_hz = 0.0;       ///< Ω_b/(2π) = r_b f_m / P_b [Hz]
  std::vector<int> meshes;         ///< model indices of its meshes
};

/// @brief One spectral line of a mesh's DTE (κ and −κ together).
struct QuasiPeriodicLine {
  std::vector<int> order;     ///< κ (one entry per base), the representative with w_κ ≥ 0
  double frequency_hz = 0.0;  ///< w_κ/(2π) ≥ 0 [Hz]
  double amplitude = 0.0;     ///< 2|D_κ| (|D_0| for κ = 0) [m]
};

/// @brief DTE of one mesh.
struct QuasiPeriodicMeshOutput {
  std::string name;
  int base = 0;                     ///< index into QuasiPeriodicHbResult::bases
  double mean_dte = 0.0;            ///< [m]
  double rms_dte = 0.0;             ///< RMS of DTE − mean over the torus [m]
  double peak_to_peak_dte = 0.0;    ///< on the torus grid [m]
  double mean_force = 0.0;          ///< mean of F_η [N] (> 0: compression)
  double rms_force = 0.0;           ///< RMS of F_η − mean over the torus [N]
  double peak_to_peak_force = 0.0;  ///< on the torus grid [N]
  /// Every kept κ ≠ 0 with amplitude above 1e-12 of the largest, by decreasing amplitude.
  std::vector<QuasiPeriodicLine> lines;
};

/// @brief Result at one mesh frequency.
struct QuasiPeriodicHbResult {
  Summary summary;  ///< status, message, error_estimate (see @file), counters, warnings, time
  double mesh_frequency_hz = 0.0;               ///< f_m of the phase of ratio 1 [Hz]
  int total_order = 0;                          ///< H
  std::vector<QuasiPeriodicBase> bases;         ///< d bases
  Eigen::MatrixXi orders;                       ///< (d × |S|) κ of every unknown block
  MatrixXc harmonics;                           ///< (n × |S|) Q_κ [m, rad]
  std::vector<QuasiPeriodicMeshOutput> meshes;  ///< per mesh, model order
  int samples_per_base = 0;                     ///< torus grid used for the peak-to-peak values
  double reciprocal_condition = 1.0;            ///< estimated 1/cond₁ of the LU
};

/// @brief The bases of a model (see @file), in order of first appearance of their ratio.
/// @throws InvalidInput on invalid options or a model without meshes.
std::vector<QuasiPeriodicBase> FindQuasiPeriodicBases(const SystemModel& model,
                                                      double mesh_frequency_hz,
                                                      const QuasiPeriodicHbOptions& options);

/// @brief Number of unknown blocks |S| = #{κ ∈ Z^d : |κ|_1 ≤ H} (d bases, total order H).
std::int64_t CountQuasiPeriodicHarmonics(int num_bases, int total_order);

/// @brief Estimated working memory of the factorization [bytes] (see @file "Memory").
double EstimateQuasiPeriodicHbBytes(const SystemModel& model,
                                    const QuasiPeriodicHbOptions& options);

/// @brief The quasi-periodic steady state at mesh frequency f_m [Hz] (of the ratio-1 phase).
/// @throws InvalidInput on f_m ≤ 0 or non-finite, invalid options, a model without meshes, a
///   NonlinearMeshCore, harmonic loads without a base of ratio 1, or an H over the memory limit.
QuasiPeriodicHbResult SolveQuasiPeriodicHb(const SystemModel& model, double mesh_frequency_hz,
                                           const QuasiPeriodicHbOptions& options = {});

}  // namespace geardyn
