// kArpackMonodromy: the arpack_nev largest-|λ| Floquet multipliers by ARPACK on the matrix-free
// operator v ↦ Φ(T) v (floquet.hpp). Φ is never formed for one period; each application
// propagates one vector with the propagators of the other methods:
// * piecewise-constant coefficients: the exact step exponentials E_k = expm(A_k Δt_k), applied in
//   time order, either formed once (dense, Eigen's Padé) or — for sparse A_k — as the action
//   expm(A_k Δt_k) v by the truncated Taylor series on s_k = ⌈‖A_k Δt_k‖₁⌉ substeps of 1-norm ≤ 1,
//   each summed until two consecutive terms are below ε relative to the sum (Al-Mohy & Higham,
//   SIAM J. Sci. Comput. 33 (2011), Alg. 3.2 with θ = 1 and the early termination of §4). The
//   cheaper of the two is chosen from the flop counts with an assumed 10·ncv applications.
//   A hunting period of P identical cycles: the cycle is formed and raised to its power by
//   scaled squaring (ScaledPower), the operator is then that one normalized matrix and its
//   log-scale is added to the multipliers' logarithms (no overflow).
// * smooth coefficients: the Gauss–Legendre Magnus step exponentials on N equal steps
//   (magnus_steps, or N = 8, 16, … until the Richardson estimate of the dominant multipliers,
//   |Δλ|/(2^p − 1), meets the tolerance).
// Error estimate: max_i min(κ_i ρ_i, √(ρ_i max|λ|)) with ρ_i the residual ‖Φx − λx‖ of the unit
// right and left Ritz vectors (computed by extra applications, not taken from ARPACK) and κ_i the
// eigenvalue condition number from the left vectors of a second ARPACK run on Φᵀ (the factors
// transposed in reverse order); + the Magnus truncation + ε·(10·dim + factors)·max|λ|.
#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <sstream>
#include <unsupported/Eigen/MatrixFunctions>

#include "floquet/floquet_internal.hpp"
#include "geardyn/common/check.hpp"
#include "geardyn/numerics/nonsymmetric_eigen.hpp"

namespace geardyn::internal {
namespace {

constexpr int kMaxTaylorTerms = 60;
constexpr double kExpmFlopsPerN3 =
    25.0;  // Padé 13 with scaling: ≈ 6 products + a solve + squarings
constexpr double kTaylorTermsPerSubstep = 20.0;

// Φ = exp(log_scale) · (the factors applied in time order).
struct Propagator {
  int dim = 0;
  std::vector<MatrixX> dense;
  std::vector<const SparseMatrix*> sparse;
  std::vector<SparseMatrix> sparse_t;  // transposes, for Φᵀ
  std::vector<double> sparse_dt;
  std::vector<int> substeps;
  double log_scale = 0.0;
  double num_factors = 0.0;
  long steps = 0;
  long evaluations = 0;
  bool expm_action = false;
  mutable long matvecs = 0;

