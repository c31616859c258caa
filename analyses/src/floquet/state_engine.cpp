// ComputeFloquetState: the single dispatch on a StateSystem (architecture §3.4) and the
// generic entry ComputeFloquet(PeriodicSecondOrderSystem, options).
#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <vector>

#include "floquet/floquet_internal.hpp"
#include "geardyn/common/check.hpp"

namespace geardyn::internal {

FloquetResult ComputeFloquetState(const StateSystem& sys, const FloquetOptions& options,
                                  FloquetMethod method) {
  if (method == FloquetMethod::kArpackMonodromy) return ArpackMonodromyFloquet(sys, options);
  FloquetResult result;
  result.method_used = method;
  result.period_s = sys.period_s;
  result.summary.warnings = sys.warnings;
  result.summary.counters["num_rigid_modes"] = sys.num_rigid;
  result.summary.counters["state_dimension"] = sys.dim;
  double truncation = 0.0;
  bool converged = true;
  std::string message;
  if (sys.dim == 0) {
    // Only rigid-body modes.
  } else if (method == FloquetMethod::kHill) {
    const HillOutcome hill = HillExponents(sys, options.hill_harmonics, options.tolerance);
    result.exponents.resize(sys.dim);
    result.multipliers.resize(sys.dim);
    for (int i = 0; i < sys.dim; ++i) {
      // Principal branch of ln λ / T, like the other methods.
      const std::complex<double> lambda = std::exp(hill.exponents[i] * sys.period_s);
      result.multipliers[i] = lambda;
      result.exponents[i] =
          std::complex<double>(hill.exponents[i].real(), std::arg(lambda) / sys.period_s);
    }
    SortSpectrum(&result.multipliers, &result.exponents);
    truncation = hill.truncation_error;
    converged = hill.converged;
    message = hill.message;
    result.summary.counters["harmonics"] = hill.harmonics;
  } else {
    MonodromyOutcome mono;
    switch (method) {
      case FloquetMethod::kExactSteps:
        mono = ExactStepsMonodromy(sys);
        break;
      case FloquetMethod::kMagnus:
        if (options.magnus_steps > 0) {
          mono = MagnusMonodromyFixed(sys, options.magnus_order, options.magnus_steps);
        } else if (options.magnus_measured_order) {
          mono = MagnusMonodromyMeasured(sys, options.magnus_order, options.tolerance);
        } else {
          mono = MagnusMonodromy(sys, options.magnus_order, options.tolerance);
        }
        break;
      case FloquetMethod::kOdeStepper:
        mono = OdeMonodromy(sys, options.tolerance);
        break;
      case FloquetMethod::kAuto:
      case FloquetMethod::kHill:
      case FloquetMethod::kModalProjection:
      case FloquetMethod::kArpackMonodromy:
        GEARDYN_DEMAND(false);
    }
    const Spectrum spectrum =
        SpectrumOf(mono.phi, sys.period_s, mono.num_factors, mono.truncation_error);
    result.multipliers = spectrum.multipliers;
    result.exponents = spectrum.exponents;
    truncation = spectrum.roundoff;  // round-off and truncation (SpectrumOf)
    converged = mono.converged && spectrum.failure.empty();
    message = !mono.converged ? mono.message : spectrum.failure;
    result.summary.counters["steps"] = mono.steps;
    result.summary.counters["evaluations"] = mono.evaluations;
    if (options.keep_monodromy) {
      MatrixX phi = mono.phi.matrix * std::exp(mono.phi.log_scale);
      result.monodromy = sys.ToOriginalMonodromy(phi);
    }
  }
  if (sys.dim == 0 && options.keep_monodromy) {
    result.monodromy = sys.ToOriginalMonodromy(MatrixX(0, 0));
  }
  result.summary.error_estimate = truncation;
  if (!converged) {
    result.summary.status = Status::kToleranceNotMet;
    result.summary.message = message;
  }
  // An overflowing |λ| with finite exponents is an answer (a fast growth); a NaN or an infinite
  // exponent is a failure, whatever the convergence said.
  if (!result.exponents.allFinite() || !result.multipliers.allFinite()) {
    // The exponents are the exact representation (an overflowing λ = polar(inf, arg) may hold
    // inf·0 = NaN in one component); a NaN |λ| (hypot is inf whenever one part is) is a failure.
    bool failed = !result.exponents.allFinite();
    for (Eigen::Index i = 0; i < result.multipliers.size(); ++i) {
      failed = failed || std::isnan(std::abs(result.multipliers[i]));
    }
    if (failed && result.summary.status != Status::kNumericalIssue) {
      result.summary.status = Status::kNumericalIssue;
      result.summary.message =
          "non-finite multipliers" + (message.empty() ? std::string() : " (" + message + ")");
    }
  }
  FinishResult(sys.num_rigid, options.tolerance, &result);
  return result;
}

FloquetMethod SelectGenericMethod(const PeriodicSecondOrderSystem& system,
                                  const FloquetOptions& options) {
  if (options.method != FloquetMethod::kAuto) return options.method;
  if (system.num_dofs() >= options.modal_projection_min_dofs)
    return FloquetMethod::kModalProjection;
  if (!system.steps.empty()) return FloquetMethod::kExactSteps;
  if (system.coefficients) return FloquetMethod::kMagnus;
  return FloquetMethod::kHill;
}

}  // namespace geardyn::internal

