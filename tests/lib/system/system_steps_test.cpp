// CollectSystemSteps: K and C are constant inside every interval and jump only at breakpoints;
// the breakpoints are those of the cores mapped through the phase offsets.
#include "geardyn/system/system_steps.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "geardyn/system/workspace.hpp"
#include "periodic_fixture.hpp"
#include "support/matrix_compare.hpp"

namespace geardyn::test {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

LinearMeshCore WaveCore(double contact_ratio, double start, double c_m = 0.0) {
  return LinearMeshCore(MeshCoreLevel::kBlankenshipSingh, SpurWave(3e8, 6e8, contact_ratio, start),
                        0.0125, std::nullopt, MeshDamping::FromCoefficient(c_m));
}

TEST(SystemSteps, BreakpointsAreTheUnionOfBothMeshesShiftedByTheirOffsets) {
  const double offset = 0.9;
  const SystemModel model = TwoMeshSystem(WaveCore(1.6, 0.0), WaveCore(1.35, 0.2), offset);
  const SystemSteps steps = CollectSystemSteps(model);
  EXPECT_DOUBLE_EQ(steps.period, kTwoPi);
  // mesh a: 0, 2π·0.6; mesh b (θ = θ_b − φ): 0.2 − 0.9 + 2π, 0.2 + 2π·0.35 − 0.9.
  std::vector<double> expected = {0.0, kTwoPi * 0.6, 0.2 - offset + kTwoPi,
                                  0.2 + kTwoPi * 0.35 - offset};
  std::sort(expected.begin(), expected.end());
  ASSERT_EQ(steps.num_intervals(), 4);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(steps.breakpoints[k], expected[k], 1e-14);
  EXPECT_DOUBLE_EQ(steps.interval_end(3), kTwoPi);
}

TEST(SystemSteps, StiffnessAndDampingAreConstantInsideEachIntervalAndJumpAtItsEnds) {
  const SystemModel model =
      TwoMeshSystem(WaveCore(1.6, 0.0, 800.0), WaveCore(1.35, 0.2, 500.0), 0.9);
  const SystemSteps steps = CollectSystemSteps(model);
  SystemWorkspace ws(model);
  for (int k = 0; k < steps.num_intervals(); ++k) {
    const MatrixX K_mid = AssembleStiffness(model, ws, steps.interval_midpoint(k));
    const MatrixX C_mid = AssembleDamping(model, ws, steps.interval_midpoint(k));
    for (const double s : {1e-9, 0.25, 0.75, 1.0 - 1e-9}) {
      const double theta = steps.interval_begin(k) + s * steps.interval_width(k);
      EXPECT_MATRIX_NEAR(AssembleStiffness(model, ws, theta), K_mid, 0.0);
      EXPECT_MATRIX_NEAR(AssembleDamping(model, ws, theta), C_mid, 0.0);
    }
    // The value changes across every breakpoint except the forced one at 0 when nothing jumps
    // there (mesh a jumps at 0 here, so all of them).
    const MatrixX K_before = AssembleStiffness(model, ws, steps.interval_begin(k) - 1e-9);
    EXPECT_GT((K_before - K_mid).norm(), 1e6) << "interval " << k;
  }
}

TEST(SystemSteps, HuntingPeriodRepeatsTheMeshBreakpoints) {
  // ε with period 3 mesh cycles makes P = 3; the stiffness steps repeat every 2π.
  MatrixX te(2, 3);
  te << 1e-6, -2e-6, 0.5e-6, 0.0, 0.0, 0.0;
  const LinearMeshCore a(MeshCoreLevel::kBlankenshipSingh, SpurWave(3e8, 6e8, 1.6), 0.0125,
                         Coefficient(TableCoefficient(te, 3)));
  const SystemModel model = TwoMeshSystem(a, WaveCore(1.6, 0.0));
  const SystemSteps steps = CollectSystemSteps(model);
  EXPECT_EQ(steps.period_meshes, 3);
  ASSERT_EQ(steps.num_intervals(), 6);
  for (int j = 0; j < 3; ++j) {
    EXPECT_NEAR(steps.breakpoints[2 * j], kTwoPi * j, 1e-13);
    EXPECT_NEAR(steps.breakpoints[2 * j + 1], kTwoPi * (j + 0.6), 1e-13);
  }
}

TEST(SystemSteps, ConstantSystemIsOneInterval) {
  const HandPairParams p;
  const SystemModel model = TwoMeshSystem(SpurCore(p), SpurCore(p), 0.4);
  EXPECT_TRUE(HasPiecewiseConstantOperator(model));
  const SystemSteps steps = CollectSystemSteps(model);
  ASSERT_EQ(steps.num_intervals(), 1);
  EXPECT_DOUBLE_EQ(steps.interval_width(0), kTwoPi);
}

TEST(SystemSteps, SmoothStiffnessAndSecondMeshFrequencyAreRejectedByName) {
  const LinearMeshCore smooth(MeshCoreLevel::kBlankenshipSingh, SmoothStiffness(4e8, 0.1, 0.05),
                              0.0125);
  const SystemModel model = TwoMeshSystem(WaveCore(1.6, 0.0), smooth);
  EXPECT_FALSE(HasPiecewiseConstantOperator(model));
  try {
    (void)CollectSystemSteps(model);
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("mesh 'mesh-b'"), std::string::npos) << e.what();
  }
  const HandPairParams p;
  SystemBuilder builder = HandPairBuilder(p, SpurCore(p));
  builder.AddBody("third", DiagMass(1.0, 1e-3, 1e-3), Vector3(0, 0.2, 0));
  builder.AddMesh("second-stage", BodyIndex(1), BodyIndex(2), HandPairJacobian(p), SpurCore(p),
                  std::nullopt, 0.4);
  EXPECT_THROW((void)CollectSystemSteps(builder.Build()), InvalidInput);
}

}  // namespace
}  // namespace geardyn::test
