/// @file
/// @brief ComputeRigidBodyModes (see rigid_modes.hpp).
#include "geardyn/numerics/rigid_modes.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

namespace geardyn {

VectorX RigidScaling(const VectorX& stiffness_diagonal) {
  VectorX d = stiffness_diagonal.cwiseAbs();
  const double dmax = d.size() > 0 ? d.maxCoeff() : 0.0;
  for (Eigen::Index i = 0; i < d.size(); ++i) {
    if (!(d(i) > 1e-14 * dmax)) d(i) = dmax > 0.0 ? dmax : 1.0;
  }
  return d;
}

double ScaledStiffnessQuotient(double phi_k_phi, const VectorX& scaling, const VectorX& phi) {
  const double phi_d_phi = phi.dot(scaling.cwiseProduct(phi));
  if (phi_d_phi > 0.0) return std::abs(phi_k_phi) / phi_d_phi;
  return phi_k_phi == 0.0 ? 0.0 : std::numeric_limits<double>::infinity();
}

bool IsRigidBodyPattern(double phi_k_phi, const VectorX& scaling, const VectorX& phi,
                        double null_tol) {
  // NaN compares false: a non-finite quotient is never "rigid".
  return ScaledStiffnessQuotient(phi_k_phi, scaling, phi) <= null_tol;
}

RigidBodyModes ComputeRigidBodyModes(const MatrixX& mean_stiffness, double null_tol) {
  const Eigen::Index n = mean_stiffness.rows();
  RigidBodyModes out;
  const VectorX d = RigidScaling(mean_stiffness.diagonal());
  out.sqrt_d = d.cwiseSqrt();
  out.inv_sqrt_d = out.sqrt_d.cwiseInverse();
  out.scaled.resize(n, 0);
  out.modes.resize(n, 0);
  out.loads.resize(n, 0);
  if (n == 0) return out;
  const MatrixX k = out.inv_sqrt_d.asDiagonal() * mean_stiffness * out.inv_sqrt_d.asDiagonal();
  Eigen::SelfAdjointEigenSolver<MatrixX> eig(0.5 * (k + k.transpose()));
  if (eig.info() != Eigen::Success) {
    out.ok = false;
    return out;
  }
  out.eigenvalues = eig.eigenvalues();
  out.eigenvectors = eig.eigenvectors();
  // K̃ has a unit diagonal (D = diag K̄), so its eigenvalue is μ of the file comment.
  Eigen::Index r = 0;
  while (r < n && std::abs(out.eigenvalues(r)) <= null_tol) ++r;
  out.scaled = eig.eigenvectors().leftCols(r);
  out.modes = out.inv_sqrt_d.asDiagonal() * out.scaled;
  out.loads = out.sqrt_d.asDiagonal() * out.scaled;
  return out;
}

double RigidBodyModes::UnbalancedFraction(const VectorX& f) const {
  if (count() == 0) return 0.0;
  const VectorX fs = inv_sqrt_d.cwiseProduct(f);
  const double norm = fs.norm();
  return norm > 0.0 ? (scaled.transpose() * fs).norm() / norm : 0.0;
}

VectorX RigidBodyModes::Balance(const VectorX& f) const {
  if (count() == 0) return f;
  return f - loads * (scaled.transpose() * inv_sqrt_d.cwiseProduct(f));
}

}  // namespace geardyn
