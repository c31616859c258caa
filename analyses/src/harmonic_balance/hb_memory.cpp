// HarmonicBalanceSolver: the working-memory estimates of the dense and sparse harmonic paths
// and the forcing classes they solve (harmonic_balance.hpp "Long hunting periods").
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

#include "geardyn/numerics/symmetric_eigen.hpp"
#include "geardyn/system/system_harmonics.hpp"
#include "hb_solver_impl.hpp"

namespace geardyn {
namespace {
using internal::kMaxHbBytes;
}  // namespace

double HarmonicBalanceSolver::Impl::EstimateBytes(int H) const {
  const double q = static_cast<double>(ClassModulus());
  const double n = model.num_dofs();
  const double meshes = model.num_meshes();
  const double kmax = H * q + q / 2.0;
  const double r = 2.0 * meshes;
  // Mesh harmonics (3 arrays of 2×2 complex up to (2H+1)q) and the expansion's samples (8
  // channels, real and complex), the response (n × (k_max+1)), the sampler (up to 16(k_max+1)
  // samples of q, q̇ and the FFT buffers, and per mesh K2, C2, ε), the per-harmonic solves (at
  // most (2H+2) min(q, 2H+2) kept harmonics of n(1+r) columns), the class coupling ((2H+2)r)².
  const double harm = (2.0 * H + 2.0) * q;
  double bytes = meshes * harm * 160.0 + harm * 2.0 * 8.0 * 24.0;
  bytes += 16.0 * n * (kmax + 1.0);
  bytes += 16.0 * (kmax + 1.0) * (4.0 * 8.0 * n + meshes * 96.0);
  bytes += 16.0 * std::min(kmax + 1.0, (2.0 * H + 2.0) * q) * n * (1.0 + r) / std::max(q, 1.0) *
           std::min(q, 2.0 * H + 2.0);
  bytes += 16.0 * std::pow((2.0 * H + 2.0) * r, 2);
  return bytes;
}

// Classes c ∈ [0, q/2] that some load line can reach: the residues mod q of the coefficient
// parts' harmonics (multiples of P/P_b) shifted by ± each sideband line (m P/P_s).
std::vector<int> HarmonicBalanceSolver::Impl::CandidateClasses() const {
  const std::int64_t q = ClassModulus();
  const std::int64_t P = model.period_meshes();
  std::vector<char> seen(static_cast<size_t>(q / 2 + 1), 0);
  seen[0] = 1;
  for (const SystemMesh& mesh : model.meshes()) {
    const auto* c = std::get_if<LinearMeshCore>(&mesh.core);
    if (c == nullptr) continue;
    const std::int64_t step = P / CoefficientPeriodMeshes(*c);  // coefficient harmonics' spacing
    const std::int64_t residues = q / std::gcd(step % q == 0 ? q : step % q, q);
    std::vector<std::int64_t> shifts = {0};
    const TransmissionErrorSidebands& sb = c->sidebands();
    for (int l = 0; l < sb.size(); ++l) {
      const std::int64_t m = (sb.harmonics[static_cast<size_t>(l)] * (P / sb.period_meshes)) % q;
      shifts.push_back(m);
      shifts.push_back(q - m);
    }
    for (std::int64_t t = 0; t < residues; ++t) {
      for (std::int64_t shift : shifts) {
        const std::int64_t r = ((t * step) % q + shift) % q;
        seen[static_cast<size_t>(std::min(r, q - r))] = 1;
      }
    }
  }
  std::vector<int> out;
  for (size_t c = 0; c < seen.size(); ++c) {
    if (seen[c]) out.push_back(static_cast<int>(c));
  }
  return out;
}

double HarmonicBalanceSolver::Impl::EstimateSparseBytes(int H, std::string* why) const {
  const std::int64_t q = ClassModulus();
  const std::int64_t P = model.period_meshes();
  for (const SystemMesh& mesh : model.meshes()) {
    const auto* c = std::get_if<LinearMeshCore>(&mesh.core);
    if (c == nullptr) {
      *why = "mesh '" + mesh.name + "' is not a linear core";
      return std::numeric_limits<double>::infinity();
    }
    // The coefficient part is expanded at its own period: (H+1) q P_b/P harmonics.
    const double nb = (H + 1.0) * static_cast<double>(q) *
                      static_cast<double>(CoefficientPeriodMeshes(*c)) / static_cast<double>(P);
    if (nb > 1e6) {
      *why = "mesh '" + mesh.name + "': its ε coefficient repeats over " +
             std::to_string(CoefficientPeriodMeshes(*c)) +
             " mesh cycles (pitch errors?); only a runout has a sparse form (sidebands)";
      return std::numeric_limits<double>::infinity();
    }
  }
  if ((H + 2.0) * static_cast<double>(q) >= std::numeric_limits<int>::max()) {
    *why = "the kept harmonics exceed the index range";
    return std::numeric_limits<double>::infinity();
  }
  const double classes = static_cast<double>(CandidateClasses().size());
  const double n = model.num_dofs();
  const double r = 2.0 * model.num_meshes();
  const double kept = classes * (2.0 * H + 2.0);
  // Per kept harmonic the LTI solve [F, Gᵀ] (n(1+r)) and its response; the class coupling
  // ((2H+2) r)²; the envelope samples (≤ 8(H+2) per operator period, n × classes × 2).
  return 16.0 * kept * n * (2.0 + r) + 16.0 * std::pow((2.0 * H + 2.0) * r, 2) +
         16.0 * classes * 2.0 * n * std::max(256.0, 16.0 * (H + 2.0));
}

// The sparse path when the dense one would exceed the memory limit and the model allows it.
bool HarmonicBalanceSolver::Impl::UseSparse(int H) const {
  if (options.harmonic_storage == HbHarmonicStorage::kSparse) return true;
  if (options.harmonic_storage == HbHarmonicStorage::kDense) return false;
  std::string why;
  return EstimateBytes(H) > kMaxHbBytes && EstimateSparseBytes(H, &why) <= kMaxHbBytes;
}

}  // namespace geardyn
