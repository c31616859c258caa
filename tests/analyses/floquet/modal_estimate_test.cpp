// kModalProjection's error estimate is conservative: on two geared-shaft systems and several
// basis sizes (m ≥ 6; see modal_projection.cpp for the m = 4 case no difference-based estimate
// sees) it bounds the true error of the reported multipliers, measured against the full system by
// the dense exact-steps path (each reported multiplier to the nearest full one).
#include <gtest/gtest.h>

#include <cmath>

#include "floquet_test_support.hpp"

namespace geardyn::test {
namespace {

constexpr double kMeshHz = 5000.0;

double ErrorAgainst(const VectorXc& reported, const VectorXc& full) {
  double worst = 0.0;
  for (int i = 0; i < reported.size(); ++i) {
    worst = std::max(worst, (full.array() - reported[i]).abs().minCoeff());
  }
  return worst;
}

void ExpectConservative(const SystemModel& model, std::initializer_list<int> basis_sizes) {
  FloquetOptions o;
  o.mesh_frequency_hz = kMeshHz;
  o.split_blocks = false;
  o.method = FloquetMethod::kExactSteps;
  const FloquetResult full = ComputeFloquet(model, o);
  ASSERT_TRUE(full.summary.ok()) << full.summary.message;
  o.method = FloquetMethod::kModalProjection;
  for (const int m : basis_sizes) {
    o.num_modes = m;
    const FloquetResult r = ComputeFloquet(model, o);
    EXPECT_EQ(r.summary.counters.at("modes"), m);
    const double error = ErrorAgainst(r.multipliers, full.multipliers);
    EXPECT_GT(error, 0.0) << m;  // a real truncation, not the complete basis
    EXPECT_GE(r.summary.error_estimate, error) << "m = " << m;
    // … and not uselessly loose (up to ≈ 700× measured where the error drops fast).
    EXPECT_LE(r.summary.error_estimate, 2000.0 * error) << "m = " << m;
  }
}

TEST(ModalEstimateTest, BoundsTheErrorOnUndampedGearedShafts) {
  // 60 DOFs, mesh damping only.
  ExpectConservative(GearedShafts(4, HandSpurWaveCore(600.0)), {6, 8, 12, 16, 20});
}

TEST(ModalEstimateTest, BoundsTheErrorOnDampedGearedShafts) {
  // 36 DOFs, shaft damping β = 2e-6 s and mesh damping.
  ExpectConservative(GearedShafts(2, HandSpurWaveCore(600.0), 2e-6), {6, 8, 10, 12});
}

}  // namespace
}  // namespace geardyn::test
