/// @file
/// @brief ComputeRigidBodyModes (see rigid_modes.hpp).
#include "geardyn/numerics/rigid_modes.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace geardyn {

RigidBodyModes ComputeRigidBodyModes(const MatrixX& mean_stiffness, double null_tol) {
  const Eigen::Index n = mean_stiffness.rows();
  RigidBodyModes out;
  VectorX d = mean_stiffness.diagonal().cwiseAbs();
  const double dmax = n > 0 ? d.maxCoeff() : 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!(d(i) > 1e-14 * dmax)) d(i) = dmax > 0.0 ? dmax : 1.0;
  }
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
  const double lmax = std::max(out.eigenvalues.cwiseAbs().maxCoeff(), 1e-300);
  Eigen::Index r = 0;
  while (r < n && std::abs(out.eigenvalues(r)) < null_tol * lmax) ++r;
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
