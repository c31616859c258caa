// Multipliers from a scaled monodromy, their round-off estimate, sorting, matching and the verdict.
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <limits>
#include <numeric>
#include <sstream>

#include "floquet/floquet_internal.hpp"

namespace geardyn::internal {

std::string FormatEstimate(double value) {
  std::ostringstream os;
  os << std::setprecision(3) << value;
  return os.str();
}

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
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (!phi.matrix.allFinite() || !std::isfinite(phi.log_scale)) {
    // A failed propagation: NaN multipliers (the verdict is then undetermined), never zeros.
    out.multipliers = VectorXc::Constant(N, std::complex<double>(nan, nan));
    out.exponents = out.multipliers;
    out.roundoff = nan;
    out.failure = "the monodromy has non-finite entries";
    return out;
  }
  const Eigen::EigenSolver<MatrixX> eig(phi.matrix, true);
  if (eig.info() != Eigen::Success) {
    out.multipliers = VectorXc::Constant(N, std::complex<double>(nan, nan));
    out.exponents = out.multipliers;
    out.roundoff = nan;
    out.failure = "the eigenvalue solver of the monodromy did not converge (Eigen info " +
                  std::to_string(static_cast<int>(eig.info())) + ")";
    return out;
  }
  const VectorXc values = eig.eigenvalues();
  const MatrixXc V = eig.eigenvectors();
  // Partial pivoting (backward stable on these unit-column eigenvector matrices; full pivoting
  // spent ≈ 7 % of a stability chart in its complex-modulus pivot search): a singular V gives a
  // non-finite row, i.e. κ = ∞ below.
  const MatrixXc Vinv = V.partialPivLu().inverse();
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
    roundoff = MaxPropagatingNaN(roundoff, std::min(kappa * delta, std::sqrt(delta * norm)));
    const double mod = std::abs(values[i]);
    const double arg = std::arg(values[i]);
    const double log_mod =
        std::log(std::max(mod, std::numeric_limits<double>::min())) + phi.log_scale;
    out.exponents[i] = std::complex<double>(log_mod / period_s, arg / period_s);
    // A real eigenvalue stays real: std::polar(inf, 0) is (inf, inf·0 = NaN), which turned an
    // overflowing growth (finite exponent, documented as |λ| = inf) into a NaN multiplier
    // (stress suite, issue 16).
    out.multipliers[i] =
        values[i].imag() == 0.0
            ? std::complex<double>(std::copysign(std::exp(log_mod), values[i].real()), 0.0)
            : std::polar(std::exp(log_mod), arg);
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

double MaxPropagatingNaN(double a, double b) {
  if (std::isnan(a) || std::isnan(b)) return std::numeric_limits<double>::quiet_NaN();
  return std::max(a, b);
}

double MaxAbsOf(const VectorXc& values) {
  double m = 0.0;
  for (const std::complex<double>& v : values) m = MaxPropagatingNaN(m, std::abs(v));
  return m;
}

FloquetVerdict DecideVerdict(const Summary& summary, const VectorXc& multipliers,
                             const VectorXc& exponents, std::string* why) {
  const double e = summary.error_estimate;
  const double max_abs = MaxAbsOf(multipliers);
  // Non-finite |λ| is an honest answer only as an overflowing growth: its exponent (computed
  // from the scaled monodromy, floquet_internal.hpp SpectrumOf) must be finite.
  bool broken = std::isnan(max_abs) || !std::isfinite(e) || std::isnan(e);
  bool overflow = false;
  for (Eigen::Index i = 0; i < multipliers.size() && !broken; ++i) {
    if (std::isfinite(std::abs(multipliers[i]))) continue;
    const bool exponent_ok = i < exponents.size() && std::isfinite(exponents[i].real()) &&
                             std::isfinite(exponents[i].imag()) && exponents[i].real() > 0.0;
    if (exponent_ok) {
      overflow = true;
    } else {
      broken = true;
    }
  }
  const bool usable =
      summary.status == Status::kSuccess || summary.status == Status::kToleranceNotMet;
  if (broken || !usable) {
    if (why != nullptr) {
      *why = broken ? "non-finite multipliers or error estimate"
                    : std::string("status ") + StatusName(summary.status);
    }
    return FloquetVerdict::kUndetermined;
  }
  // Unstable beyond the estimated error: decisive even when the tolerance was missed. A growth
  // below kMarginalFloor per period is round-off, not physics (the exact-steps product of an
  // undamped pair reads 1 + 1.2e-13 with an estimate of 7.7e-14; a real growth that small would
  // take 10¹² periods to double): it reads as marginal, as IsMarginal does.
  if (overflow || max_abs - std::max(e, kMarginalFloor) > 1.0) return FloquetVerdict::kUnstable;
  if (summary.status != Status::kSuccess) {
    if (why != nullptr) {
      *why = "max|λ| − 1 is within the error estimate and the tolerance was not met";
    }
    return FloquetVerdict::kUndetermined;
  }
  return FloquetVerdict::kStable;
}

FloquetVerdict CombineVerdicts(FloquetVerdict a, FloquetVerdict b) {
  // One unstable block makes the system unstable; otherwise one unknown block leaves it unknown.
  if (a == FloquetVerdict::kUnstable || b == FloquetVerdict::kUnstable) {
    return FloquetVerdict::kUnstable;
  }
  if (a == FloquetVerdict::kUndetermined || b == FloquetVerdict::kUndetermined) {
    return FloquetVerdict::kUndetermined;
  }
  return FloquetVerdict::kStable;
}

VectorXc WithoutRigid(const VectorXc& multipliers) {
  VectorXc out(multipliers.size());
  Eigen::Index k = 0;
  for (const std::complex<double>& l : multipliers) {
    if (l != std::complex<double>(1.0, 0.0)) out[k++] = l;
  }
  return out.head(k);
}

bool IsMarginal(FloquetVerdict verdict, const VectorXc& flexible, double error_estimate) {
  if (verdict != FloquetVerdict::kStable || flexible.size() == 0) return false;
  return 1.0 - MaxAbsOf(flexible) <= std::max(error_estimate, kMarginalFloor);
}

void RedecideVerdict(FloquetResult* result) {
  std::string why;
  result->verdict = DecideVerdict(result->summary, result->multipliers, result->exponents, &why);
  if (result->verdict == FloquetVerdict::kUndetermined) {
    result->summary.warnings.push_back("verdict undetermined: " + why);
  }
  result->marginal = IsMarginal(result->verdict, WithoutRigid(result->multipliers),
                                result->summary.error_estimate);
}

void FinishResult(int num_rigid, double tolerance, FloquetResult* result) {
  const bool marginal_flexible =
      IsMarginal(FloquetVerdict::kStable, result->multipliers, result->summary.error_estimate);
  if (num_rigid > 0) {
    const int N = static_cast<int>(result->multipliers.size());
    result->multipliers.conservativeResize(N + 2 * num_rigid);
    result->exponents.conservativeResize(N + 2 * num_rigid);
    result->multipliers.tail(2 * num_rigid).setConstant(1.0);
    result->exponents.tail(2 * num_rigid).setZero();
    SortSpectrum(&result->multipliers, &result->exponents);
  }
  result->max_abs_multiplier = MaxAbsOf(result->multipliers);
  if (result->exponents.size() && std::isinf(result->max_abs_multiplier)) {
    result->summary.warnings.push_back(
        "multipliers overflow double (max Re(mu) T = " +
        std::to_string(result->exponents.real().maxCoeff() * result->period_s) +
        "); the exponents are exact");
  }
  result->stability_margin = 1.0 - result->max_abs_multiplier;
  std::string why;
  result->verdict = DecideVerdict(result->summary, result->multipliers, result->exponents, &why);
  result->marginal = result->verdict == FloquetVerdict::kStable && marginal_flexible;
  if (result->verdict == FloquetVerdict::kUndetermined) {
    result->summary.warnings.push_back("verdict undetermined: " + why);
  }
  (void)tolerance;
}

}  // namespace geardyn::internal

namespace geardyn {

const char* ToString(FloquetVerdict verdict) {
  switch (verdict) {
    case FloquetVerdict::kStable:
      return "stable";
    case FloquetVerdict::kUnstable:
      return "unstable";
    case FloquetVerdict::kUndetermined:
      return "undetermined";
  }
  return "unknown";
}

std::string FormatMaxAbsMultiplier(double max_abs) {
  char text[48];
  const double growth = max_abs - 1.0;
  if (std::isfinite(max_abs) && growth != 0.0 && std::abs(growth) < 5e-4) {
    std::snprintf(text, sizeof(text), "1 %s %.2g", growth > 0.0 ? "+" : "−", std::abs(growth));
  } else {
    std::snprintf(text, sizeof(text), "%.4g", max_abs);
  }
  return text;
}

}  // namespace geardyn
