// Real layout of two-sided harmonic blocks, rigid-body penalty and model checks of the linear
// harmonic balance (hb_internal.hpp).
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <variant>

#include "geardyn/common/check.hpp"
#include "geardyn/common/overloaded.hpp"
#include "geardyn/numerics/rigid_modes.hpp"
#include "geardyn/system/system_steps.hpp"
#include "hb_internal.hpp"

namespace geardyn::internal {

void AddRealBlock(int b, int k, int j, const MatrixXc& B, MatrixX* A) {
  GEARDYN_DEMAND(k >= 0 && B.rows() == b && B.cols() == b);
  const MatrixX Br = B.real();
  const MatrixX Bi = B.imag();
  // Rows: equation 0 → [0, b) (real part); equation k ≥ 1 → real [b(2k−1), …), imag [b·2k, …).
  const int row_re = k == 0 ? 0 : b * (2 * k - 1);
  const int row_im = b * (2 * k);
  const int m = std::abs(j);
  if (m == 0) {
    A->block(row_re, 0, b, b) += Br;
    if (k > 0) A->block(row_im, 0, b, b) += Bi;
    return;
  }
  // Unknowns X_m = a + i c: a at column b(2m−1), c at b·2m. For j < 0, X_j = a − i c.
  const int col_a = b * (2 * m - 1);
  const int col_c = b * (2 * m);
  const double s = j > 0 ? 1.0 : -1.0;
  A->block(row_re, col_a, b, b) += Br;  // Re(B X) = Br a − s Bi c
  A->block(row_re, col_c, b, b) -= s * Bi;
  if (k > 0) {
    A->block(row_im, col_a, b, b) += Bi;  // Im(B X) = Bi a + s Br c
    A->block(row_im, col_c, b, b) += s * Br;
  }
}

VectorX ToRealLayout(const std::vector<VectorXc>& harmonics) {
  GEARDYN_DEMAND(!harmonics.empty());
  const Eigen::Index b = harmonics[0].size();
  const int H = static_cast<int>(harmonics.size()) - 1;
  VectorX x(b * (2 * H + 1));
  x.head(b) = harmonics[0].real();
  for (int k = 1; k <= H; ++k) {
    x.segment(b * (2 * k - 1), b) = harmonics[k].real();
    x.segment(b * (2 * k), b) = harmonics[k].imag();
  }
  return x;
}

MatrixXc FromRealLayout(const VectorX& x, int b, int harmonics) {
  GEARDYN_DEMAND(x.size() == static_cast<Eigen::Index>(b) * (2 * harmonics + 1));
  MatrixXc X(b, harmonics + 1);
  X.col(0) = x.head(b).cast<Complex>();
  for (int k = 1; k <= harmonics; ++k) {
    X.col(k).real() = x.segment(b * (2 * k - 1), b);
    X.col(k).imag() = x.segment(b * (2 * k), b);
  }
  return X;
}

RigidModes ComputeRigidModes(const MatrixX& mean_stiffness, double null_tol) {
  const RigidBodyModes modes = ComputeRigidBodyModes(mean_stiffness, null_tol);
  RigidModes out;
  out.U = modes.loads;
  out.Vs = modes.modes;
  out.inv_sqrt_d = modes.inv_sqrt_d;
  return out;
}

double BalanceMeanLoad(const RigidModes& rigid, VectorXc* f0) {
  if (rigid.count() == 0) return 0.0;
  // In the scaled coordinates f̃ = D^{-1/2} f the unbalanced part is V Vᵀ f̃.
  const VectorXc along = rigid.Vs.transpose().cast<Complex>() * (*f0);
  const double scaled_norm = rigid.inv_sqrt_d.cast<Complex>().cwiseProduct(*f0).norm();
  *f0 -= rigid.U.cast<Complex>() * along;
  return scaled_norm > 0.0 ? along.norm() / scaled_norm : 0.0;
}

std::vector<std::string> CheckLinearHbModel(const SystemModel& model) {
  CheckSingleMeshFrequency(model, "harmonic balance");
  std::vector<std::string> warnings;
  for (const SystemMesh& mesh : model.meshes()) {
    std::visit(Overloaded{
                   [](const LinearMeshCore&) {},
                   [&](const SliceMeshCore&) {
                     warnings.push_back("mesh '" + mesh.name +
                                        "': slice core linearized with every slice loaded "
                                        "(linear harmonic balance; contact loss is ignored)");
                   },
                   [&](const std::shared_ptr<const NonlinearMeshCore>&) {
                     GEARDYN_THROW_UNLESS(false, "harmonic balance (linear): mesh '"
                                                     << mesh.name
                                                     << "' has a nonlinear contact core; "
                                                        "the linear solver cannot use it");
                   },
               },
               mesh.core);
  }
  return warnings;
}

int ChooseTimeSamples(int highest, int requested, std::int64_t q) {
  if (requested > 0) return requested;
  const std::int64_t target =
      std::max<std::int64_t>(256, 8 * (static_cast<std::int64_t>(highest) + 1));
  std::int64_t s = std::max<std::int64_t>(q, 1);
  while (s < target) s *= 2;
  return static_cast<int>(s);
}

}  // namespace geardyn::internal
