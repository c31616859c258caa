/// @file
/// @brief The three-valued stability verdict (stable, unstable, undetermined) shared by the
/// Floquet analyses (floquet.hpp), the linear HB verdicts (hb_stability.hpp) and the nonlinear
/// HB points (nonlinear_hb.hpp): a computation can fail, and a failed one has no verdict.
#pragma once

#include <string>

namespace geardyn {

/// @brief The stability verdict of a Floquet analysis (three-valued: a computation can fail).
///
/// Rules (FinishResult in analyses/src/floquet/multipliers.cpp; docs/design.md "Floquet verdicts"),
/// with e = summary.error_estimate and the flexible multipliers (rigid-body ones, exactly 1,
/// excluded):
/// * kUndetermined when e or any multiplier is NaN, e is infinite, a multiplier is infinite while
///   its exponent is not finite (a failed monodromy, not an overflowing growth), or the status is
///   neither kSuccess nor kToleranceNotMet; also kToleranceNotMet unless the point is unstable
///   beyond its estimate.
/// * kUnstable when max|λ| − e > 1 (an overflowing |λ| = inf with a finite exponent Re μ > 0
///   counts), with status kSuccess or kToleranceNotMet: the growth exceeds the estimated error.
/// * kStable only when the status is kSuccess, every multiplier is finite and max|λ| ≤ 1 + e.
///   FloquetResult::marginal then says whether the stability is only neutral.
enum class FloquetVerdict { kStable, kUnstable, kUndetermined };
/// "stable", "unstable", "undetermined".
const char* ToString(FloquetVerdict verdict);
/// @brief max|λ| for a report: 4 significant digits ("1.069"), but "1 + 6.4e-12" (or "1 − …")
/// when |max|λ| − 1| < 5e-4, where 4 digits would print "1" next to an "unstable" verdict;
/// "nan"/"inf" as such.
std::string FormatMaxAbsMultiplier(double max_abs);

}  // namespace geardyn
