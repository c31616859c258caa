// kExactSteps: Φ(T) = Π_k expm(A_k Δt_k) for piecewise-constant coefficients (spec 02), exact up
// to round-off. Consecutive equal steps are merged (expm(AΔt1) expm(AΔt2) = expm(A(Δt1+Δt2))); a
// sequence that repeats with a sub-period of d steps (a hunting period made of identical mesh
// cycles) is raised to its power by squaring.
#include <cmath>
#include <cstdint>
#include <unsupported/Eigen/MatrixFunctions>

#include "floquet/floquet_internal.hpp"
#include "geardyn/common/check.hpp"

namespace geardyn::internal {
int RepeatingStepPeriod(const std::vector<double>& dt, const std::vector<const MatrixX*>& A,
                        double period_s) {
  const int K = static_cast<int>(dt.size());
  for (int d = 1; d < K; ++d) {
    if (K % d != 0) continue;
    bool ok = true;
    for (int i = 0; i + d < K && ok; ++i) {
      ok = std::abs(dt[i] - dt[i + d]) <= 1e-13 * period_s &&
           (A[i] == A[i + d] || *A[i] == *A[i + d]);
    }
    if (ok) return d;
  }
  return K;
}

MergedSteps MergeEqualSteps(const StateSystem& sys) {
  MergedSteps m;
  for (std::size_t k = 0; k < sys.step_matrices.size(); ++k) {
    if (!m.A.empty() && *m.A.back() == sys.step_matrices[k]) {
      m.dt.back() += sys.step_durations[k];
    } else {
      m.dt.push_back(sys.step_durations[k]);
      m.A.push_back(&sys.step_matrices[k]);
      m.index.push_back(static_cast<int>(k));
    }
  }
  return m;
}

double StepProductFactors(const MergedSteps& merged, int d) {
  double factors = d;
  for (int k = 0; k < d; ++k) {
    factors += merged.A[k]->cwiseAbs().colwise().sum().maxCoeff() * merged.dt[k];
  }
  return factors;
}

MonodromyOutcome ExactStepsMonodromy(const StateSystem& sys) {
  GEARDYN_THROW_UNLESS(!sys.step_matrices.empty(),
                       "method: exact_steps needs piecewise-constant coefficients (steps)");
  const MergedSteps merged = MergeEqualSteps(sys);
  const std::vector<double>& dt = merged.dt;
  const std::vector<const MatrixX*>& A = merged.A;
  const int d = RepeatingStepPeriod(dt, A, sys.period_s);
  const std::int64_t power = static_cast<std::int64_t>(dt.size()) / d;
  MonodromyOutcome out;
  ScaledMatrix cycle{MatrixX::Identity(sys.dim, sys.dim), 0.0};
  long products = 0;
  for (int k = 0; k < d; ++k) {
    MatrixX E = (*A[k] * dt[k]).exp();
    if (!E.allFinite()) {
      // One step's exponential overflowed (a growth like e^{1000} within a step: k < 0 for a
      // long interval). Take it as the scaled power of s sub-steps of ‖AΔt‖₁/s ≤ 512 (each
      // e^{≤512}, finite), so that the growth lands in log_scale and the exponents stay finite
      // instead of a NaN monodromy and an "undetermined" verdict (stress suite, issue 16).
      const double norm = A[k]->cwiseAbs().colwise().sum().maxCoeff() * dt[k];
      const auto s = static_cast<std::int64_t>(std::ceil(norm / 512.0));
      if (std::isfinite(norm) && s > 1) {
        const ScaledMatrix sub{(*A[k] * (dt[k] / static_cast<double>(s))).exp(), 0.0};
        if (sub.matrix.allFinite()) {
          const ScaledMatrix step = ScaledPower(sub, s, &products);
          cycle.matrix = step.matrix * cycle.matrix;
          cycle.log_scale += step.log_scale;
          cycle.Normalize();
          continue;
        }
      }
    }
    cycle.matrix = E * cycle.matrix;
    cycle.Normalize();
  }
  out.phi = power == 1 ? cycle : ScaledPower(cycle, power, &products);
  out.steps = d;
  out.evaluations = d;
  out.num_factors = StepProductFactors(merged, d) * static_cast<double>(power);
  return out;
}

}  // namespace geardyn::internal
