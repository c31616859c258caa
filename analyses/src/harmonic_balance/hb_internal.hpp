/// @file
/// @brief Internal pieces of the linear harmonic balance (harmonic_balance.hpp): the real layout
/// of two-sided harmonic blocks, the rigid-body penalty, and the output sampler (FFTW).
#pragma once

#include <Eigen/SparseLU>
#include <complex>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "geardyn/analyses/harmonic_balance.hpp"
#include "geardyn/common/eigen_types.hpp"
#include "geardyn/numerics/rigid_modes.hpp"
#include "geardyn/system/probes.hpp"
#include "geardyn/system/system_harmonics.hpp"
#include "geardyn/system/system_model.hpp"

namespace geardyn::internal {

using Complex = std::complex<double>;
using ComplexSparse = Eigen::SparseMatrix<Complex, Eigen::ColMajor, int>;

/// @brief Estimate of the reciprocal 1-norm condition number 1/(‖A‖₁ ‖A⁻¹‖₁) of a factorized
/// sparse matrix: ‖A⁻¹‖₁ by Hager's method as refined by Higham (1988, ACM TOMS 14(4) 381–396,
/// Alg. 4.1, complex form), at most 5 solves with A and 5 with Aᴴ. The estimate of ‖A⁻¹‖₁ is a
/// lower bound (so the result is ≥ the true value), usually exact or within a factor 3.
/// @return the estimate; 0 when a solve is not finite.
double EstimateSparseRcond(const ComplexSparse& A, Eigen::SparseLU<ComplexSparse>& lu);

// ------------------------------------------------------------------ real layout

/// @brief Adds the complex block B (b×b) coupling unknown harmonic j ∈ [−H, H] into equation
/// k ∈ [0, H] to the real matrix A ((2H+1)b square) in the layout of harmonic_balance.hpp, using
/// X_{−j} = conj(X_j): B X_j = B (a + i c) for j > 0, B (a − i c) for j < 0, B a for j = 0
/// (X_0 real); equation 0 keeps its real part only.
void AddRealBlock(int b, int k, int j, const MatrixXc& B, MatrixX* A);

/// @brief [Re X_0; Re X_1; Im X_1; …] of the one-sided harmonics X_0 … X_H (each size b).
VectorX ToRealLayout(const std::vector<VectorXc>& harmonics);

/// @brief Inverse of ToRealLayout: column k of the result is X_k (b × (H+1)).
MatrixXc FromRealLayout(const VectorX& x, int b, int harmonics);

// ------------------------------------------------------------------ rigid-body modes

/// @brief The rigid-body penalty of harmonic_balance.hpp: null space V of D^{-1/2} K̄ D^{-1/2},
/// U = D^{1/2} V (penalty W = U Uᵀ) and Vs = D^{-1/2} V (F_0 ← F_0 − U Vsᵀ F_0).
struct RigidModes {
  MatrixX U;           ///< (n × r) [√(N/m)-like]
  MatrixX Vs;          ///< (n × r)
  VectorX inv_sqrt_d;  ///< (n) D^{-1/2}
  int count() const { return static_cast<int>(U.cols()); }
};

/// @brief Rigid modes of the mean stiffness `mean_stiffness` (dense symmetric eigen-solve).
/// @param[in] null_tol eigenvalues below null_tol·max count as zero.
RigidModes ComputeRigidModes(const MatrixX& mean_stiffness, double null_tol = kRigidNullTol);

/// @brief Removes the unbalanced part of F_0 (in place); returns its size relative to F_0, both
/// in the scaled coordinates D^{-1/2} f.
double BalanceMeanLoad(const RigidModes& rigid, VectorXc* f0);

// ------------------------------------------------------------------ model checks

/// @brief Throws InvalidInput for a NonlinearMeshCore or a phase ratio ≠ 1; returns warnings
/// (slice cores linearized).
std::vector<std::string> CheckLinearHbModel(const SystemModel& model);

/// @brief `requested` when > 0, else the smallest q·2^j ≥ max(256, 8(k_max+1)): a power of two
/// when q = 1, and a whole number of samples per operator period otherwise (the sampler then
/// evaluates K2, C2 over one operator period only).
/// @param[in] highest k_max. @param[in] requested HbOptions::time_samples. @param[in] q P/P_K.
int ChooseTimeSamples(int highest, int requested, std::int64_t q = 1);

// ------------------------------------------------------------------ outputs

/// @brief Synthesizes q(θ_s), q̇(θ_s) from Q_k by FFTW c2r (plans made once per (n, S)) and
/// evaluates the probes (DTE, mesh force, element forces) at the S samples.
class HbOutputSampler {
 public:
  HbOutputSampler(const SystemModel& model, int harmonics, int time_samples);
  ~HbOutputSampler();
  HbOutputSampler(const HbOutputSampler&) = delete;
  HbOutputSampler& operator=(const HbOutputSampler&) = delete;

