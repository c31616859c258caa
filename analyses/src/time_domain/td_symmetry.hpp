/// @file
/// @brief The period of the steady-state test modulo the cores' symmetry (issue 14):
/// NonlinearMeshCore::symmetry_period_meshes and ApplySymmetryShift combined over the meshes.
///
/// A steady response of identical tooth bodies repeats after one mesh cycle up to the relabelling
/// S "tooth k → k + 1" (x(t + T_m) = S x(t)), while its full period is the hunting period
/// lcm(z1, z2). The steady test and the recording then use the symmetry period P_S and compare
/// the state after it with the shifted state before it (time_response.cpp).
///
/// **Several meshes.** Mesh k's phase is θ_k = r_k θ + φ_k: P_S system mesh cycles advance it by
/// r_k P_S cycles, which must be a whole number c_k of its core's symmetry periods s_k (a linear or
/// slice core: its own period P_k, shift identity). P_S is the smallest multiple of lcm_k(s_k) for
/// which every r_k P_S / s_k is an integer (to 1e-9); mesh k's internal coordinates are then
/// shifted c_k times. When no such P_S lies below the model's period P (= lcm of the cores' P_k),
/// or the symmetry is switched off, the plan is P with no shift (the full-period test).
///
/// **Model period P.** With every r_k = 1, P = model.period_meshes(). Meshes at different
/// frequencies (a two-stage train) repeat together only after the common period
/// (FindCommonPeriodMeshes, common_period.hpp: r = 7/40 gives 40 cycles); without one up to
/// kMaxCommonPeriodMeshes the response is quasi-periodic, the plan keeps model.period_meshes()
/// and says so (`quasi_periodic`): a steady test over it cannot pass.
#pragma once

#include <cstdint>
#include <vector>

#include "geardyn/common/eigen_types.hpp"
#include "td_system.hpp"

namespace geardyn::internal {

/// Longest common period of meshes at different frequencies searched [system mesh cycles].
inline constexpr std::int64_t kMaxCommonPeriodMeshes = 100000;

/// @brief Period of the steady test and the shifts of the internal coordinates over it.
struct TdSymmetry {
  std::int64_t period_meshes = 1;  ///< P_S [system mesh cycles]
  /// Meshes at incommensurate frequencies (no common period up to kMaxCommonPeriodMeshes).
  bool quasi_periodic = false;
  /// Per mesh term (TdSystem::terms order): applications c_k of its core's S per P_S (0: none).
  std::vector<std::int64_t> shifts;
  /// True when some mesh's internal coordinates are shifted.
  bool any_shift() const;
};

/// @brief The plan of the @file for `sys`; with use_symmetry false, P with no shift.
TdSymmetry MakeTdSymmetry(const TdSystem& sys, bool use_symmetry);

/// @brief y ← S^multiple y on the internal coordinates of a state part y (n: positions or
/// velocities) — S^multiple maps the state at θ to the steady state at θ + 2π·multiple·P_S. The
/// system DOFs are unchanged. No allocation.
void ApplyTdSymmetry(const TdSystem& sys, const TdSymmetry& sym, int multiple,
                     Eigen::Ref<VectorX> y);

}  // namespace geardyn::internal
