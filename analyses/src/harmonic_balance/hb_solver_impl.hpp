// The HarmonicBalanceSolver's per-H setup and its Impl (hb_solver.cpp), shared with the files
// that hold its memory estimates (hb_memory.cpp) and its undamped-mode check
// (hb_undamped_modes.cpp).
#pragma once

#include <Eigen/LU>
#include <Eigen/SparseLU>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "geardyn/analyses/harmonic_balance.hpp"
#include "geardyn/common/check.hpp"
#include "hb_internal.hpp"

namespace geardyn {
namespace internal {

// Relative size below which a θ-varying harmonic counts as zero (round-off of the expansion).
inline constexpr double kVaryingTol = 1e-13;
// Estimated reciprocal condition number below which a solve is reported as unreliable.
inline constexpr double kMinRcond = 1e-14;
// Estimated reciprocal condition number below which a warning names the digits lost.
inline constexpr double kWarnRcond = 1e-10;
// A forcing class whose largest load harmonic is below this fraction of the largest is not
// solved (round-off of the expansion).
inline constexpr double kForcingTol = 1e-12;
// Modal damping ratio below which a mode of the mean system counts as undamped [-].
inline constexpr double kUndampedZeta = 1e-6;
// Share of the alternating response (mass-weighted) above which an undamped mode "dominates".
inline constexpr double kUndampedShare = 0.1;
// Largest model whose mean modes are computed (dense) for the undamped-mode check.
inline constexpr int kMaxModalCheckDofs = 3000;
// Largest working memory of one H accepted (EstimateBytes) [B].
inline constexpr double kMaxHbBytes = 2.0 * 1024 * 1024 * 1024;

}  // namespace internal

using internal::ComplexSparse;

// Everything that depends on (model, H) but not on the frequency. Harmonic indices k are of
// Ω = ω_m/P (P = period_meshes()); the operator K, C repeats every q = P/P_K of them, so only
// harmonics in one class k ≡ ±c (mod q) couple (harmonic_balance.hpp "Harmonic set").
struct HbSetup {
  int H = 0;  // harmonics of the operator frequency ω_m/P_K (mesh orders when P_K = 1)
  int n = 0;
  int q = 1;     // P / P_K
  int kmax = 0;  // largest kept one-sided harmonic
  bool dense = true;
  // Sparse harmonics (harmonic_balance.hpp "Long hunting periods"): nothing is indexed by k up
  // to k_max; the outputs come from the class envelopes (HbClassSampler).
  bool sparse = false;
  std::vector<int> ks;       // kept one-sided harmonics, ascending, ks[0] = 0
  std::vector<int> classes;  // c ∈ [0, q/2] solved (0 always)
  // Per mesh: K2, C2 at the operator harmonics jq (j = 0 … 2H+1), K2 ε and ε at ks[i].
  std::vector<std::vector<Matrix2c>> op_stiffness, op_damping;
  std::vector<std::vector<Vector2c>> load, eps;
  SparseMatrix M, Kbar, Cbar;            // mean system
  SparseMatrix Kbar0;                    // K̄ + rigid-body penalty W (harmonic 0 only)
  MatrixX M_d, Kbar_d, Kbar0_d, Cbar_d;  // dense copies (dense storage)
  std::vector<VectorXc> F;               // per position in ks (F_0 balanced)
  double unbalanced = 0.0;
  // Mesh-deflection channels (rows of G_all) whose stiffness or damping varies with θ.
  int r = 0;
  MatrixX Gt_d;                  // (n × r) dense G_allᵀ
  SparseMatrix Gt;               // (n × r)
  SparseMatrix G;                // (r × n)
  std::vector<MatrixXc> dK, dC;  // j = 0 … 2H+1: (r × r) harmonic jq of the θ-varying part
  // Reused factorizations.
  Eigen::PartialPivLU<MatrixXc> dense_lu;
  Eigen::SparseLU<ComplexSparse> sparse_lu;
  bool pattern_analysed = false;
  std::unique_ptr<internal::HbOutputSampler> sampler;
  std::unique_ptr<internal::HbClassSampler> class_sampler;

  // Position of the kept harmonic k in ks (k must be kept).
  int Pos(int k) const {
    const auto it = std::lower_bound(ks.begin(), ks.end(), k);
    GEARDYN_DEMAND(it != ks.end() && *it == k);
    return static_cast<int>(it - ks.begin());
  }
  // ΔK, ΔC at harmonic m (a multiple of q), X_{−m} = conj(X_m).
  MatrixXc DeltaAt(const std::vector<MatrixXc>& d, int m) const {
    const MatrixXc& x = d[static_cast<size_t>(std::abs(m) / q)];
    return m >= 0 ? x : MatrixXc(x.conjugate());
  }
};

// Undamped modes of the mean system (harmonic_balance.hpp "Undamped modes").
struct UndampedModes {
  bool checked = false;
  std::string note;  // why the check was skipped
  MatrixX phi;       // (n × u) M-orthonormal
  VectorX freq_hz;   // (u)
  VectorX zeta;      // (u) φᵀ C̄ φ / (2ω)
};

struct HarmonicBalanceSolver::Impl {
  SystemModel model;
  HbOptions options;
  std::vector<std::string> warnings;
  internal::RigidModes rigid;
  bool rigid_done = false;
  UndampedModes undamped;
  std::map<int, std::unique_ptr<HbSetup>> setups;

  std::int64_t ClassModulus() const { return model.period_meshes() / OperatorPeriodMeshes(model); }
  double EstimateBytes(int H) const;
  // The sparse path's memory [B] (harmonic_balance.hpp "Long hunting periods"), or +inf when
  // the model cannot take it (why in *why).
  double EstimateSparseBytes(int H, std::string* why) const;
  bool UseSparse(int H) const;
  std::vector<int> CandidateClasses() const;
  HbSetup& Setup(int H);
  void FindUndampedModes(const HbSetup& s);
  void CheckUndampedShare(const HbSetup& s, const MatrixXc& Q, double f_m, Summary* out) const;
  MatrixXc SolveDecoupledOrCondensed(HbSetup& s, double omega, bool condensed, double* rcond,
                                     long* factorizations);
  MatrixXc SolveDirect(HbSetup& s, double omega, double* rcond);
  HbResult SolveFixed(int H, double f_m);
};

}  // namespace geardyn
