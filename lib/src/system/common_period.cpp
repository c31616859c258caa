#include "geardyn/system/common_period.hpp"

#include <cmath>

#include "geardyn/common/check.hpp"

namespace geardyn {

bool HasSeveralMeshFrequencies(const SystemModel& model) {
  for (const SystemMesh& mesh : model.meshes()) {
    if (std::abs(mesh.phase_ratio - 1.0) > 1e-12) return true;
  }
  return false;
}

std::int64_t FindCommonPeriodMeshes(const SystemModel& model, std::int64_t max_period_meshes,
                                    double cycle_tolerance) {
  GEARDYN_THROW_UNLESS(max_period_meshes >= 1,
                       "max_period_meshes: must be >= 1, got " << max_period_meshes);
  GEARDYN_THROW_UNLESS(
      std::isfinite(cycle_tolerance) && cycle_tolerance >= 0.0 && cycle_tolerance <= 1e-3,
      "cycle_tolerance: must be in [0, 1e-3], got " << cycle_tolerance);
  const std::int64_t base = model.period_meshes();
  if (!HasSeveralMeshFrequencies(model)) return base <= max_period_meshes ? base : 0;
  // q is a multiple of the lcm of the P_k (model.period_meshes()): at q = j·base every
  // r_k q / P_k = r_k j (base / P_k) is whole iff r_k j · (base / P_k) is.
  for (std::int64_t q = base; q <= max_period_meshes; q += base) {
    bool whole = true;
    for (const SystemMesh& mesh : model.meshes()) {
      const double cycles =
          mesh.phase_ratio * static_cast<double>(q) / static_cast<double>(PeriodMeshes(mesh.core));
      const double nearest = std::round(cycles);
      if (nearest < 1.0 || std::abs(cycles - nearest) > cycle_tolerance) {
        whole = false;
        break;
      }
    }
    if (whole) return q;
  }
  return 0;
}

}  // namespace geardyn
