/// @file
/// @brief MakeTdSymmetry and ApplyTdSymmetry (td_symmetry.hpp).
#include "td_symmetry.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <variant>

#include "geardyn/system/common_period.hpp"

namespace geardyn::internal {
namespace {

/// Relative tolerance on r_k P_S / s_k being a whole number [-].
constexpr double kRatioTolerance = 1e-9;
/// Multiples of lcm(s_k) tried before falling back to the full period (ratios far from rational).
constexpr std::int64_t kMaxMultiples = 1000000;

/// s_k of a mesh: the core's symmetry period when it is a valid divisor of its period, else P_k.
std::int64_t SymmetryPeriod(const SystemMesh& mesh) {
  const std::int64_t p = PeriodMeshes(mesh.core);
  if (const auto* nl = std::get_if<std::shared_ptr<const NonlinearMeshCore>>(&mesh.core)) {
    const std::int64_t s = (*nl)->symmetry_period_meshes();
    if (s >= 1 && p % s == 0) return s;
  }
  return p;
}

}  // namespace

bool TdSymmetry::any_shift() const {
  return std::any_of(shifts.begin(), shifts.end(), [](std::int64_t c) { return c > 0; });
}

TdSymmetry MakeTdSymmetry(const TdSystem& sys, bool use_symmetry) {
  const SystemModel& model = sys.model;
  const int num_meshes = model.num_meshes();
  TdSymmetry full;  // the full-period plan: P, no shift
  full.period_meshes = model.period_meshes();
  if (HasSeveralMeshFrequencies(model)) {
    const std::int64_t common = FindCommonPeriodMeshes(model, kMaxCommonPeriodMeshes);
    if (common > 0) {
      full.period_meshes = common;
    } else {
      full.quasi_periodic = true;
    }
  }
  full.shifts.assign(static_cast<std::size_t>(num_meshes), 0);
  if (!use_symmetry) return full;
  std::vector<std::int64_t> s(static_cast<std::size_t>(num_meshes));
  std::int64_t base = 1;
  for (int k = 0; k < num_meshes; ++k) {
    s[static_cast<std::size_t>(k)] = SymmetryPeriod(model.meshes()[static_cast<std::size_t>(k)]);
    base = std::lcm(base, s[static_cast<std::size_t>(k)]);
  }
  // Smallest P_S = j·base below P with every r_k P_S / s_k whole.
  for (std::int64_t j = 1; j <= kMaxMultiples && j * base < full.period_meshes; ++j) {
    const std::int64_t candidate = j * base;
    TdSymmetry plan;
    plan.period_meshes = candidate;
    plan.shifts.assign(static_cast<std::size_t>(num_meshes), 0);
    bool exact = true;
    for (int k = 0; k < num_meshes && exact; ++k) {
      const SystemMesh& mesh = model.meshes()[static_cast<std::size_t>(k)];
      const double c = mesh.phase_ratio * static_cast<double>(candidate) /
                       static_cast<double>(s[static_cast<std::size_t>(k)]);
      const double whole = std::round(c);
      exact = whole >= 1.0 && std::abs(c - whole) <= kRatioTolerance * whole;
      if (exact) plan.shifts[static_cast<std::size_t>(k)] = static_cast<std::int64_t>(whole);
    }
    if (!exact) continue;
    // Only the tooth-body cores with a true symmetry (s_k < P_k) shift anything.
    for (int k = 0; k < num_meshes; ++k) {
      const SystemMesh& mesh = model.meshes()[static_cast<std::size_t>(k)];
      if (!std::holds_alternative<std::shared_ptr<const NonlinearMeshCore>>(mesh.core) ||
          s[static_cast<std::size_t>(k)] == PeriodMeshes(mesh.core)) {
        plan.shifts[static_cast<std::size_t>(k)] = 0;
      }
    }
    return plan;
  }
  return full;
}

void ApplyTdSymmetry(const TdSystem& sys, const TdSymmetry& sym, int multiple,
                     Eigen::Ref<VectorX> y) {
  for (const TdMeshTerm& term : sys.terms) {
    const std::int64_t count =
        static_cast<std::int64_t>(multiple) * sym.shifts[static_cast<std::size_t>(term.mesh)];
    if (count == 0 || term.nonlinear == nullptr || term.num_internal == 0) continue;
    auto part = y.segment(term.internal_offset, term.num_internal);
    for (std::int64_t c = 0; c < count; ++c) term.nonlinear->ApplySymmetryShift(part);
  }
}

}  // namespace geardyn::internal
