// kHill: characteristic exponents from the truncated Hill matrix of ż = A(t) z.
//
// With z(t) = e^{μt} Σ_{k=−H..H} z_k e^{ikΩt} (Ω = 2π/T) and A(t) = Σ_m A_m e^{imΩt}, the
// harmonic balance of ż = A z gives the eigenproblem (Hill matrix, block (k, j) of size dim):
//   𝓗_{kj} = A_{k−j} − ikΩ δ_{kj} I,   𝓗 Z = μ Z.
// Every exact exponent μ appears as the family μ + ilΩ (l ∈ ℤ) with the eigenvector shifted by l
// harmonics; truncation spoils the members near the edges. **Selection** (Lazarus & Thomas,
// C. R. Mécanique 338 (2010) 510–517; Bentvelsen & Lazarus, Nonlinear Dyn. 94 (2018)): keep the
// dim eigenvalues whose eigenvectors are the most concentrated in the central block,
// w = ‖z_0‖²/‖Z‖² largest — the family member whose Fourier content is centred on k = 0, i.e. the
// best resolved one, taking one member per family (a member of a selected family, recognized by
// μ_j − μ_i ∈ iΩℤ∖{0} and the shifted eigenvector, is skipped: in a principal tongue two members
// are equally central). Multipliers λ = exp(μT) do not depend on the member.
// **Truncation** H: options.hill_harmonics, else H = 4, 6, 9, 14, … until the multipliers of two
// successive H agree within the tolerance (at most dim·(2H+1) ≤ kMaxHillSize). The error estimate
// is the change of the multipliers from round(H/1.5) (fixed H) or the previous H (adaptive) to H.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>

#include "floquet/floquet_internal.hpp"
#include "geardyn/common/check.hpp"

namespace geardyn::internal {
namespace {

VectorXc SelectedExponents(const StateSystem& sys, int H) {
  const int d = sys.dim, size = d * (2 * H + 1);
  const double Omega = 2.0 * std::numbers::pi / sys.period_s;
  const int available = static_cast<int>(sys.harmonics.size()) - 1;
  MatrixXc hill = MatrixXc::Zero(size, size);
  for (int k = -H; k <= H; ++k) {
    for (int j = -H; j <= H; ++j) {
      const int m = k - j;
      if (std::abs(m) > available) continue;
      auto block = hill.block((k + H) * d, (j + H) * d, d, d);
      if (m >= 0) {
        block = sys.harmonics[m];
      } else {
        block = sys.harmonics[-m].conjugate();
      }
    }
    hill.block((k + H) * d, (k + H) * d, d, d).diagonal().array() -=
        std::complex<double>(0.0, k * Omega);
  }
  const Eigen::ComplexEigenSolver<MatrixXc> eig(hill, true);
  if (eig.info() != Eigen::Success) {
    // NaN exponents: the verdict becomes undetermined (never a default 0 → |λ| = 1).
    const double nan = std::numeric_limits<double>::quiet_NaN();
    return VectorXc::Constant(d, std::complex<double>(nan, nan));
  }
  const VectorXc& mu = eig.eigenvalues();
  const MatrixXc& Z = eig.eigenvectors();
  std::vector<double> weight(size);
  for (int i = 0; i < size; ++i) {
    weight[i] = Z.col(i).segment(H * d, d).squaredNorm() / Z.col(i).squaredNorm();
  }
  std::vector<int> order(size);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return weight[a] > weight[b]; });
  // Take the most central eigenvalues, one per family: a candidate j is the member of a selected
  // family i when μ_j ≈ μ_i + ilΩ (l ≠ 0) and its eigenvector is the one of i shifted by l blocks
  // (z^j_k = z^i_{k+l}); where two members are equally central (a principal tongue, content at
  // ±Ω/2) the weight alone would pick both of one family.
  std::vector<int> chosen;
  for (int idx = 0; idx < size && static_cast<int>(chosen.size()) < d; ++idx) {
    const int j = order[idx];
    bool duplicate = false;
    for (const int i : chosen) {
      const double shift = (mu[j] - mu[i]).imag() / Omega;
      const long l = std::lround(shift);
      if (l == 0 ||
          std::abs(mu[j] - mu[i] - std::complex<double>(0.0, static_cast<double>(l) * Omega)) >
              1e-6 * (std::abs(mu[i]) + Omega)) {
        continue;
      }
      std::complex<double> dot = 0.0;
      for (int k = -H; k <= H; ++k) {
        if (k + l < -H || k + l > H) continue;
        dot += Z.col(j).segment((k + H) * d, d).dot(Z.col(i).segment((k + l + H) * d, d));
      }
      if (std::abs(dot) > 0.9 * Z.col(i).norm() * Z.col(j).norm()) {
        duplicate = true;
        break;
      }
    }
    if (!duplicate) chosen.push_back(j);
  }
  VectorXc out(d);
  if (chosen.empty()) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    return VectorXc::Constant(d, std::complex<double>(nan, nan));
  }
  for (int i = 0; i < d; ++i) out[i] = mu[chosen[std::min(i, static_cast<int>(chosen.size()) - 1)]];
  return out;
}

VectorXc MultipliersOf(const VectorXc& mu, double T) {
  VectorXc l(mu.size());
  for (int i = 0; i < mu.size(); ++i) l[i] = std::exp(mu[i] * T);
  return l;
}

}  // namespace

HillOutcome HillExponents(const StateSystem& sys, int harmonics, double tolerance) {
  GEARDYN_THROW_UNLESS(!sys.harmonics.empty(),
                       "method: hill needs the Fourier harmonics of the coefficients");
  const double T = sys.period_s;
  const int max_h = std::max(1, static_cast<int>((kMaxHillSize / std::max(sys.dim, 1) - 1) / 2));
  HillOutcome out;
  if (harmonics > 0) {
    const int lower = std::max(1, static_cast<int>(std::lround(harmonics / 1.5)));
    // The estimate's second solve uses H + 1 when round(H/1.5) = H.
    CheckHillSize(sys.dim, lower == harmonics ? harmonics + 1 : harmonics, true);
    out.exponents = SelectedExponents(sys, harmonics);
    out.harmonics = harmonics;
    const VectorXc coarse = SelectedExponents(sys, lower == harmonics ? harmonics + 1 : lower);
    out.truncation_error =
        MatchedDistance(MultipliersOf(out.exponents, T), MultipliersOf(coarse, T));
  } else {
    CheckHillSize(sys.dim, 4, false);  // the smallest H of the ladder
    int H = 4;
    VectorXc previous = SelectedExponents(sys, H);
    while (true) {
      const int next = std::min(max_h, std::max(H + 1, static_cast<int>(std::ceil(1.5 * H))));
      if (next <= H) break;
      const VectorXc current = SelectedExponents(sys, next);
      const double err = MatchedDistance(MultipliersOf(current, T), MultipliersOf(previous, T));
      out.exponents = current;
      out.harmonics = next;
      out.truncation_error = err;
      H = next;
      previous = current;
      if (err <= tolerance || H >= max_h) break;
    }
    if (out.exponents.size() == 0) {
      out.exponents = previous;
      out.harmonics = H;
      out.truncation_error = std::numeric_limits<double>::infinity();
    }
  }
  if (!(out.truncation_error <= tolerance)) {
    out.converged = false;
    out.message = "hill: error estimate " + FormatEstimate(out.truncation_error) +
                  " above the tolerance at H = " + std::to_string(out.harmonics);
  }
  return out;
}

}  // namespace geardyn::internal
