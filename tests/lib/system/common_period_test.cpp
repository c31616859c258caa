// FindCommonPeriodMeshes (geardyn/system/common_period.hpp) on the two-mesh fixture with mesh-b
// at ratio r: the truth is the reduced fraction r = p/q (q mesh cycles of mesh-a are p of
// mesh-b), times the cores' own periods; an irrational ratio has none.
#include "geardyn/system/common_period.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "geardyn/common/errors.hpp"
#include "periodic_fixture.hpp"

namespace geardyn {
namespace {

SystemModel TwoMesh(double ratio_b, std::int64_t period_b = 1) {
  const LinearMeshCore core_a(MeshCoreLevel::kBlankenshipSingh,
                              test::SmoothStiffness(2e8, 0.2, 0.05), 0.0125);
  FourierCoefficient k_b = test::SmoothStiffness(1.5e8, 0.1, 0.05);
  if (period_b > 1) {
    k_b = FourierCoefficient(k_b.mean(), k_b.harmonics(), period_b);  // harmonics of f/P
  }
  const LinearMeshCore core_b(MeshCoreLevel::kBlankenshipSingh, k_b, 0.0125);
  return test::TwoMeshBuilder(core_a, core_b, 0.0, 1.0, ratio_b).Build();
}

TEST(CommonPeriodTest, OneFrequencyIsTheModelPeriod) {
  const SystemModel model = TwoMesh(1.0);
  EXPECT_FALSE(HasSeveralMeshFrequencies(model));
  EXPECT_EQ(FindCommonPeriodMeshes(model), model.period_meshes());
}

TEST(CommonPeriodTest, RationalRatioGivesItsDenominator) {
  EXPECT_EQ(FindCommonPeriodMeshes(TwoMesh(21.0 / 13.0)), 13);
  EXPECT_EQ(FindCommonPeriodMeshes(TwoMesh(7.0 / 40.0)), 40);
  EXPECT_EQ(FindCommonPeriodMeshes(TwoMesh(3.0)), 1);
  // The planetary-behind-parallel ratio of the wind-turbine example from its tooth counts.
  EXPECT_EQ(FindCommonPeriodMeshes(TwoMesh(7.0 / 40.0), 39), 0);
  // Mesh-b's core repeats every 3 of its cycles: r q / 3 whole → q = 3·13.
  EXPECT_EQ(FindCommonPeriodMeshes(TwoMesh(21.0 / 13.0, 3)), 39);
  EXPECT_TRUE(HasSeveralMeshFrequencies(TwoMesh(21.0 / 13.0)));
}

TEST(CommonPeriodTest, IrrationalRatioHasNone) {
  // Convergents p/q of √2 slip by |√2 q − p| ≈ 1/(2√2 q) cycles per period: above the 1e-6
  // tolerance for every q below 10⁵ (the default bound). The golden ratio (the slowest to
  // approximate, 1/(√5 q)) likewise.
  EXPECT_EQ(FindCommonPeriodMeshes(TwoMesh(std::sqrt(2.0))), 0);
  EXPECT_EQ(FindCommonPeriodMeshes(TwoMesh(0.5 * (1.0 + std::sqrt(5.0)))), 0);
  // A slip of 1e-3 cycles accepts the convergent 577/408 (slip 8.7e-4; 99/70 slips 5.1e-3).
  EXPECT_EQ(FindCommonPeriodMeshes(TwoMesh(std::sqrt(2.0)), 100000, 1e-3), 408);
}

TEST(CommonPeriodTest, RejectsBadArguments) {
  const SystemModel model = TwoMesh(1.5);
  EXPECT_THROW(FindCommonPeriodMeshes(model, 0), InvalidInput);
  EXPECT_THROW(FindCommonPeriodMeshes(model, 10, -1.0), InvalidInput);
  EXPECT_THROW(FindCommonPeriodMeshes(model, 10, std::nan("")), InvalidInput);
}

TEST(CommonPeriodTest, WithPhaseRatiosReplacesOnlyTheRatios) {
  // The rational approximant of the √2 train by 99/70: its period is 70; the original keeps none,
  // and everything but the ratios (and the id) is the original's.
  const SystemModel model = TwoMesh(std::sqrt(2.0));
  const SystemModel approximant = model.WithPhaseRatios({1.0, 99.0 / 70.0});
  EXPECT_EQ(FindCommonPeriodMeshes(approximant), 70);
  EXPECT_EQ(FindCommonPeriodMeshes(model), 0);
  EXPECT_EQ(model.meshes()[1].phase_ratio, std::sqrt(2.0));
  EXPECT_EQ(approximant.meshes()[1].phase_ratio, 99.0 / 70.0);
  EXPECT_EQ(approximant.meshes()[1].phase_offset, model.meshes()[1].phase_offset);
  EXPECT_NE(approximant.id(), model.id());
  EXPECT_EQ(approximant.num_dofs(), model.num_dofs());
  EXPECT_EQ(approximant.period_meshes(), model.period_meshes());
  EXPECT_EQ((approximant.DenseMass() - model.DenseMass()).norm(), 0.0);
  EXPECT_THROW(model.WithPhaseRatios({1.0}), InvalidInput);
  EXPECT_THROW(model.WithPhaseRatios({1.0, 0.0}), InvalidInput);
  EXPECT_THROW(model.WithPhaseRatios({1.0, std::nan("")}), InvalidInput);
}

}  // namespace
}  // namespace geardyn
