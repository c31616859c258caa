#include "mesh_coefficients.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "geardyn/common/overloaded.hpp"

namespace geardyn::internal {

std::vector<const Coefficient*> MeshOperatorCoefficients(const MeshCore& core, bool with_load) {
  std::vector<const Coefficient*> out;
  std::visit(Overloaded{
                 [&](const LinearMeshCore& linear) {
                   // The mean-LTI stiffness is constant by construction; its ε still varies.
                   if (!linear.is_mean_lti() || with_load) out.push_back(&linear.stiffness());
                   if (with_load && linear.transmission_error()) {
                     out.push_back(&*linear.transmission_error());
                   }
                 },
                 [&](const SliceMeshCore& slice) { out.push_back(&slice.stiffness()); },
                 [&](const std::shared_ptr<const NonlinearMeshCore>&) {},
             },
             core);
  return out;
}

std::int64_t MeshCorePeriod(const MeshCore& core) {
  return std::visit(
      Overloaded{
          [](const LinearMeshCore& linear) { return PeriodMeshes(linear); },
          [](const SliceMeshCore& slice) { return PeriodMeshes(slice); },
          [](const std::shared_ptr<const NonlinearMeshCore>&) { return std::int64_t{1}; },
      },
      core);
}

bool AllStepwise(const std::vector<const Coefficient*>& coefs) {
  return std::all_of(coefs.begin(), coefs.end(), [](const Coefficient* c) {
    return Classify(*c) != TimeDependence::kSmoothPeriodic;
  });
}

std::vector<double> SortAndMerge(std::vector<double> points, double period, double tol) {
  points.push_back(0.0);
  std::sort(points.begin(), points.end());
  std::vector<double> merged;
  const double gap = tol * period;
  for (const double p : points) {
    if (merged.empty() || p - merged.back() > gap) merged.push_back(p);
  }
  while (merged.size() > 1 && period - merged.back() <= gap) merged.pop_back();
  return merged;
}

std::vector<double> RawBreakpoints(const std::vector<const Coefficient*>& coefs,
                                   std::int64_t period_meshes) {
  std::vector<double> points;
  for (const Coefficient* coef : coefs) {
    if (Classify(*coef) == TimeDependence::kConstant) continue;
    const auto& steps = std::get<PiecewiseConstantCoefficient>(*coef);
    const std::int64_t copies = period_meshes / steps.period_meshes();
    const double own_period = 2.0 * std::numbers::pi * static_cast<double>(steps.period_meshes());
    for (std::int64_t j = 0; j < copies; ++j) {
      for (int k = 0; k < steps.num_intervals(); ++k) {
        points.push_back(steps.interval_begin(k) + own_period * static_cast<double>(j));
      }
    }
  }
  return points;
}

std::vector<double> UnionBreakpoints(const std::vector<const Coefficient*>& coefs,
                                     std::int64_t period_meshes, double merge_tol) {
  const double period = 2.0 * std::numbers::pi * static_cast<double>(period_meshes);
  return SortAndMerge(RawBreakpoints(coefs, period_meshes), period, merge_tol);
}

}  // namespace geardyn::internal