  /// y = Φ x, or y = Φᵀ x (the factors transposed, in reverse order).
  void Apply(const Eigen::Ref<const VectorX>& x, Eigen::Ref<VectorX> y, bool transpose) const {
    VectorX u = x, w, t;
    const int nd = static_cast<int>(dense.size()), ns = static_cast<int>(sparse.size());
    auto apply_dense = [&](int k) {
      if (transpose) {
        t.noalias() = dense[k].transpose() * u;
      } else {
        t.noalias() = dense[k] * u;
      }
      u.swap(t);
      ++matvecs;
    };
    auto apply_sparse = [&](int k) {
      constexpr double eps = std::numeric_limits<double>::epsilon() / 2.0;
      const SparseMatrix& A = transpose ? sparse_t[k] : *sparse[k];
      const double h = sparse_dt[k] / substeps[k];
      for (int s = 0; s < substeps[k]; ++s) {
        // expm(hA) u = Σ (hA)^j u / j!, ‖hA‖₁ ≤ 1.
        VectorX sum = u;
        w = u;
        double previous = w.lpNorm<Eigen::Infinity>();
        for (int j = 1; j <= kMaxTaylorTerms; ++j) {
          t.noalias() = A * w;
          w = t * (h / j);
          ++matvecs;
          sum += w;
          const double current = w.lpNorm<Eigen::Infinity>();
          if (previous + current <= eps * sum.lpNorm<Eigen::Infinity>()) break;
          previous = current;
        }
        u.swap(sum);
      }
    };
    if (!transpose) {
      for (int k = 0; k < nd; ++k) apply_dense(k);
      for (int k = 0; k < ns; ++k) apply_sparse(k);
    } else {
      for (int k = ns - 1; k >= 0; --k) apply_sparse(k);
      for (int k = nd - 1; k >= 0; --k) apply_dense(k);
    }
    y = u;
  }
};

double SparseNorm1(const SparseMatrix& A) {
  return (A.cwiseAbs().transpose() * VectorX::Ones(A.rows())).maxCoeff();
}

Propagator PiecewisePropagator(const StateSystem& sys, int ncv) {
  // Merge consecutive equal steps (as ExactStepsMonodromy).
  const MergedSteps merged = MergeEqualSteps(sys);
  const std::vector<double>& dt = merged.dt;
  const std::vector<const MatrixX*>& A = merged.A;
  const std::vector<int>& index = merged.index;
  const int d = RepeatingStepPeriod(dt, A, sys.period_s);
  const std::int64_t power = static_cast<std::int64_t>(dt.size()) / d;
  Propagator p;
  p.dim = sys.dim;
  p.steps = d;
  p.evaluations = d;
  p.num_factors = StepProductFactors(merged, d) * static_cast<double>(power);
  const double n = sys.dim;
  if (power > 1) {
    ScaledMatrix cycle{MatrixX::Identity(sys.dim, sys.dim), 0.0};
    for (int k = 0; k < d; ++k) {
      cycle.matrix = (*A[k] * dt[k]).exp() * cycle.matrix;
      cycle.Normalize();
    }
    long products = 0;
    const ScaledMatrix phi = ScaledPower(cycle, power, &products);
    p.dense.push_back(phi.matrix);
    p.log_scale = phi.log_scale;
    return p;
  }
  if (!sys.sparse_step_matrices.empty()) {
    double action = 0.0, substeps_total = 0.0;
    std::vector<int> substeps;
    for (int k = 0; k < d; ++k) {
      const SparseMatrix& S = sys.sparse_step_matrices[index[k]];
      const int s = std::max(1, static_cast<int>(std::ceil(SparseNorm1(S) * dt[k])));
      substeps.push_back(s);
      substeps_total += s;
      action += s * kTaylorTermsPerSubstep * 2.0 * static_cast<double>(S.nonZeros());
    }
    const double applications = 10.0 * ncv;
    const double dense_cost = d * kExpmFlopsPerN3 * n * n * n + applications * d * 2.0 * n * n;
    if (applications * action < dense_cost) {
      for (int k = 0; k < d; ++k) {
        p.sparse.push_back(&sys.sparse_step_matrices[index[k]]);
        p.sparse_t.push_back(sys.sparse_step_matrices[index[k]].transpose());
        p.sparse_dt.push_back(dt[k]);
      }
      p.substeps = std::move(substeps);
      p.expm_action = true;
      p.num_factors = substeps_total * kTaylorTermsPerSubstep;
      return p;
    }
  }
  for (int k = 0; k < d; ++k) p.dense.push_back((*A[k] * dt[k]).exp());
  return p;
}

Propagator MagnusPropagator(const StateSystem& sys, int order, int steps) {
  Propagator p;
  p.dim = sys.dim;
  double t = 0.0;
  for (const double end : MagnusGrid(sys, steps)) {
    p.dense.push_back(MagnusStepPropagator(sys, order, t, end - t, &p.evaluations));
    t = end;
  }
  p.steps = static_cast<long>(p.dense.size());
  p.num_factors = static_cast<double>(p.dense.size());
  return p;
}

// One ARPACK run on Φ (or Φᵀ): the Ritz values θ sorted by |θ| descending (ties: arg
// descending, as SortSpectrum), their unit vectors and residuals ‖Φx − θx‖, and the multipliers
// λ = e^{log_scale} θ in the same order.
struct Run {
  ArnoldiOutcome arnoldi;
  VectorXc theta;
  MatrixXc vectors;
  VectorX residuals;
  VectorXc multipliers;
  VectorXc exponents;
};

Run RunOperator(const Propagator& p, bool transpose, int nev, int ncv, double tol,
                int max_iterations, double period_s) {
  Run run;
  const int n = p.dim;
  run.arnoldi = RunArnoldiLargestMagnitude(
      [&p, n, transpose](const double* x, double* y) {
        p.Apply(Eigen::Map<const VectorX>(x, n), Eigen::Map<VectorX>(y, n), transpose);
      },
      n, nev, ncv, tol, max_iterations);
  const ArnoldiOutcome& a = run.arnoldi;
  if (!a.ok) return run;
  const int m = static_cast<int>(a.values.size());
  std::vector<int> order(m);
  for (int i = 0; i < m; ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](int i, int j) {
    const double ai = std::abs(a.values[i]), aj = std::abs(a.values[j]);
    if (ai != aj) return ai > aj;
    return std::arg(a.values[i]) > std::arg(a.values[j]);
  });
  VectorX yr(n), yi(n);
  run.theta.resize(m);
  run.vectors.resize(n, m);
  run.residuals.resize(m);
  run.multipliers.resize(m);
  run.exponents.resize(m);
  for (int k = 0; k < m; ++k) {
    const int i = order[k];
    const std::complex<double> theta = a.values[i];
    run.theta[k] = theta;
    run.vectors.col(k) = a.vectors.col(i);
    // Residual with two real applications (Φ real).
    const VectorX xr = a.vectors.col(i).real(), xi = a.vectors.col(i).imag();
    p.Apply(xr, yr, transpose);
    p.Apply(xi, yi, transpose);
    const VectorXc r = (yr.cast<std::complex<double>>() +
                        std::complex<double>(0.0, 1.0) * yi.cast<std::complex<double>>()) -
                       theta * a.vectors.col(i);
    run.residuals[k] = r.norm();
    const double log_mod =
        std::log(std::max(std::abs(theta), std::numeric_limits<double>::min())) + p.log_scale;
    run.exponents[k] = std::complex<double>(log_mod / period_s, std::arg(theta) / period_s);
    run.multipliers[k] = std::polar(std::exp(log_mod), std::arg(theta));
  }
  return run;
}

// Error bound of the first `count` multipliers of `right` (absolute, on λ): with the left
// eigenvectors w from the run on Φᵀ, κ_i = ‖w‖‖x‖/|wᵀx| and e_i = min(κ_i ρ_i, √(ρ_i |θ|_max)),
// ρ_i = max(residual of x_i, residual of w_i) (first-order perturbation; the √ bound covers
// (nearly) double multipliers, as SpectrumOf). Without a matching left vector: √(ρ_i |θ|_max).
double ResidualBound(const Run& right, const Run& left, int count, double log_scale) {
  const double theta_max = right.theta.size() ? std::abs(right.theta[0]) : 0.0;
  double worst = 0.0;
  for (int i = 0; i < count && i < right.theta.size(); ++i) {
    double rho = right.residuals[i];
    double bound = std::sqrt(rho * theta_max);
    if (left.arnoldi.ok && left.theta.size() > 0) {
      Eigen::Index j = 0;
      (left.theta.array() - right.theta[i]).abs().minCoeff(&j);
      const double gap = std::abs(left.theta[j] - right.theta[i]);
      rho = MaxPropagatingNaN(rho, left.residuals[j]);
      if (gap <= 1e3 * rho + 1e-12 * theta_max) {
        const double overlap =
            std::abs((left.vectors.col(j).transpose() * right.vectors.col(i))(0));
        const double kappa =
            overlap > 0.0 ? 1.0 / overlap : std::numeric_limits<double>::infinity();
        bound = std::min(kappa * rho + gap, std::sqrt(rho * theta_max) + gap);
      } else {
        bound = std::sqrt(rho * theta_max);
      }
    }
    worst = MaxPropagatingNaN(worst, bound);
  }
  return worst * std::exp(std::min(log_scale, 700.0));
}

// The first `count` entries, plus the conjugate partner of the last one if it follows.
void KeepLeading(int count, VectorXc* multipliers, VectorXc* exponents) {
  const int size = static_cast<int>(multipliers->size());
  if (size <= count) return;
  int keep = count;
  const std::complex<double> last = (*multipliers)[count - 1];
  if (last.imag() != 0.0 &&
      std::abs((*multipliers)[count] - std::conj(last)) <= 1e-8 * std::max(1.0, std::abs(last))) {
    ++keep;
  }
  *multipliers = multipliers->head(keep).eval();
  *exponents = exponents->head(keep).eval();
}

}  // namespace

