// Floquet of a train whose meshes run at incommensurate frequencies: the rational approximants
// (floquet.hpp "Incommensurate frequencies", docs/design.md "Incommensurate frequencies: rational
// approximants"). Every ratio r_k is replaced by a continued-fraction convergent p_k/q_k, the
// approximated model is periodic over the common period of the convergents, and its monodromy is
// the ordinary one; the convergents of all ratios are taken together by a growing denominator
// bound Q (each ratio its last convergent with q ≤ Q), which gives a sequence of models whose
// ratio error falls like 1/(q Q) and whose exponents converge to the Lyapunov exponents of the
// quasi-periodic system.
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <functional>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

#include "floquet/floquet_internal.hpp"
#include "geardyn/analyses/floquet.hpp"
#include "geardyn/common/check.hpp"
#include "geardyn/common/errors.hpp"
#include "geardyn/system/common_period.hpp"

namespace geardyn::internal {
namespace {

struct Fraction {
  std::int64_t p = 0;
  std::int64_t q = 1;
};

// The convergents h_n/k_n of r > 0 with p ≥ 1 and q ≤ max_q, in order (h_n = a_n h_{n−1} + h_{n−2},
// the same for k). The expansion stops when the remainder is exhausted to round-off.
std::vector<Fraction> Convergents(double r, std::int64_t max_q) {
  std::vector<Fraction> out;
  std::int64_t h_prev = 1, h_prev2 = 0, k_prev = 0, k_prev2 = 1;
  double x = r;
  for (int n = 0; n < 64; ++n) {
    const double a_real = std::floor(x);
    if (a_real > 1e12) break;
    const auto a = static_cast<std::int64_t>(a_real);
    const std::int64_t h = a * h_prev + h_prev2;
    const std::int64_t k = a * k_prev + k_prev2;
    if (k > max_q) break;
    if (h >= 1) out.push_back({h, k});
    h_prev2 = h_prev;
    h_prev = h;
    k_prev2 = k_prev;
    k_prev = k;
    const double rest = x - a_real;
    if (rest < 1e-12) break;  // r was this fraction (to round-off)
    x = 1.0 / rest;
  }
  return out;
}

// A multiplier this far below the largest is not resolved by a product over a long period (its
// absolute error is ≈ ε‖Φ‖): its exponent says only "more damped than this".
constexpr double kResolvedMultiplierRatio = 1e-8;

// The real parts of the flexible exponents whose multipliers are resolved, descending (the
// rigid-body multipliers, exactly 1, left out: their exponent is 0 for every approximant).
std::vector<double> ResolvedRealExponents(const FloquetResult& r) {
  std::vector<double> out;
  for (Eigen::Index i = 0; i < r.exponents.size(); ++i) {
    if (r.multipliers[i] == std::complex<double>(1.0, 0.0)) continue;
    out.push_back(r.exponents[i].real());
  }
  std::sort(out.begin(), out.end(), std::greater<>());
  if (out.empty() || !(r.period_s > 0.0)) return out;
  const double floor = out.front() + std::log(kResolvedMultiplierRatio) / r.period_s;
  while (!out.empty() && !(out.back() >= floor)) out.pop_back();
  return out;
}

// The largest change of a resolved exponent's real part between two approximants, in descending
// order of both (the first min(count) of each; NaN passes through).
double ExponentChange(const FloquetResult& a, const FloquetResult& b) {
  const std::vector<double> ra = ResolvedRealExponents(a);
  const std::vector<double> rb = ResolvedRealExponents(b);
  double change = 0.0;
  for (std::size_t i = 0; i < std::min(ra.size(), rb.size()); ++i) {
    const double d = std::abs(ra[i] - rb[i]);
    if (std::isnan(d) || d > change) change = d;
  }
  return change;
}

double MaxRealExponent(const FloquetResult& r) {
  const std::vector<double> resolved = ResolvedRealExponents(r);
  return resolved.empty() ? 0.0 : resolved.front();
}

}  // namespace

std::vector<FloquetApproximant> RationalApproximants(const SystemModel& model,
                                                     std::int64_t max_period_meshes) {
  const std::vector<SystemMesh>& meshes = model.meshes();
  std::vector<std::vector<Fraction>> convergents(meshes.size());
  std::vector<std::int64_t> bounds;
  for (std::size_t k = 0; k < meshes.size(); ++k) {
    convergents[k] = Convergents(meshes[k].phase_ratio, max_period_meshes);
    for (const Fraction& f : convergents[k]) bounds.push_back(f.q);
  }
  std::sort(bounds.begin(), bounds.end());
  bounds.erase(std::unique(bounds.begin(), bounds.end()), bounds.end());
  std::vector<FloquetApproximant> out;
  for (const std::int64_t bound : bounds) {
    FloquetApproximant level;
    bool complete = true;
    for (std::size_t k = 0; k < meshes.size() && complete; ++k) {
      const Fraction* best = nullptr;
      for (const Fraction& f : convergents[k]) {
        if (f.q <= bound) best = &f;
      }
      complete = best != nullptr;
      if (!complete) break;
      const double ratio = static_cast<double>(best->p) / static_cast<double>(best->q);
      level.ratios.push_back(ratio);
      level.ratio_error = std::max(level.ratio_error, std::abs(ratio - meshes[k].phase_ratio));
    }
    if (!complete) continue;
    if (!out.empty() && out.back().ratios == level.ratios) continue;
    level.period_meshes =
        FindCommonPeriodMeshes(model.WithPhaseRatios(level.ratios), max_period_meshes);
    if (level.period_meshes == 0) break;  // longer than the bound; later levels are longer still
    out.push_back(std::move(level));
  }
  return out;
}

FloquetResult ComputeApproximantFloquet(const SystemModel& model, const FloquetOptions& options,
                                        const std::string& ratios_text) {
  std::vector<FloquetApproximant> levels =
      RationalApproximants(model, options.max_approximant_period_meshes);
  GEARDYN_THROW_UNLESS(
      levels.size() >= 2,
      "max_approximant_period_meshes: the meshes run at incommensurate frequencies ("
          << ratios_text << " times the first mesh's), and " << (levels.empty() ? "no" : "only one")
          << " rational approximant of their ratios has a common period of at most "
          << options.max_approximant_period_meshes
          << " mesh cycles; a convergence study needs two (raise the bound; the work grows with "
             "the period)");
  // The last three: the coarse ones tell nothing the study needs, and cost little anyway.
  if (levels.size() > 3) levels.erase(levels.begin(), levels.end() - 3);
  FloquetOptions inner = options;
  inner.max_approximant_period_meshes = 0;
  std::vector<FloquetResult> results;
  for (FloquetApproximant& level : levels) {
    const SystemModel approximant = model.WithPhaseRatios(level.ratios);
    FloquetResult r = ComputeFloquet(approximant, inner);
    level.max_real_exponent = MaxRealExponent(r);
    level.verdict = r.verdict;
    level.error_estimate = r.summary.error_estimate;
    const bool failed = !r.summary.ok();
    results.push_back(std::move(r));
    if (failed) break;  // its status and message are the answer
  }
  FloquetResult result = std::move(results.back());
  levels.resize(results.size());
  result.approximants = levels;
  std::ostringstream study;
  study << "meshes at incommensurate frequencies (" << ratios_text
        << " times the first mesh's): no monodromy; analysed the rational approximants with "
           "common periods ";
  for (std::size_t j = 0; j < levels.size(); ++j) {
    study << (j ? ", " : "") << levels[j].period_meshes << " (max Re mu "
          << levels[j].max_real_exponent << " 1/s, ratio error " << levels[j].ratio_error << ")";
  }
  study << " mesh cycles; the multipliers are the last one's";
  result.summary.warnings.insert(result.summary.warnings.begin(), study.str());
  result.summary.counters["approximants"] = static_cast<long>(levels.size());
  if (!result.summary.ok()) return result;
  if (results.size() < 2) return result;  // cannot happen: two levels ran unless one failed
  const FloquetResult& previous = results[results.size() - 2];
  const double change = ExponentChange(result, previous);
  const double study_estimate = result.max_abs_multiplier * result.period_s * change;
  // A NaN change (a NaN exponent) must reach the verdict: std::max would drop it.
  if (std::isnan(study_estimate) || study_estimate > result.summary.error_estimate) {
    result.summary.error_estimate = study_estimate;
  }
  const FloquetVerdict last_verdict = result.verdict;
  const bool last_marginal = result.marginal;
  FinishResult(0, options.tolerance, &result);
  if (previous.verdict != last_verdict) {
    result.verdict = FloquetVerdict::kUndetermined;
    result.summary.warnings.push_back(
        std::string("verdict undetermined: the last two rational approximants disagree (") +
        ToString(previous.verdict) + ", then " + ToString(last_verdict) +
        "): a combination resonance of an approximant, or a study too short to settle");
  } else if (result.verdict != FloquetVerdict::kUndetermined) {
    result.verdict = last_verdict;
  }
  result.marginal = result.verdict == FloquetVerdict::kStable && last_marginal;
  return result;
}

}  // namespace geardyn::internal
