#include "geardyn/system/system_steps.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <variant>
#include <vector>

#include "geardyn/common/check.hpp"
#include "geardyn/system/common_period.hpp"
#include "mesh_coefficients.hpp"

namespace geardyn {

double SystemSteps::interval_end(int k) const {
  return k + 1 < num_intervals() ? breakpoints[k + 1] : breakpoints[0] + period;
}

namespace {

/// Own-cycle copies r·P/P_own of a mesh over P system mesh cycles (whole: P is a common period).
std::int64_t OwnCopies(const SystemMesh& mesh, std::int64_t period_meshes, std::int64_t own,
                       const char* analysis) {
  const double copies =
      mesh.phase_ratio * static_cast<double>(period_meshes) / static_cast<double>(own);
  const double whole = std::round(copies);
  GEARDYN_THROW_UNLESS(whole >= 1.0 && std::abs(copies - whole) <= 1e-6,
                       analysis << ": mesh '" << mesh.name << "' (phase ratio " << mesh.phase_ratio
                                << ", period " << own << ") does not repeat after " << period_meshes
                                << " system mesh cycles");
  return static_cast<std::int64_t>(whole);
}

/// System phase θ = (θ_k − φ_k)/r_k of own phase θ_k, reduced to [0, period).
double SystemPhase(const SystemMesh& mesh, double own_phase, double period) {
  const double theta = std::fmod((own_phase - mesh.phase_offset) / mesh.phase_ratio, period);
  return theta < 0.0 ? theta + period : theta;
}

}  // namespace

void CheckSingleMeshFrequency(const SystemModel& model, const char* analysis) {
  for (const SystemMesh& mesh : model.meshes()) {
    GEARDYN_THROW_UNLESS(std::abs(mesh.phase_ratio - 1.0) <= 1e-12,
                         analysis << ": mesh '" << mesh.name << "' runs at " << mesh.phase_ratio
                                  << " times the first mesh frequency; meshes at different "
                                     "frequencies (e.g. a two-stage train) make the system "
                                     "quasi-periodic, and this analysis needs one mesh frequency");
  }
}

bool HasPiecewiseConstantOperator(const SystemModel& model) {
  for (const SystemMesh& mesh : model.meshes()) {
    if (!internal::AllStepwise(internal::MeshOperatorCoefficients(mesh.core, false))) return false;
  }
  return true;
}

SystemSteps CollectSystemSteps(const SystemModel& model, double merge_tol) {
  GEARDYN_THROW_UNLESS(std::isfinite(merge_tol) && merge_tol >= 0.0,
                       "CollectSystemSteps: merge_tol must be finite and >= 0, got " << merge_tol);
  SystemSteps steps;
  // One frequency: the model's period, however long (a hunting period lcm(z1, z2) may exceed
  // the common-period search bound); several: their common period.
  steps.period_meshes =
      HasSeveralMeshFrequencies(model) ? FindCommonPeriodMeshes(model) : model.period_meshes();
  GEARDYN_THROW_UNLESS(steps.period_meshes > 0,
                       "CollectSystemSteps: the meshes run at incommensurate frequencies (no "
                       "common period of at most 100000 mesh cycles)");
  steps.period = 2.0 * std::numbers::pi * static_cast<double>(steps.period_meshes);
  std::vector<double> points;
  for (const SystemMesh& mesh : model.meshes()) {
    const std::vector<const Coefficient*> coefs =
        internal::MeshOperatorCoefficients(mesh.core, false);
    GEARDYN_THROW_UNLESS(internal::AllStepwise(coefs),
                         "CollectSystemSteps: mesh '"
                             << mesh.name
                             << "' has a smooth (Fourier or table) stiffness; the step structure "
                                "exists only for constant and piecewise-constant coefficients");
    const std::int64_t own = internal::MeshCorePeriod(mesh.core);
    const std::vector<double> mesh_points = internal::RawBreakpoints(coefs, own);
    const double own_period = 2.0 * std::numbers::pi * static_cast<double>(own);
    const std::int64_t copies = OwnCopies(mesh, steps.period_meshes, own, "CollectSystemSteps");
    for (std::int64_t j = 0; j < copies; ++j) {
      for (const double b : mesh_points) {
        points.push_back(SystemPhase(mesh, b + own_period * static_cast<double>(j), steps.period));
      }
    }
  }
  const std::vector<double> merged =
      internal::SortAndMerge(std::move(points), steps.period, merge_tol);
  steps.breakpoints =
      Eigen::Map<const VectorX>(merged.data(), static_cast<Eigen::Index>(merged.size()));
  return steps;
}

VectorX CollectSystemKinks(const SystemModel& model, std::int64_t period_meshes, double merge_tol) {
  GEARDYN_THROW_UNLESS(period_meshes >= 1,
                       "CollectSystemKinks: period_meshes must be >= 1, got " << period_meshes);
  GEARDYN_THROW_UNLESS(std::isfinite(merge_tol) && merge_tol >= 0.0,
                       "CollectSystemKinks: merge_tol must be finite and >= 0, got " << merge_tol);
  const double period = 2.0 * std::numbers::pi * static_cast<double>(period_meshes);
  std::vector<double> points;
  for (const SystemMesh& mesh : model.meshes()) {
    for (const Coefficient* coef : internal::MeshOperatorCoefficients(mesh.core, false)) {
      // Mesh-phase points of one own period 2π·P_c: steps' interval starts, tables' samples.
      std::vector<double> own_points;
      std::int64_t own = 1;
      if (const auto* steps = std::get_if<PiecewiseConstantCoefficient>(coef)) {
        own = steps->period_meshes();
        for (int k = 0; k < steps->num_intervals(); ++k)
          own_points.push_back(steps->interval_begin(k));
      } else if (const auto* table = std::get_if<TableCoefficient>(coef)) {
        own = table->period_meshes();
        const double own_period = 2.0 * std::numbers::pi * static_cast<double>(own);
        for (int s = 0; s < table->num_samples(); ++s) {
          own_points.push_back(own_period * s / table->num_samples());
        }
      } else {
        continue;  // constant or Fourier: analytic everywhere
      }
      const double own_period = 2.0 * std::numbers::pi * static_cast<double>(own);
      // Over 2π·P the mesh runs r·P of its own cycles (at least one period of the coefficient).
      const double own_cycles =
          mesh.phase_ratio * static_cast<double>(period_meshes) / static_cast<double>(own);
      const std::int64_t copies =
          std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil(own_cycles - 1e-9)));
      for (std::int64_t j = 0; j < copies; ++j) {
        for (const double b : own_points) {
          points.push_back(SystemPhase(mesh, b + own_period * static_cast<double>(j), period));
        }
      }
    }
  }
  const std::vector<double> merged = internal::SortAndMerge(std::move(points), period, merge_tol);
  return Eigen::Map<const VectorX>(merged.data(), static_cast<Eigen::Index>(merged.size()));
}

}  // namespace geardyn
