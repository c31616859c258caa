// The marginal flag and the undamped-modes list are the same whatever the method (issue 12):
// a stable verdict with a flexible multiplier on the unit circle is "stable, marginal" for the
// exact product, Magnus, the ODE path, ARPACK and a complete modal projection alike. Truth: the
// exact step product (round-off) for the verdict, and the mean system's modes for the list
// (undamped hand pair: every flexible mode; mesh damping only: the modes the mesh does not damp).
#include <gtest/gtest.h>

#include <string>

#include "floquet_test_support.hpp"

namespace geardyn::test {
namespace {

constexpr FloquetMethod kMethods[] = {FloquetMethod::kExactSteps, FloquetMethod::kMagnus,
                                      FloquetMethod::kOdeStepper, FloquetMethod::kArpackMonodromy,
                                      FloquetMethod::kModalProjection};

FloquetResult RunFloquet(const SystemModel& model, FloquetMethod method, double hz) {
  FloquetOptions o;
  o.mesh_frequency_hz = hz;
  o.method = method;
  o.tolerance = 1e-8;
  o.arpack_nev = 4;
  // A complete basis: the projection is then a change of variables (estimate 0).
  if (method == FloquetMethod::kModalProjection) o.num_modes = model.num_dofs();
  return ComputeFloquet(model, o);
}

void ExpectSameMarginalAsExact(const SystemModel& model, double hz) {
  const FloquetResult exact = RunFloquet(model, FloquetMethod::kExactSteps, hz);
  ASSERT_EQ(exact.verdict, FloquetVerdict::kStable) << exact.max_abs_multiplier;
  ASSERT_TRUE(exact.marginal);
  ASSERT_FALSE(exact.undamped_modes.empty());
  for (const FloquetMethod method : kMethods) {
    SCOPED_TRACE(std::string("method ") + ToString(method) + ", f_m = " + std::to_string(hz));
    const FloquetResult r = RunFloquet(model, method, hz);
    // ARPACK on a system whose multipliers all sit on the unit circle may not resolve them
    // (floquet.hpp); it must then say so, never "stable" without "marginal".
    if (r.verdict == FloquetVerdict::kUndetermined) {
      EXPECT_EQ(method, FloquetMethod::kArpackMonodromy) << r.summary.message;
      continue;
    }
    EXPECT_EQ(r.verdict, exact.verdict)
        << r.max_abs_multiplier << " ± " << r.summary.error_estimate;
    EXPECT_EQ(r.marginal, exact.marginal);
    ASSERT_EQ(r.undamped_modes.size(), exact.undamped_modes.size());
    for (std::size_t k = 0; k < r.undamped_modes.size(); ++k) {
      EXPECT_EQ(r.undamped_modes[k].index, exact.undamped_modes[k].index);
    }
  }
}

TEST(MarginalConsistencyTest, UndampedPairIsMarginalForEveryMethod) {
  ExpectSameMarginalAsExact(HandPair(HandSpurWaveCore(0.0)), 500.0);
}

TEST(MarginalConsistencyTest, MeshDampingOnlyLeavesUndampedModesForEveryMethod) {
  ExpectSameMarginalAsExact(HandPair(HandSpurWaveCore(600.0)), 500.0);
}

}  // namespace
}  // namespace geardyn::test