namespace geardyn {

FloquetResult ComputeFloquet(const PeriodicSecondOrderSystem& system,
                             const FloquetOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  FloquetOptions checked = options;
  checked.mesh_frequency_hz = 1.0;  // ignored here: the period is system.period_s
  std::string why;
  GEARDYN_THROW_UNLESS(checked.IsValid(&why), why);
  GEARDYN_THROW_UNLESS(std::isfinite(system.period_s) && system.period_s > 0.0,
                       "period_s: must be finite and > 0, got " << system.period_s);
  const FloquetMethod method = internal::SelectGenericMethod(system, checked);
  GEARDYN_THROW_UNLESS(
      method != FloquetMethod::kArpackMonodromy || checked.arpack_nev <= 2 * system.num_dofs(),
      "arpack_nev: must be <= 2n = " << 2 * system.num_dofs() << ", got " << checked.arpack_nev);
  FloquetResult result;
  if (method == FloquetMethod::kModalProjection) {
    GEARDYN_THROW_UNLESS(system.mass.rows() >= 1 && system.mass.rows() == system.mass.cols(),
                         "mass: must be square and non-empty");
    // Lowest modes of the mean system (K̄, M) by the dense symmetric solver.
    const internal::StateSystem probe = internal::MakeStateSystem(system, false);
    const int n = system.num_dofs();
    MatrixX K_mean = MatrixX::Zero(n, n);
    if (!system.steps.empty()) {
      for (const PeriodicStep& s : system.steps)
        K_mean += s.stiffness * (s.duration_s / system.period_s);
    } else if (!system.stiffness_harmonics.empty()) {
      K_mean = system.stiffness_harmonics[0].real();
    } else {
      constexpr int kSamples = 32;
      MatrixX K, C;
      for (int j = 0; j < kSamples; ++j) {
        system.coefficients(system.period_s * (j + 0.5) / kSamples, &K, &C);
        K_mean += K / kSamples;
      }
    }
    const Eigen::GeneralizedSelfAdjointEigenSolver<MatrixX> eig(0.5 * (K_mean + K_mean.transpose()),
                                                                system.mass);
    const MatrixX modes = eig.eigenvectors();
    (void)probe;
    result = internal::ModalProjectionFloquet(
        [&modes](int m) { return MatrixX(modes.leftCols(m)); }, n,
        [&system](const MatrixX& V) { return internal::ProjectSystem(system, V); }, checked);
  } else {
    const internal::StateSystem sys =
        internal::MakeStateSystem(system, checked.deflate_rigid_modes);
    result = internal::ComputeFloquetState(sys, checked, method);
  }
  result.period_meshes = 1;
  result.period_s = system.period_s;
  result.summary.wall_time_s = internal::SecondsSince(start);
  return result;
}

}  // namespace geardyn