  /// @brief Fills result->meshes, result->elements (when forces), dte_samples (when keep).
  /// @param[in] Q (n × (H+1)) one-sided harmonics. @param[in] omega Ω [rad/s].
  /// @return max over meshes of the RMS DTE [m].
  double Evaluate(const MatrixXc& Q, double omega, bool forces, bool keep, HbResult* result);

  int time_samples() const { return S_; }

 private:
  struct Fft;
  const SystemModel& model_;
  int H_;
  int S_;
  std::unique_ptr<Fft> fft_;
  ProbeWorkspace probe_ws_;
  VectorX q_, v_;
  std::vector<VectorX> element_force_;
  MatrixX dte_, force_;  // (meshes × S)
  MatrixX q_all_;        // (S × n) q samples
  // Per linear-core mesh and sample (they do not depend on the frequency): K2, C2 and ε at
  // θ_s, so that a sweep evaluates no coefficient; empty for slice cores (EvalMeshProbe).
  std::vector<std::vector<Matrix2>> k2_, c2_;
  std::vector<std::vector<Vector2>> eps_;
};

// ------------------------------------------------------- class envelopes (hb_class_outputs.cpp)

/// @brief The outputs of a sparse-harmonics solve (harmonic_balance.hpp "Long hunting periods")
/// from the class envelopes instead of samples over the hunting period: every output y is
/// Σ_c e^{icθ/P} E_c(θ) with E_c of the operator period 2πP_K, so the mean is that of E_0 and the
/// mean square Σ_c w_c ⟨|E_c|²⟩ (w = 1 for c = 0 and c = q/2, else 2: the classes are orthogonal
/// over the hunting period), each ⟨·⟩ from `samples` points of one operator period; the
/// peak-to-peak values are sampled over min(q, kHbPeakWindowPeriods) operator periods spread
/// evenly over the hunting period (a lower bound when q is larger).
class HbClassSampler {
 public:
  /// @param[in] q P/P_K. @param[in] ks kept harmonics (ascending). @param[in] classes solved
  /// classes. @param[in] eps per mesh, ε at ks[i] (system phase). @param[in] samples per operator
  /// period (> 2(H+1)).
  HbClassSampler(const SystemModel& model, int q, const std::vector<int>& ks,
                 const std::vector<int>& classes, const std::vector<std::vector<Vector2c>>& eps,
                 int samples);

  /// @brief Fills result->meshes (dte_amplitudes at the kept harmonics), result->elements (when
  /// forces), response_harmonics (kept order, when keep); time_samples = samples per operator
  /// period. @param[in] Q (n × ks) Q at ks[i]. @param[in] omega Ω = ω_m/P [rad/s].
  /// @return max over meshes of the RMS DTE [m].
  double Evaluate(const MatrixXc& Q, double omega, bool forces, bool keep, HbResult* result) const;

 private:
  const SystemModel& model_;
  int q_;
  std::vector<int> ks_, classes_;
  std::vector<std::vector<Vector2c>> eps_;
  int S_;
  std::vector<std::vector<Matrix2>> k2_, c2_;  // per mesh at the S samples of one period
};

// ---------------------------------------------------------------- warnings (hb_warnings.cpp)

/// Texts that mark the per-point warnings a sweep merges (after PointWarningPrefix and the
/// varying number: undamped share [%], or 1/cond).
inline constexpr const char* kUndampedShareText =
    " % of the alternating response (mass-weighted) is in an undamped mode of the mean system";
inline constexpr const char* kIllConditionedText = "ill-conditioned solve (estimated 1/cond ";

/// x with 3 significant digits.
std::string FormatG(double x);
/// A mesh frequency in a warning [Hz]: 6 significant digits ("3287.5", not "3.29e+03").
std::string FormatHz(double f);
/// "harmonic balance at <f_m> Hz: ", the prefix of every per-point warning.
std::string PointWarningPrefix(double f_m);
/// One warning per distinct per-point warning of a sweep, with the mesh-frequency range and the
/// number of points where it occurred, and the worst value of its number.
std::vector<std::string> MergePointWarnings(const std::vector<HbResult>& points);

}  // namespace geardyn::internal
