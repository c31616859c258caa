// System damping (Rayleigh, modal) added to C0 of a built model; see system_damping.hpp.
#include "geardyn/system/system_damping.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>
#include <utility>

#include "geardyn/common/check.hpp"
#include "geardyn/numerics/symmetric_eigen.hpp"
#include "geardyn/system/workspace.hpp"
#include "system_model_data.hpp"

namespace geardyn {
namespace {

bool ValidRatio(double zeta) { return std::isfinite(zeta) && zeta >= 0.0 && zeta < 1.0; }

// Modes of (K̄, M) of one decoupled DOF block.
struct BlockModes {
  std::vector<int> dofs;
  VectorX omega;  // ω_r [rad/s], exactly 0 for rigid-body modes
  MatrixX mphi;   // M Φ (M-orthonormal Φ)
};

// C_ζ = Σ_r 2 ζ_r ω_r (MΦ)_r (MΦ)_rᵀ with ζ_r from the per-mode list by global ascending ω.
MatrixX ModalDampingMatrix(const SystemModel::Data& data, const MatrixX& kbar,
                           const SystemDamping& damping) {
  const int n = static_cast<int>(kbar.rows());
  const MatrixX mass = MatrixX(data.mass);
  std::vector<BlockModes> blocks;
  for (const std::vector<int>& dofs : data.blocks) {
    const int nb = static_cast<int>(dofs.size());
    MatrixX kb(nb, nb), mb(nb, nb);
    for (int a = 0; a < nb; ++a) {
      for (int b = 0; b < nb; ++b) {
        kb(a, b) = kbar(dofs[a], dofs[b]);
        mb(a, b) = mass(dofs[a], dofs[b]);
      }
    }
    const GeneralizedEigenResult eig =
        SolveGeneralizedEigenDense(0.5 * (kb + kb.transpose()), 0.5 * (mb + mb.transpose()));
    GEARDYN_THROW_UNLESS(eig.summary.ok(),
                         "modal damping: eigen-decomposition of the mean "
                         "system failed: "
                             << eig.summary.message);
    blocks.push_back({dofs, eig.eigenvalues.cwiseMax(0.0).cwiseSqrt(), mb * eig.vectors});
  }
  // Flexible modes (block, column) in ascending ω over the whole system.
  std::vector<std::pair<int, int>> order;
  for (int b = 0; b < static_cast<int>(blocks.size()); ++b) {
    for (int r = 0; r < blocks[b].omega.size(); ++r) {
      if (blocks[b].omega(r) > 0.0) order.emplace_back(b, r);
    }
  }
  std::stable_sort(order.begin(), order.end(), [&](const auto& x, const auto& y) {
    return blocks[x.first].omega(x.second) < blocks[y.first].omega(y.second);
  });
  std::vector<VectorX> zeta;
  for (const BlockModes& b : blocks) zeta.push_back(VectorX::Zero(b.omega.size()));
  for (std::size_t k = 0; k < order.size(); ++k) {
    zeta[order[k].first](order[k].second) =
        k < damping.modal_ratios.size() ? damping.modal_ratios[k] : damping.modal_ratio.value_or(0);
  }
  MatrixX c = MatrixX::Zero(n, n);
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    const BlockModes& bm = blocks[b];
    const VectorX d = 2.0 * zeta[b].cwiseProduct(bm.omega);
    const MatrixX cb = bm.mphi * d.asDiagonal() * bm.mphi.transpose();
    const int nb = static_cast<int>(bm.dofs.size());
    for (int a = 0; a < nb; ++a) {
      for (int j = 0; j < nb; ++j) c(bm.dofs[a], bm.dofs[j]) = cb(a, j);
    }
  }
  return 0.5 * (c + c.transpose());
}

}  // namespace

bool SystemDamping::IsValid(std::string* why) const {
  std::ostringstream os;
  if (!std::isfinite(rayleigh_alpha) || rayleigh_alpha < 0.0) {
    os << "rayleigh_alpha: must be finite and >= 0 [1/s], got " << rayleigh_alpha;
  } else if (!std::isfinite(rayleigh_beta) || rayleigh_beta < 0.0) {
    os << "rayleigh_beta: must be finite and >= 0 [s], got " << rayleigh_beta;
  } else if (modal_ratio && !ValidRatio(*modal_ratio)) {
    os << "modal_ratio: must be in [0, 1), got " << *modal_ratio;
  } else if (has_rayleigh() && has_modal()) {
    os << "damping: give Rayleigh coefficients or modal ratios, not both";
  } else {
    for (std::size_t r = 0; r < modal_ratios.size(); ++r) {
      if (!ValidRatio(modal_ratios[r])) {
        os << "modal_ratios[" << r << "]: must be in [0, 1), got " << modal_ratios[r];
        break;
      }
    }
  }
  if (os.str().empty()) return true;
  if (why != nullptr) *why = os.str();
  return false;
}

SystemModel AddSystemDamping(const SystemModel& model, const SystemDamping& damping) {
  std::string why;
  GEARDYN_THROW_UNLESS(damping.IsValid(&why), why);
  if (!damping.has_rayleigh() && !damping.has_modal()) return model;
  auto data = std::make_shared<SystemModel::Data>(*model.data_);
  data->rayleigh_alpha = damping.rayleigh_alpha;
  data->rayleigh_beta = damping.rayleigh_beta;
  data->modal_zeta = damping.modal_ratio.value_or(0.0);
  SystemWorkspace ws(model, StorageKind::kSparse);
  const SparseMatrix& kbar = AssembleMeanStiffnessSparse(model, ws);
  if (damping.has_rayleigh()) {
    data->damping0 =
        data->damping0 + damping.rayleigh_alpha * data->mass + damping.rayleigh_beta * kbar;
  } else {
    const SparseMatrix c = ModalDampingMatrix(*data, MatrixX(kbar), damping).sparseView();
    data->damping0 = data->damping0 + c;
  }
  data->damping0.prune(0.0);
  data->damping0.makeCompressed();
  data->id = internal::NextModelId();
  return SystemModel(std::move(data));
}

}  // namespace geardyn
