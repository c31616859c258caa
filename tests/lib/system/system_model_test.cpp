#include "geardyn/system/system_model.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "geardyn/system/workspace.hpp"
#include "hand_pair.hpp"
#include "support/expect_throws.hpp"

namespace geardyn {
namespace {

using test::HandPairBuilder;
using test::HandPairParams;
using test::SortedEigenvalues;
using test::SpurCore;

MatrixX MeanStiffness(const SystemModel& model) {
  SystemWorkspace ws(model, StorageKind::kDense);
  return AssembleMeanStiffness(model, ws);
}

std::vector<int> TorsionalDofs(const SystemModel& model) {
  return {model.dof_map().dof(BodyIndex(0), BodyDof::kThetaZ),
          model.dof_map().dof(BodyIndex(1), BodyDof::kThetaZ)};
}

// ω² = k̄ (r_b1²/I1 + r_b2²/I2) and one rigid-body zero (issue 4).
TEST(SystemModelTest, TorsionalPairMatchesClosedForm) {
  const HandPairParams p;
  const SystemModel full = HandPairBuilder(p, SpurCore(p)).Build();
  const SystemModel pair = full.Restrict(TorsionalDofs(full));
  ASSERT_EQ(pair.num_dofs(), 2);
  const VectorX lambda = SortedEigenvalues(MeanStiffness(pair), pair.DenseMass());
  const double expected = p.k * (p.r1 * p.r1 / p.I1 + p.r2 * p.r2 / p.I2);
  EXPECT_NEAR(lambda(0), 0.0, 1e-9 * expected);
  EXPECT_NEAR(lambda(1), expected, 1e-12 * expected);
}

// The same with the translations held by very stiff bearings instead of the restriction.
TEST(SystemModelTest, TorsionalPairWithStiffBearingsApproachesClosedForm) {
  HandPairParams p;
  p.bearing = 1e15;  // k / k_bearing = 4e-7
  const SystemModel full = HandPairBuilder(p, SpurCore(p)).Build();
  const VectorX lambda = SortedEigenvalues(MeanStiffness(full), full.DenseMass());
  const double expected = p.k * (p.r1 * p.r1 / p.I1 + p.r2 * p.r2 / p.I2);
  EXPECT_NEAR(lambda(0), 0.0, 1e-6 * expected);
  double nearest = lambda(1);
  for (int i = 1; i < lambda.size(); ++i) {
    if (std::abs(lambda(i) - expected) < std::abs(nearest - expected)) nearest = lambda(i);
  }
  EXPECT_NEAR(nearest, expected, 1e-5 * expected);
}

// Spur limit (spec 01 §6): the torsional/transverse DOFs decouple from the axial/rocking ones,
// and the full spectrum is the union of the blocks' spectra.
TEST(SystemModelTest, SpurLimitSplitsIntoBlocksWithTheSameEigenvalues) {
  const HandPairParams p;
  const SystemModel model = HandPairBuilder(p, SpurCore(p)).Build();
  const DofMap& map = model.dof_map();
  ASSERT_GT(model.num_blocks(), 2);
  int torsional_block = -1;
  int rocking_block = -1;
  for (int b = 0; b < model.num_blocks(); ++b) {
    const std::vector<int>& block = model.blocks()[b];
    auto has = [&](BodyIndex body, BodyDof c) {
      return std::find(block.begin(), block.end(), map.dof(body, c)) != block.end();
    };
    if (has(BodyIndex(0), BodyDof::kThetaZ)) torsional_block = b;
    if (has(BodyIndex(0), BodyDof::kThetaX)) rocking_block = b;
  }
  ASSERT_GE(torsional_block, 0);
  ASSERT_GE(rocking_block, 0);
  EXPECT_NE(torsional_block, rocking_block);
  EXPECT_EQ(model.blocks()[torsional_block],
            (std::vector<int>{1, 5, 7, 11}));                          // y_i, θz_i, y_j, θz_j
  EXPECT_EQ(model.blocks()[rocking_block], (std::vector<int>{3, 9}));  // θx_i, θx_j

  const VectorX full = SortedEigenvalues(MeanStiffness(model), model.DenseMass());
  std::vector<double> union_values;
  for (int b = 0; b < model.num_blocks(); ++b) {
    const SystemModel sub = model.RestrictToBlock(b);
    const VectorX values = SortedEigenvalues(MeanStiffness(sub), sub.DenseMass());
    union_values.insert(union_values.end(), values.data(), values.data() + values.size());
  }
  std::sort(union_values.begin(), union_values.end());
  ASSERT_EQ(static_cast<int>(union_values.size()), full.size());
  for (int i = 0; i < full.size(); ++i) {
    EXPECT_NEAR(union_values[i], full(i), 1e-10 * full.cwiseAbs().maxCoeff()) << "i = " << i;
  }
}

TEST(SystemModelTest, HelicalLikeCrossTermCouplesTheBlocks) {
  const HandPairParams p;
  // c1 = K·h ≠ 0 (moving load centre): η and ζ rows couple.
  const LinearMeshCore core(MeshCoreLevel::kBlankenshipSingh,
                            ConstantCoefficient(Vector3(p.k, 0.2 * p.k * p.b, p.k * p.b * p.b / 2)),
                            p.b);
  const SystemModel model = HandPairBuilder(p, core).Build();
  const std::vector<int>& block0 = model.blocks()[1];  // the block holding y_i (DOF 1)
  EXPECT_EQ(block0, (std::vector<int>{1, 3, 5, 7, 9, 11}));
}

TEST(SystemModelTest, FactsAndPlanarRestriction) {
  const HandPairParams p;
  const SystemModel model = HandPairBuilder(p, SpurCore(p)).Build();
  EXPECT_EQ(model.num_dofs(), 12);
  EXPECT_EQ(model.time_dependence(), TimeDependence::kConstant);
  EXPECT_EQ(model.period_meshes(), 1);
  EXPECT_EQ(model.storage_hint(), StorageKind::kDense);
  EXPECT_TRUE(model.is_symmetric());
  const SystemModel copy = model;  // O(1), shares the data
  EXPECT_EQ(copy.id(), model.id());

  const SystemModel planar = model.RestrictToPlanar();
  EXPECT_EQ(planar.num_dofs(), 6);
  EXPECT_NE(planar.id(), model.id());
  ASSERT_EQ(planar.num_meshes(), 1);
  EXPECT_EQ(planar.meshes()[0].dofs[3], -1);  // θx_i held fixed
  EXPECT_EQ(planar.meshes()[0].dofs[5], planar.dof_map().dof(BodyIndex(0), BodyDof::kThetaZ));
  EXPECT_EQ(planar.elements().size(), 2u);
  EXPECT_THROWS_MESSAGE(model.RestrictToBlock(100), InvalidInput, "block 100");
}

TEST(SystemModelTest, PiecewiseCoreMakesThePeriodicFacts) {
  const HandPairParams p;
  MatrixX values(3, 2);
  values << p.k, 1.5 * p.k, 0, 0, p.k * p.b * p.b / 3, 1.5 * p.k * p.b * p.b / 3;
  const LinearMeshCore core(MeshCoreLevel::kBlankenshipSingh,
                            PiecewiseConstantCoefficient(Eigen::Vector2d(0.0, 2.0), values, 3),
                            p.b);
  const SystemModel model = HandPairBuilder(p, core).Build();
  EXPECT_EQ(model.time_dependence(), TimeDependence::kPiecewiseConstant);
  EXPECT_EQ(model.period_meshes(), 3);
}

}  // namespace
}  // namespace geardyn
