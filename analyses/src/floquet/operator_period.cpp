// One operator period of the homogeneous Floquet problem (P_K = OperatorPeriodMeshes, issue 12).
// Tooth errors give ε a hunting period of up to lcm(z1, z2) mesh cycles
// (SystemModel::period_meshes()), but ε enters only the load f(θ) = Gᵀ K2 ε: it forces the system
// and does not excite it parametrically. Over the model's period the monodromy would be Φ_K^(P/P_K)
// (multipliers raised to that power, and P/P_K times the work).
#include <cmath>
#include <numbers>
#include <numeric>
#include <variant>

#include "floquet/floquet_internal.hpp"
#include "geardyn/common/check.hpp"
#include "geardyn/common/overloaded.hpp"
#include "geardyn/system/common_period.hpp"

namespace geardyn::internal {

std::int64_t FloquetPeriodMeshes(const SystemModel& model) {
  if (!HasSeveralMeshFrequencies(model)) return OperatorPeriodMeshes(model);
  return FindCommonPeriodMeshes(model, kMaxFloquetCommonPeriodMeshes);
}

SystemSteps OperatorSteps(const SystemModel& model, std::int64_t operator_period) {
  SystemSteps all = CollectSystemSteps(model);
  if (operator_period == all.period_meshes) return all;
  // K and C repeat every 2π·P_K, so the breakpoints in [0, 2π·P_K) are one operator period's;
  // the last interval ends at 2π·P_K (interval_end uses `period`).
  SystemSteps out;
  out.period_meshes = operator_period;
  out.period = 2.0 * std::numbers::pi * static_cast<double>(operator_period);
  const double end = out.period * (1.0 - 1e-13);
  Eigen::Index count = 0;
  while (count < all.breakpoints.size() && all.breakpoints[count] < end) ++count;
  out.breakpoints = all.breakpoints.head(count);
  return out;
}

void CheckHillSize(int dim, int harmonics, bool requested) {
  const long size = static_cast<long>(dim) * (2L * harmonics + 1);
  if (size <= kMaxHillSize) return;
  // Complex dense eigenproblem with vectors: 16·S² bytes per matrix (the matrix, its Schur
  // form and the vectors: about 3 of them), ≈ 25·S³ complex flops (Golub & Van Loan §7.5).
  const double mb = 3.0 * 16.0 * static_cast<double>(size) * static_cast<double>(size) / 1e6;
  const double gflop = 25.0 * std::pow(static_cast<double>(size), 3) / 1e9;
  const int max_h = std::max(0, static_cast<int>((kMaxHillSize / std::max(dim, 1) - 1) / 2));
  GEARDYN_THROW_UNLESS(false, (requested ? "hill_harmonics: " : "method: hill: ")
                                  << "H = " << harmonics << " on a state of dimension " << dim
                                  << " makes a complex Hill matrix of size " << size << " (" << mb
                                  << " MB, about " << gflop
                                  << " Gflop per eigen solve, several solves for the estimate); "
                                     "at most "
                                  << kMaxHillSize << (max_h >= 1 ? ", i.e. H <= " : "")
                                  << (max_h >= 1 ? std::to_string(max_h) : std::string())
                                  << (max_h >= 1 ? "" : ": this system is too large for hill")
                                  << "; use exact_steps, magnus or arpack_monodromy");
}

}  // namespace geardyn::internal
