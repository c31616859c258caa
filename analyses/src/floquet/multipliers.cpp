// Multipliers from a scaled monodromy, their round-off estimate, sorting, matching and the verdict.
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "floquet/floquet_internal.hpp"

namespace geardyn::internal {

double SecondsSince(const std::chrono::steady_clock::time_point& start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double RelativeDifference(const ScaledMatrix& a, const ScaledMatrix& b) {
  const double nb = b.matrix.norm();
  if (!(nb > 0.0)) return std::numeric_limits<double>::infinity();
  return (a.matrix * std::exp(a.log_scale - b.log_scale) - b.matrix).norm() / nb;
}

Spectrum SpectrumOf(const ScaledMatrix& phi, double period_s, double num_factors,
                    double matrix_error) {
  Spectrum out;
  const int N = static_cast<int>(phi.matrix.rows());
  if (N == 0) return out;
  const Eigen::EigenSolver<MatrixX> eig(phi.matrix, true);
  const VectorXc values = eig.eigenvalues();
  const MatrixXc V = eig.eigenvectors();
  const MatrixXc Vinv = V.fullPivLu().inverse();
  // Round-off (+ truncation e): δ = (ε (10 N + factors) + e) ‖Φ‖; error_i = min(κ_i δ, √(δ‖Φ‖))
  // (floquet_system.hpp).
  const double eps = std::numeric_limits<double>::epsilon();
  const double norm = phi.matrix.norm();
  const double delta = (eps * (10.0 * N + num_factors) + matrix_error) * norm;
  const double scale = std::exp(std::min(phi.log_scale, 700.0));
  double roundoff = 0.0;
  out.multipliers.resize(N);
  out.exponents.resize(N);
  for (int i = 0; i < N; ++i) {
    double kappa = V.col(i).norm() * Vinv.row(i).norm();
    if (!std::isfinite(kappa)) kappa = std::numeric_limits<double>::infinity();
    roundoff = std::max(roundoff, std::min(kappa * delta, std::sqrt(delta * norm)));
    const double mod = std::abs(values[i]);
    const double arg = std::arg(values[i]);
    const double log_mod =
        std::log(std::max(mod, std::numeric_limits<double>::min())) + phi.log_scale;
    out.exponents[i] = std::complex<double>(log_mod / period_s, arg / period_s);
    out.multipliers[i] = std::polar(std::exp(log_mod), arg);
  }
  out.roundoff = roundoff * scale;
  SortSpectrum(&out.multipliers, &out.exponents);
  return out;
}

void SortSpectrum(VectorXc* multipliers, VectorXc* exponents) {
  const int N = static_cast<int>(multipliers->size());
  std::vector<int> order(N);
  std::iota(order.begin(), order.end(), 0);
  const VectorXc& l = *multipliers;
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    const double ma = std::abs(l[a]), mb = std::abs(l[b]);
    if (ma != mb) return ma > mb;
    return std::arg(l[a]) > std::arg(l[b]);
  });
  VectorXc sorted_l(N), sorted_e(N);
  for (int i = 0; i < N; ++i) {
    sorted_l[i] = l[order[i]];
    if (exponents != nullptr && exponents->size() == N) sorted_e[i] = (*exponents)[order[i]];
  }
  *multipliers = sorted_l;
  if (exponents != nullptr && exponents->size() == N) *exponents = sorted_e;
}

double MatchedDistance(const VectorXc& a, const VectorXc& b) {
  std::vector<bool> used(b.size(), false);
  double worst = 0.0;
  for (int i = 0; i < a.size(); ++i) {
    double best = std::numeric_limits<double>::infinity();
    int best_j = -1;
    for (int j = 0; j < b.size(); ++j) {
      if (used[j]) continue;
      const double d = std::abs(a[i] - b[j]);
      if (d < best) {
        best = d;
        best_j = j;
      }
    }
    if (best_j < 0) return std::numeric_limits<double>::infinity();
    used[best_j] = true;
    worst = std::max(worst, best);
  }
  return worst;
}

void FinishResult(int num_rigid, double tolerance, FloquetResult* result) {
  if (num_rigid > 0) {
    const int N = static_cast<int>(result->multipliers.size());
    result->multipliers.conservativeResize(N + 2 * num_rigid);
    result->exponents.conservativeResize(N + 2 * num_rigid);
    result->multipliers.tail(2 * num_rigid).setConstant(1.0);
    result->exponents.tail(2 * num_rigid).setZero();
    SortSpectrum(&result->multipliers, &result->exponents);
  }
  result->max_abs_multiplier =
      result->multipliers.size() ? result->multipliers.cwiseAbs().maxCoeff() : 0.0;
  if (result->exponents.size() && !std::isfinite(result->max_abs_multiplier)) {
    result->summary.warnings.push_back(
        "multipliers overflow double (max Re(mu) T = " +
        std::to_string(result->exponents.real().maxCoeff() * result->period_s) +
        "); the exponents are exact");
  }
  result->stability_margin = 1.0 - result->max_abs_multiplier;
  result->stable = result->max_abs_multiplier <= 1.0 + result->summary.error_estimate;
  (void)tolerance;
}

}  // namespace geardyn::internal
