// kAuto's modal projection (issue 12): Floquet on the mesh-driven modal basis of the mean system,
// accepted when its estimate of max|λ| — the number the verdict reads — is small and does not
// decide the verdict, else widened, else the unprojected system.
//
// **Why a basis is enough.** A parametric resonance of the mesh stiffness needs f_m ≈ (f_p ± f_q)/k
// with modes p, q that store strain energy in the mesh; the basis (SelectMeshDrivenBasis) holds
// every mode below k_max·f_m/2 with margin (k_max = 3, ×1.5), every mode with ≥ 5 % of its strain
// energy in a mesh, and every mode that decays over a period no faster than those. A shaft's
// element modes far above the mesh-driven range only add a quasi-static correction to the retained
// ones, which the estimate measures, and their own multipliers are below the slowest-decaying
// retained mode's (the decay rule), so max|λ| does not come from them.
//
// **Estimate** e = e_trunc + e_inner, on max|λ| of the flexible multipliers (rigid ones are exact):
// e_trunc = 4·max(|M₀ − M₁|, |M₁ − M₂|), M_i = max|λ_flex| of the runs on m₀, m₁ = ⌈1.5m₀⌉,
// m₂ = ⌈1.5m₁⌉ modes (the factor 4 and the second level as in modal_projection.cpp); e_inner the
// m₂ run's own (Magnus or round-off) estimate. Unlike the forced kModalProjection it does not
// compare the complex multipliers: the phase of a stiff retained mode's multiplier (ω_k T of
// tens of radians) moves by 1e-2 when its frequency moves by 1e-3 between bases, which says
// nothing about stability (measured on builtin:geared-shafts: complex changes 0.02–0.2 with
// max|λ| changes of 1e-7). The reported multipliers are the m₂ run's; the phases of its highest
// modes are not covered by e.
//
// **Acceptance** (status success), only where the changes shrink (d₂ = |M₁ − M₂| ≤ d₁ =
// |M₀ − M₁|, or d₂ below the inner estimate): e ≤ tolerance; or e ≤ 1e-4
// (kAutoProjectionMaxEstimate) and |1 − M₂| > 10·e (kAutoVerdictSafety) — the verdict is then the
// same for every value within ten estimates, and a warning says that the projection did not meet
// the tolerance and how to get the full system. Otherwise the window moves up one level (m₀ ← m₁),
// and when the check basis would hold all n modes the unprojected system is solved instead at the
// requested tolerance (`full`). The inner runs use the error target 0.01·max(tolerance, 1e-6) on Φ.
// A failed inner run (status not success or NaN estimate) is returned as it is (undetermined).
#include <algorithm>
#include <cmath>
#include <utility>

#include "floquet/floquet_internal.hpp"

namespace geardyn::internal {
namespace {

constexpr double kSafetyFactor = 4.0;  // as modal_projection.cpp

double FlexibleMax(const FloquetResult& r) { return MaxAbsOf(WithoutRigid(r.multipliers)); }

}  // namespace

FloquetResult AutoModalProjectionFloquet(
    const std::function<MatrixX(int)>& modes, int num_dofs,
    const std::function<PeriodicSecondOrderSystem(const MatrixX&)>& project,
    const std::function<FloquetResult()>& full, const FloquetOptions& options, int initial_modes) {
  FloquetOptions inner = options;
  inner.method = FloquetMethod::kAuto;
  inner.modal_projection_min_dofs = num_dofs + 1;  // never recurse
  inner.keep_monodromy = false;
  inner.tolerance =
      kAutoInnerToleranceFactor * std::max(options.tolerance, kAutoProjectionAccuracy);
  auto run = [&](int m) { return ComputeReducedFloquet(project(modes(m)), inner); };
  auto unprojected = [&](const std::string& why) {
    FloquetResult r = full();
    r.summary.warnings.push_back("kAuto: the modal projection " + why +
                                 "; the full system was solved instead");
    return r;
  };
  int m0 = std::min(initial_modes > 0 ? initial_modes : 12, num_dofs);
  int m1 = NextBasisSize(m0, num_dofs), m2 = NextBasisSize(m1, num_dofs);
  if (m2 >= num_dofs) return unprojected("would need all " + std::to_string(num_dofs) + " modes");
  FloquetResult r0 = run(m0), r1 = run(m1), r2 = run(m2);
  long runs = 3;
  while (true) {
    const double M0 = FlexibleMax(r0), M1 = FlexibleMax(r1), M2 = FlexibleMax(r2);
    const double d1 = std::abs(M0 - M1), d2 = std::abs(M1 - M2);
    const double truncation = kSafetyFactor * MaxPropagatingNaN(d1, d2);
    const double e = truncation + r2.summary.error_estimate;  // NaN stays NaN
    const bool ok = r0.summary.ok() && r1.summary.ok() && r2.summary.ok();
    const bool met = e <= options.tolerance;
    // Trusted only where the changes shrink (d₂ ≤ d₁, the regime the factor 4 was calibrated in)
    // or are below the inner runs' own error (noise): a growing change means that a coupling
    // mode has just entered and more may follow (measured: 204-DOF shafts at 2.3 f_p, changes
    // 5.7e-7 then 1.2e-6, true error of M₂ 4.9e-6 > e = 4.7e-6).
    const bool shrinking = d2 <= d1 || d2 <= r2.summary.error_estimate;
    const bool resolved =
        e <= kAutoProjectionMaxEstimate && kAutoVerdictSafety * e < std::abs(1.0 - M2);
    const bool accepted = shrinking && (met || resolved);
    if (!ok || std::isnan(e) || accepted) {
      FloquetResult out = std::move(r2);
      if (ok && !std::isnan(e)) {
        out.summary.error_estimate = e;
      } else {
        out.summary.error_estimate = MaxPropagatingNaN(out.summary.error_estimate, e);
        if (out.summary.ok()) {
          const FloquetResult& bad = !r0.summary.ok() ? r0 : r1;
          out.summary.status = bad.summary.ok() ? Status::kNumericalIssue : bad.summary.status;
          out.summary.message =
              "modal_projection (auto): " +
              (bad.summary.ok() ? std::string("NaN estimate of max|λ|") : bad.summary.message);
        }
      }
      out.summary.counters["modes"] = m0;
      out.summary.counters["modes_check"] = m2;
      out.summary.counters["projection_runs"] = runs;
      out.method_used = FloquetMethod::kModalProjection;
      if (ok && accepted && !met) {
        out.summary.warnings.push_back(
            "kAuto modal projection on " + std::to_string(m2) + " of " + std::to_string(num_dofs) +
            " modes: max|λ| is known to " + FormatEstimate(e) + " (basis truncation " +
            FormatEstimate(truncation) + "), above the tolerance " +
            FormatEstimate(options.tolerance) +
            ", which does not change the verdict; --method magnus (or exact_steps) solves the "
            "full system to the tolerance");
      }
      RedecideVerdict(&out);
      return out;
    }
    const int next = NextBasisSize(m2, num_dofs);
    if (next >= num_dofs) {
      return unprojected("estimated max|λ| to " + FormatEstimate(e) + " with " +
                         std::to_string(m0) + "/" + std::to_string(m1) + "/" + std::to_string(m2) +
                         " modes and would need all " + std::to_string(num_dofs));
    }
    m0 = m1;
    m1 = m2;
    m2 = next;
    r0 = std::move(r1);
    r1 = std::move(r2);
    r2 = run(m2);
    ++runs;
  }
}

}  // namespace geardyn::internal
