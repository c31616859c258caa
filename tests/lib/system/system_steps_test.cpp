// CollectSystemSteps: K and C are constant inside every interval and jump only at breakpoints;
// the breakpoints are those of the cores mapped through the phase offsets.
#include "geardyn/system/system_steps.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

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

TEST(SystemSteps, SmoothStiffnessAndIncommensurateSecondMeshAreRejected) {
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
  // A second stage at an irrational ratio has no common period: refused.
  const HandPairParams p;
  SystemBuilder builder = HandPairBuilder(p, SpurCore(p));
  builder.AddBody("third", DiagMass(1.0, 1e-3, 1e-3), Vector3(0, 0.2, 0));
  builder.AddMesh("second-stage", BodyIndex(1), BodyIndex(2), HandPairJacobian(p), SpurCore(p),
                  std::nullopt, std::sqrt(2.0) / 3.0);
  EXPECT_THROW((void)CollectSystemSteps(builder.Build()), InvalidInput);
}

// One mesh frequency with a period beyond the common-period search bound (10⁵ cycles: a hunting
// period of coprime tooth counts near 317 × 331 = 104 927): the steps span the model's period.
TEST(SystemSteps, LongHuntingPeriodOfOneFrequencyIsKept) {
  const std::int64_t P = 104927;
  VectorX breakpoints(2);
  breakpoints << 0.0, 1.0;
  MatrixX values(3, 2);
  values << 6e8, 3e8, 0.0, 0.0, 1e4, 5e3;
  const LinearMeshCore core(MeshCoreLevel::kBlankenshipSingh,
                            PiecewiseConstantCoefficient(breakpoints, values, P), 0.0125);
  const SystemSteps steps = CollectSystemSteps(HandPairBuilder(HandPairParams(), core).Build());
  EXPECT_EQ(steps.period_meshes, P);
  EXPECT_EQ(steps.num_intervals(), 2);
  EXPECT_NEAR(steps.interval_width(0), 1.0, 1e-9);
}

// Mesh b at r = 2/5 of mesh a (a two-stage train): the system repeats after 5 cycles of θ, in
// which mesh a makes 5 own cycles and mesh b 2; b's own-phase jump β lands at θ = (β + 2πj − φ)/r.
TEST(SystemSteps, SecondMeshFrequencyMapsItsBreakpointsThroughTheRatio) {
  const double offset = 0.3, r = 0.4;
  const SystemModel model =
      TwoMeshBuilder(WaveCore(1.6, 0.0), WaveCore(1.35, 0.2), offset, 1.0, r).Build();
  const SystemSteps steps = CollectSystemSteps(model);
  EXPECT_EQ(steps.period_meshes, 5);
  EXPECT_DOUBLE_EQ(steps.period, 5.0 * kTwoPi);
  std::vector<double> expected;
  for (int j = 0; j < 5; ++j) {
    expected.push_back(kTwoPi * j);
    expected.push_back(kTwoPi * (j + 0.6));
  }
  for (int j = 0; j < 2; ++j) {
    for (const double beta : {0.2, 0.2 + kTwoPi * 0.35}) {
      double theta = std::fmod((beta + kTwoPi * j - offset) / r, 5.0 * kTwoPi);
      expected.push_back(theta < 0.0 ? theta + 5.0 * kTwoPi : theta);
    }
  }
  std::sort(expected.begin(), expected.end());
  ASSERT_EQ(steps.num_intervals(), static_cast<int>(expected.size()));
  for (int k = 0; k < steps.num_intervals(); ++k) {
    EXPECT_NEAR(steps.breakpoints[k], expected[static_cast<std::size_t>(k)], 1e-12);
  }
  // K is constant inside each interval: at two points of it the assembled K agrees.
  SystemWorkspace ws(model, StorageKind::kDense);
  for (int k = 0; k < steps.num_intervals(); ++k) {
    const double a = steps.interval_begin(k), w = steps.interval_width(k);
    const MatrixX K1 = AssembleStiffness(model, ws, a + 0.25 * w);
    const MatrixX K2 = AssembleStiffness(model, ws, a + 0.75 * w);
    EXPECT_LE((K1 - K2).cwiseAbs().maxCoeff(), 1e-12 * K1.cwiseAbs().maxCoeff()) << k;
  }
}

}  // namespace
}  // namespace geardyn::test
