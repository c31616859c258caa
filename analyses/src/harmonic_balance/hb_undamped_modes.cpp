// HarmonicBalanceSolver: the undamped modes of the mean system and the warning when one
// dominates a response (harmonic_balance.hpp "Undamped modes").
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "geardyn/numerics/symmetric_eigen.hpp"
#include "geardyn/system/system_harmonics.hpp"
#include "hb_solver_impl.hpp"

namespace geardyn {
namespace {
using internal::Complex;
using internal::FormatG;
using internal::kMaxModalCheckDofs;
using internal::kUndampedShare;
using internal::kUndampedShareText;
using internal::kUndampedZeta;
using internal::PointWarningPrefix;
}  // namespace

void HarmonicBalanceSolver::Impl::FindUndampedModes(const HbSetup& s) {
  undamped.checked = true;
  if (s.n == 0) return;
  if (s.n > kMaxModalCheckDofs) {
    undamped.note = "undamped modes not checked (" + std::to_string(s.n) + " DOFs > " +
                    std::to_string(kMaxModalCheckDofs) + ")";
    return;
  }
  GeneralizedEigenResult eig;
  try {
    eig = SolveGeneralizedEigenDense(MatrixX(s.Kbar), MatrixX(s.M));
  } catch (const InvalidInput& e) {
    undamped.note = std::string("undamped modes not checked (") + e.what() + ")";
    return;
  }
  if (!eig.summary.ok() || eig.vectors.cols() != eig.eigenvalues.size()) {
    undamped.note = "undamped modes not checked (mean eigenproblem: " + eig.summary.message + ")";
    return;
  }
  const MatrixX C = MatrixX(s.Cbar);
  std::vector<int> keep;
  std::vector<double> f, z;
  for (Eigen::Index i = 0; i < eig.eigenvalues.size(); ++i) {
    const double lambda = eig.eigenvalues(i);
    if (!(lambda > 0.0)) continue;  // rigid-body zero
    const double w = std::sqrt(lambda);
    const double zeta = eig.vectors.col(i).dot(C * eig.vectors.col(i)) / (2.0 * w);
    if (zeta < kUndampedZeta) {
      keep.push_back(static_cast<int>(i));
      f.push_back(w / (2.0 * std::numbers::pi));
      z.push_back(zeta);
    }
  }
  undamped.phi.resize(s.n, static_cast<Eigen::Index>(keep.size()));
  for (size_t i = 0; i < keep.size(); ++i) undamped.phi.col(i) = eig.vectors.col(keep[i]);
  undamped.freq_hz = Eigen::Map<const VectorX>(f.data(), static_cast<Eigen::Index>(f.size()));
  undamped.zeta = Eigen::Map<const VectorX>(z.data(), static_cast<Eigen::Index>(z.size()));
}

// Share of the alternating response along each undamped mode, in the mass norm: Σ_{k≥1}
// |φᵀ M Q_k|² / Σ_{k≥1} Q_kᴴ M Q_k (φ M-orthonormal, so the shares of all modes sum to 1).
void HarmonicBalanceSolver::Impl::CheckUndampedShare(const HbSetup& s, const MatrixXc& Q,
                                                     double f_m, Summary* out) const {
  if (undamped.phi.cols() == 0) return;
  const MatrixXc MQ = s.M.cast<Complex>() * Q.rightCols(Q.cols() - 1);
  const double total = (Q.rightCols(Q.cols() - 1).conjugate().cwiseProduct(MQ)).sum().real();
  if (!(total > 0.0)) return;
  const MatrixXc modal = undamped.phi.transpose().cast<Complex>() * MQ;  // (u × kmax)
  for (Eigen::Index i = 0; i < undamped.phi.cols(); ++i) {
    const double share = modal.row(i).squaredNorm() / total;
    if (share > kUndampedShare) {
      out->warnings.push_back(
          PointWarningPrefix(f_m) + FormatG(100.0 * share) + kUndampedShareText + " (" +
          FormatG(undamped.freq_hz(i)) + " Hz, modal damping ratio " + FormatG(undamped.zeta(i)) +
          "): its amplitude is set by the truncation, not by damping; add damping (bearings, "
          "system modal/Rayleigh damping) before trusting it");
    }
  }
}

// Block-diagonal LTI harmonics A_k = −k²Ω²M + ikΩC̄ + K̄ solved for [F_k, G_allᵀ] at every kept
// k; with the coupling (condensed), per class c the mesh-deflection system (I + R T) D = D⁰ over
// the two-sided window k ≡ c (mod q), |k| ≤ Hq + c (class 0 in the real layout, stride q;
// others complex, k < 0 by A_{−k} = conj A_k), then Q_k = A_k⁻¹ (F_k − G_allᵀ (T D)_k).
}  // namespace geardyn