FloquetResult ArpackMonodromyFloquet(const StateSystem& sys, const FloquetOptions& options) {
  const int nev = options.arpack_nev;
  if (sys.dim < nev + 2) {
    // Too small for ARPACK: Φ from the same propagators, all multipliers.
    const FloquetMethod dense =
        sys.step_matrices.empty() ? FloquetMethod::kMagnus : FloquetMethod::kExactSteps;
    FloquetResult r = ComputeFloquetState(sys, options, dense);
    r.method_used = FloquetMethod::kArpackMonodromy;
    r.summary.warnings.push_back("arpack_monodromy: state dimension " + std::to_string(sys.dim) +
                                 " < arpack_nev + 2 = " + std::to_string(nev + 2) +
                                 ": all multipliers from the dense monodromy (" + ToString(dense) +
                                 ")");
    return r;
  }
  GEARDYN_THROW_UNLESS(!sys.step_matrices.empty() || static_cast<bool>(sys.evaluate),
                       "method: arpack_monodromy needs steps or the coefficients callback");
  FloquetResult result;
  result.method_used = FloquetMethod::kArpackMonodromy;
  result.period_s = sys.period_s;
  result.summary.warnings = sys.warnings;
  result.summary.counters["num_rigid_modes"] = sys.num_rigid;
  result.summary.counters["state_dimension"] = sys.dim;
  const int nev_run = std::min(nev + 2, sys.dim - 2);  // 2 spare for the Richardson matching
  const int ncv = options.arpack_ncv > 0
                      ? std::min(std::max(options.arpack_ncv, nev_run + 2), sys.dim)
                      : std::min(sys.dim, std::max(2 * nev_run + 1, 20));
  const double tol = std::max(1e-15, 0.1 * options.tolerance);
  double truncation = 0.0;
  bool magnus_met = true;
  std::string magnus_message;
  Propagator prop;
  Run run;
  long applications = 0, evaluations = 0;
  if (!sys.step_matrices.empty()) {
    prop = PiecewisePropagator(sys, ncv);
    run = RunOperator(prop, false, nev_run, ncv, tol, options.arpack_max_iterations, sys.period_s);
  } else if (options.magnus_steps > 0) {
    prop = MagnusPropagator(sys, options.magnus_order, options.magnus_steps);
    run = RunOperator(prop, false, nev_run, ncv, tol, options.arpack_max_iterations, sys.period_s);
  } else {
    // Step doubling with Richardson on the dominant multipliers (as MagnusMonodromy on Φ).
    // Start where h‖A‖ ≤ 1 (MagnusStartSteps, magnus.cpp), capped so one doubling fits.
    const double norm_T = MaxOperatorNormTimesPeriod(sys, &evaluations);
    const int start = MagnusStartSteps(norm_T);
    if (start > kMaxMagnusSteps) {
      result.summary.status = Status::kToleranceNotMet;
      result.summary.message = "arpack_monodromy: max‖A‖₁·T = " + FormatEstimate(norm_T) +
                               " needs more than " + std::to_string(kMaxMagnusSteps) +
                               " Magnus steps per period; not attempted";
      result.summary.error_estimate = std::numeric_limits<double>::quiet_NaN();
      result.max_abs_multiplier = std::numeric_limits<double>::quiet_NaN();
      result.stability_margin = std::numeric_limits<double>::quiet_NaN();
      result.verdict = FloquetVerdict::kUndetermined;
      return result;
    }
    int n1 = std::min(start, kMaxMagnusSteps / 2);
    prop = MagnusPropagator(sys, options.magnus_order, n1);
    run = RunOperator(prop, false, nev_run, ncv, tol, options.arpack_max_iterations, sys.period_s);
    evaluations += prop.evaluations;
    int n2 = std::min(kMaxMagnusSteps, 2 * n1);
    double previous_difference = std::numeric_limits<double>::quiet_NaN();
    int previous_n = 0;
    while (run.arnoldi.ok) {
      Propagator fine_prop = MagnusPropagator(sys, options.magnus_order, n2);
      applications += run.arnoldi.applications + 2 * run.multipliers.size();
      Run fine = RunOperator(fine_prop, false, nev_run, ncv, tol, options.arpack_max_iterations,
                             sys.period_s);
      evaluations += fine_prop.evaluations;
      const int m = std::min<int>(nev, static_cast<int>(fine.multipliers.size()));
      const double ratio = static_cast<double>(fine_prop.steps) / static_cast<double>(prop.steps);
      const bool fine_ok = fine.arnoldi.ok;
      const double difference = fine_ok ? MatchedDistance(fine.multipliers.head(m), run.multipliers)
                                        : std::numeric_limits<double>::infinity();
      // The observed order (magnus.cpp ObservedOrder): jumps or kinks lower it below p.
      const int coarse_steps = static_cast<int>(prop.steps);
      const double q = ObservedOrder(previous_difference, difference, previous_n, coarse_steps,
                                     options.magnus_order);
      const double err = ratio > 1.0 ? difference / (std::pow(ratio, q) - 1.0)
                                     : std::numeric_limits<double>::infinity();
      prop = std::move(fine_prop);
      run = std::move(fine);
      // A non-finite estimate (failed or overflowing coarse run) means "refine", not "done".
      if (err <= options.tolerance || n2 >= kMaxMagnusSteps || !fine_ok) {
        truncation = std::isnan(err) ? std::numeric_limits<double>::infinity() : err;
        if (!(err <= options.tolerance)) {
          magnus_met = false;
          magnus_message = "arpack_monodromy: Richardson estimate of the dominant multipliers " +
                           FormatEstimate(err) + " above the tolerance at " + std::to_string(n2) +
                           " Magnus steps";
        }
        break;
      }
      const double grow =
          std::isfinite(err)
              ? std::clamp(1.2 * std::pow(err / options.tolerance, 1.0 / q), 1.5, 16.0)
              : 4.0;
      previous_difference = difference;
      previous_n = coarse_steps;
      n1 = n2;
      n2 = static_cast<int>(std::min<double>(kMaxMagnusSteps, std::ceil(n2 * grow)));
    }
  }
  const ArnoldiOutcome& a = run.arnoldi;
  applications += a.applications + 2 * run.multipliers.size();
  // Left eigenvectors (ARPACK on Φᵀ) for the condition numbers of the error bound.
  Run left;
  if (a.ok) {
    left = RunOperator(prop, true, nev_run, ncv, tol, options.arpack_max_iterations, sys.period_s);
    applications += left.arnoldi.applications + 2 * left.multipliers.size();
  }
  evaluations += prop.evaluations;
  Summary& s = result.summary;
  s.counters["arpack_info"] = a.info;
  s.counters["arpack_converged"] = std::min(a.num_converged, nev);
  s.counters["arpack_restarts"] = a.iterations;
  s.counters["arpack_ncv"] = ncv;
  s.counters["operator_applications"] = applications;
  s.counters["matvecs"] = prop.matvecs;
  s.counters["steps"] = prop.steps;
  s.counters["evaluations"] = evaluations;
  s.counters["expm_action"] = prop.expm_action ? 1 : 0;
  if (!a.ok) {
    s.status = Status::kNumericalIssue;
    s.message = "arpack_monodromy: " + a.message;
    result.max_abs_multiplier = std::numeric_limits<double>::quiet_NaN();
    result.stability_margin = std::numeric_limits<double>::quiet_NaN();
    result.verdict = FloquetVerdict::kUndetermined;
    return result;
  }
  result.multipliers = run.multipliers;
  result.exponents = run.exponents;
  KeepLeading(nev, &result.multipliers, &result.exponents);
  const double max_abs = MaxAbsOf(result.multipliers);
  const double roundoff =
      std::numeric_limits<double>::epsilon() * (10.0 * sys.dim + prop.num_factors) * max_abs;
  s.error_estimate =
      ResidualBound(run, left, static_cast<int>(result.multipliers.size()), prop.log_scale) +
      truncation + roundoff;
  if (a.info != 0 || a.num_converged < nev_run) {
    s.status = Status::kNotConverged;
    s.message = "arpack_monodromy: " + a.message;
  } else if (!magnus_met) {
    s.status = Status::kToleranceNotMet;
    s.message = magnus_message;
  }
  FinishResult(sys.num_rigid, options.tolerance, &result);
  if (options.keep_monodromy) {
    s.warnings.push_back("arpack_monodromy: the monodromy is not formed (keep_monodromy ignored)");
  }
  return result;
}

}  // namespace geardyn::internal
