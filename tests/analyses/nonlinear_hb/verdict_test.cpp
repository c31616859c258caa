/// @file
/// @brief The nonlinear HB's stability verdict is three-valued (issue 12 leftover, architecture
/// §3.7 "no verdict without a clean status"): a NaN or infinite max |μ| is undetermined, never
/// unstable (nor stable through a comparison that NaN fails both ways), and a point whose
/// Newton did not converge carries no verdict.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>

#include "geardyn/analyses/nonlinear_hb.hpp"

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

/// A law whose force is NaN wherever u > 0 (a broken user law): no Newton can converge.
class NanLaw final : public NhbNonlinearLaw {
 public:
  int num_coordinates() const override { return 1; }
  void Evaluate(const MatrixX& u, const VectorX& /*phase*/, MatrixX& force,
                MatrixX& jacobian) const override {
    force = u.unaryExpr(
        [](double v) { return v > 0.0 ? std::numeric_limits<double>::quiet_NaN() : 0.0; });
    jacobian = MatrixX::Zero(1, u.cols());
  }
  void ContactBranch(MatrixX& stiffness, VectorX& offset) const override {
    stiffness = MatrixX::Zero(1, 1);
    offset = VectorX::Zero(1);
  }
};

// A point whose solve failed carries no verdict (before, `stable` stayed true on it) and the
// solve reports the failure.
TEST(NhbVerdict, FailedSolveHasNoVerdict) {
  NhbProblem problem;
  problem.mass = MatrixX::Identity(1, 1);
  problem.damping = 0.1 * MatrixX::Identity(1, 1);
  problem.stiffness = MatrixX::Identity(1, 1);
  problem.projection = MatrixX::Identity(1, 1);
  problem.force_mean = VectorX::Ones(1);  // static deflection u = 1 > 0: the law is NaN there
  problem.force_amplitude = VectorXc::Zero(1);
  problem.law = std::make_shared<NanLaw>();
  NhbOptions options;
  options.harmonics = 4;
  options.force_integration = NhbForceIntegration::kSampled;
  const NhbSolveResult r = SolveNonlinearHarmonicBalance(problem, 1.0, options);
  ASSERT_NE(r.point.status, Status::kSuccess);
  EXPECT_FALSE(r.summary.ok());
  EXPECT_EQ(r.point.stable, FloquetVerdict::kUndetermined);
}

}  // namespace
}  // namespace geardyn
