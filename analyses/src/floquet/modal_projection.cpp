// kModalProjection: Floquet analysis of the system projected on its lowest LTI modes.
//
// q ≈ V η with V (n × m) the lowest M-orthonormal modes of the mean system (K̄, M): the reduced
// system Vᵀ M V η̈ + Vᵀ C(t) V η̇ + Vᵀ K(t) V η = 0 (Galerkin) is analysed by the best method for
// its form (kExactSteps for steps, else kMagnus). **Error estimate**: the same analysis with
// m₂ = ⌈1.5 m⌉ modes; the estimate is the largest change of the m-mode multipliers (each matched
// to the nearest m₂-mode multiplier). It measures the truncation error of the multipliers of the
// retained (low) modes; the reported multipliers are the 2m multipliers of the m₂-mode run matched
// to those (more accurate than the m-mode ones, and covered by the estimate) — all 2n when m₂ = n
// (a complete basis, estimate 0 from the projection). Multipliers of the discarded high modes are
// not reported: parametric resonances that involve them (ω_m ≈ 2ω_k/j with ω_k above the
// retained range) are outside the estimate. num_modes = 0: m = 12, then m ← m₂ until the
// estimate meets the tolerance or m₂ = n.
#include <algorithm>
#include <cmath>
#include <memory>

#include "floquet/floquet_internal.hpp"

namespace geardyn::internal {

PeriodicSecondOrderSystem ProjectSystem(const PeriodicSecondOrderSystem& system, const MatrixX& V) {
  PeriodicSecondOrderSystem out;
  out.period_s = system.period_s;
  out.mass = V.transpose() * system.mass * V;
  out.mass = 0.5 * (out.mass + out.mass.transpose()).eval();
  for (const PeriodicStep& s : system.steps) {
    PeriodicStep r;
    r.duration_s = s.duration_s;
    r.stiffness = V.transpose() * s.stiffness * V;
    if (s.damping.size()) r.damping = V.transpose() * s.damping * V;
    out.steps.push_back(std::move(r));
  }
  if (system.coefficients) {
    auto buffers = std::make_shared<std::pair<MatrixX, MatrixX>>();
    out.coefficients = [buffers, V, f = system.coefficients](double t, MatrixX* K, MatrixX* C) {
      f(t, &buffers->first, &buffers->second);
      *K = V.transpose() * buffers->first * V;
      if (buffers->second.size()) {
        *C = V.transpose() * buffers->second * V;
      } else {
        C->resize(0, 0);
      }
    };
  }
  const MatrixXc Vc = V.cast<std::complex<double>>();
  for (const MatrixXc& K : system.stiffness_harmonics) {
    out.stiffness_harmonics.push_back(Vc.transpose() * K * Vc);
  }
  for (const MatrixXc& C : system.damping_harmonics) {
    out.damping_harmonics.push_back(Vc.transpose() * C * Vc);
  }
  return out;
}

FloquetResult ModalProjectionFloquet(
    const std::function<MatrixX(int)>& modes, int num_dofs,
    const std::function<PeriodicSecondOrderSystem(const MatrixX&)>& project,
    const FloquetOptions& options) {
  FloquetOptions inner = options;
  inner.method = FloquetMethod::kAuto;
  inner.modal_projection_min_dofs = num_dofs + 1;  // never recurse
  inner.keep_monodromy = false;
  auto run = [&](int m) {
    const PeriodicSecondOrderSystem reduced = project(modes(m));
    const FloquetMethod method = SelectGenericMethod(reduced, inner);
    const StateSystem sys = MakeStateSystem(reduced, inner.deflate_rigid_modes);
    FloquetResult r = ComputeFloquetState(sys, inner, method);
    r.summary.counters["inner_method"] = static_cast<long>(method);
    return r;
  };
  int m = options.num_modes > 0 ? std::min(options.num_modes, num_dofs) : std::min(12, num_dofs);
  FloquetResult coarse = run(m);
  while (true) {
    const int m2 = std::min(num_dofs, std::max(m + 1, static_cast<int>(std::ceil(1.5 * m))));
    FloquetResult fine = m2 == m ? coarse : run(m2);
    // With m₂ = n the projection is complete (a change of basis): the m₂ run is the full system.
    const double est = m2 >= num_dofs && options.num_modes == 0
                           ? 0.0
                           : MatchedDistance(coarse.multipliers, fine.multipliers);
    if (options.num_modes > 0 || est <= options.tolerance || m2 >= num_dofs) {
      if (m2 > m && !(m2 >= num_dofs && options.num_modes == 0)) {
        // Report the 2m multipliers of the m₂ run that continue the m-mode ones: those are what
        // the estimate covers (the m₂ run's top modes are the least resolved).
        std::vector<bool> used(fine.multipliers.size(), false);
        VectorXc l(coarse.multipliers.size()), e(coarse.multipliers.size());
        for (int i = 0; i < coarse.multipliers.size(); ++i) {
          int best = -1;
          for (int j = 0; j < fine.multipliers.size(); ++j) {
            if (!used[j] &&
                (best < 0 || std::abs(fine.multipliers[j] - coarse.multipliers[i]) <
                                 std::abs(fine.multipliers[best] - coarse.multipliers[i]))) {
              best = j;
            }
          }
          used[best] = true;
          l[i] = fine.multipliers[best];
          e[i] = fine.exponents[best];
        }
        fine.multipliers = l;
        fine.exponents = e;
        SortSpectrum(&fine.multipliers, &fine.exponents);
        fine.max_abs_multiplier = fine.multipliers.cwiseAbs().maxCoeff();
        fine.stability_margin = 1.0 - fine.max_abs_multiplier;
      }
      fine.summary.error_estimate = std::max(fine.summary.error_estimate, est);
      fine.summary.counters["modes"] = m;
      fine.summary.counters["modes_check"] = m2;
      fine.method_used = FloquetMethod::kModalProjection;
      if (est > options.tolerance && fine.summary.ok()) {
        fine.summary.status = Status::kToleranceNotMet;
        fine.summary.message = "modal_projection: the multipliers change by " +
                               std::to_string(est) + " from " + std::to_string(m) + " to " +
                               std::to_string(m2) + " modes";
      }
      fine.stable = fine.max_abs_multiplier <= 1.0 + fine.summary.error_estimate;
      return fine;
    }
    m = m2;
    coarse = std::move(fine);
  }
}

}  // namespace geardyn::internal
