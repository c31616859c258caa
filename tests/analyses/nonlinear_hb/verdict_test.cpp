/// @file
/// @brief The nonlinear HB's stability verdict is three-valued (issue 12 leftover, architecture
/// §3.7 "no verdict without a clean status"): a NaN or infinite max |μ| is undetermined, never
/// unstable (nor stable through a comparison that NaN fails both ways), and a point whose
/// Newton did not converge carries no verdict.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "analyses/nonlinear_hb/bk_parameter_sets.hpp"
#include "geardyn/analyses/nonlinear_hb.hpp"
#include "geardyn/analyses/nonlinear_hb_clearance.hpp"

namespace geardyn {
namespace {

constexpr double kMargin = 1e-5;  // NhbOptions::stability_margin default

TEST(NhbVerdict, NonFiniteMultiplierIsUndetermined) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(NhbVerdict(nan, kMargin), FloquetVerdict::kUndetermined);
  EXPECT_EQ(NhbVerdict(inf, kMargin), FloquetVerdict::kUndetermined);
  EXPECT_EQ(NhbVerdict(-inf, kMargin), FloquetVerdict::kUndetermined);
}

// The rule of the margin (NhbOptions::stability_margin): stable iff max|μ| < 1 + margin.
TEST(NhbVerdict, FiniteMultiplierAgainstTheMargin) {
  EXPECT_EQ(NhbVerdict(0.0, kMargin), FloquetVerdict::kStable);
  EXPECT_EQ(NhbVerdict(0.9, kMargin), FloquetVerdict::kStable);
  EXPECT_EQ(NhbVerdict(1.0 + 0.5 * kMargin, kMargin), FloquetVerdict::kStable);
  EXPECT_EQ(NhbVerdict(1.0 + kMargin, kMargin), FloquetVerdict::kUnstable);
  EXPECT_EQ(NhbVerdict(1.03, kMargin), FloquetVerdict::kUnstable);
  EXPECT_EQ(NhbVerdict(1.0, 0.0), FloquetVerdict::kUnstable);  // no margin: |μ| = 1 is not < 1
}

// One Newton iteration cannot reach the contact-loss orbit of the B&K oscillator from the
// contact-branch guess: the solve reports the failure and its point has no verdict (before,
// `stable` stayed true on a failed point).
TEST(NhbVerdict, FailedSolveHasNoVerdict) {
  NhbOptions options;
  options.harmonics = 16;
  options.max_newton_iterations = 1;
  const NhbSolveResult r = SolveNonlinearHarmonicBalance(
      MakeClearanceOscillator(testing::BkSingleSidedSet()), 0.85, options);
  ASSERT_NE(r.point.status, Status::kSuccess) << "expected a failed solve at 1 iteration";
  EXPECT_FALSE(r.summary.ok());
  EXPECT_EQ(r.point.stable, FloquetVerdict::kUndetermined);
}

}  // namespace
}  // namespace geardyn
