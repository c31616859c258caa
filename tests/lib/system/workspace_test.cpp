#include "geardyn/system/workspace.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "hand_pair.hpp"
#include "support/expect_throws.hpp"
#include "support/matrix_compare.hpp"
#include "support/no_malloc.hpp"

namespace geardyn {
namespace {

using test::HandPairBuilder;
using test::HandPairJacobian;
using test::HandPairParams;
using test::SpurCore;

constexpr double kTol = 1e-13;  // 12×12 assembly: a few rounding errors per entry

// A time-varying B–S core with a moving load centre (c1 ≠ 0) and ε, damping c_m.
LinearMeshCore VaryingCore(const HandPairParams& p, double c_m = 0.0) {
  MatrixX values(3, 3);
  values << p.k, 1.6 * p.k, 1.2 * p.k,         //
      0.1 * p.k * p.b, -0.2 * p.k * p.b, 0.0,  //
      0.4 * p.k * p.b * p.b, 0.7 * p.k * p.b * p.b, 0.5 * p.k * p.b * p.b;
  MatrixX te(2, 3);
  te << 1e-6, 2e-6, -1e-6, 1e-5, 0.0, -2e-5;
  return LinearMeshCore(MeshCoreLevel::kBlankenshipSingh,
                        PiecewiseConstantCoefficient(Eigen::Vector3d(0.0, 2.0, 4.0), values), p.b,
                        PiecewiseConstantCoefficient(Eigen::Vector3d(0.0, 1.0, 3.0), te),
                        c_m > 0 ? MeshDamping::FromCoefficient(c_m) : MeshDamping::None());
}

TEST(WorkspaceTest, StiffnessIsK0PlusGtK2G) {
  const HandPairParams p;
  const LinearMeshCore core = VaryingCore(p);
  const SystemModel model = HandPairBuilder(p, core).Build();
  SystemWorkspace ws(model);
  for (double theta : {0.1, 2.5, 5.0, -7.3}) {
    const MatrixX& K = AssembleStiffness(model, ws, theta);
    const Matrix2x12 G = HandPairJacobian(p);
    const MatrixX expected = model.DenseConstantStiffness() +
                             MatrixX(G.transpose() * EvalStiffnessCore(core, theta) * G);
    EXPECT_MATRIX_NEAR(K, expected, kTol);
    // Symmetric PSD.
    EXPECT_MATRIX_NEAR(K, K.transpose(), 0.0);
    Eigen::SelfAdjointEigenSolver<MatrixX> eig(K, Eigen::EigenvaluesOnly);
    EXPECT_GE(eig.eigenvalues().minCoeff(), -1e-12 * eig.eigenvalues().maxCoeff());
  }
}

// spec 01 §6: the LTV model with constant coefficients reproduces the LTI model exactly.
TEST(WorkspaceTest, LtvWithConstantCoefficientsEqualsLti) {
  const HandPairParams p;
  const Vector3 channels(p.k, 0.05 * p.k * p.b, 0.4 * p.k * p.b * p.b);
  MatrixX values(3, 2);
  values << channels, channels;
  const LinearMeshCore ltv(MeshCoreLevel::kBlankenshipSingh,
                           PiecewiseConstantCoefficient(Eigen::Vector2d(0.0, 1.0), values), p.b);
  const LinearMeshCore lti = MakeMeanLinearMeshCore(
      LinearMeshCore(MeshCoreLevel::kBlankenshipSingh, ConstantCoefficient(channels), p.b));
  const SystemModel a = HandPairBuilder(p, ltv).Build();
  const SystemModel b = HandPairBuilder(p, lti).Build();
  SystemWorkspace wa(a), wb(b);
  for (double theta : {0.0, 0.5, 1.5, 4.0}) {
    const MatrixX ka = AssembleStiffness(a, wa, theta);
    const MatrixX kb = AssembleStiffness(b, wb, theta);
    EXPECT_TRUE(ka == kb) << "θ = " << theta;
  }
  // The mean of a piecewise coefficient is a weighted sum of its values: equal to rounding.
  const MatrixX mean_a = AssembleMeanStiffness(a, wa);
  EXPECT_MATRIX_NEAR(mean_a, AssembleMeanStiffness(b, wb), 1e-15);
}

TEST(WorkspaceTest, MeanStiffnessIsThePeriodMean) {
  const HandPairParams p;
  const LinearMeshCore core = VaryingCore(p);
  const SystemModel model = HandPairBuilder(p, core).Build();
  SystemWorkspace ws(model);
  MatrixX mean = MatrixX::Zero(12, 12);
  // Piecewise constant on [0,2), [2,4), [4,2π): exact weighted average.
  const double T = 2.0 * M_PI;
  mean += 2.0 / T * AssembleStiffness(model, ws, 1.0);
  mean += 2.0 / T * AssembleStiffness(model, ws, 3.0);
  mean += (T - 4.0) / T * AssembleStiffness(model, ws, 5.0);
  EXPECT_MATRIX_NEAR(AssembleMeanStiffness(model, ws), mean, kTol);
}

TEST(WorkspaceTest, DampingAndLoadFollowTheCore) {
  const HandPairParams p;
  const double c_m = 1500.0;
  const LinearMeshCore core = VaryingCore(p, c_m);
  const SystemModel model = HandPairBuilder(p, core).Build();
  EXPECT_DOUBLE_EQ(model.meshes()[0].damping_coefficient, c_m);
  SystemWorkspace ws(model);
  const Matrix2x12 G = HandPairJacobian(p);
  const double theta = 2.2;
  const Matrix2 k2 = EvalStiffnessCore(core, theta);
  EXPECT_MATRIX_NEAR(AssembleDamping(model, ws, theta),
                     MatrixX(G.transpose() * (c_m / k2(0, 0) * k2) * G), kTol);
  EXPECT_MATRIX_NEAR(AssembleLoad(model, ws, theta),
                     VectorX(G.transpose() * (k2 * EvalTransmissionError(core, theta))), kTol);
}

TEST(WorkspaceTest, SparseKernelsEqualDenseKernels) {
  const HandPairParams p;
  const SystemModel model = HandPairBuilder(p, VaryingCore(p, 800.0)).Build();
  SystemWorkspace dense(model, StorageKind::kDense);
  SystemWorkspace sparse(model, StorageKind::kSparse);
  for (double theta : {0.3, 3.3}) {
    EXPECT_MATRIX_NEAR(MatrixX(AssembleStiffnessSparse(model, sparse, theta)),
                       AssembleStiffness(model, dense, theta), kTol);
    EXPECT_MATRIX_NEAR(MatrixX(AssembleDampingSparse(model, sparse, theta)),
                       AssembleDamping(model, dense, theta), kTol);
  }
  EXPECT_MATRIX_NEAR(MatrixX(AssembleMeanStiffnessSparse(model, sparse)),
                     AssembleMeanStiffness(model, dense), kTol);
  EXPECT_THROWS_MESSAGE(AssembleStiffness(model, sparse, 0.0), InvalidInput, "dense workspace");
  const SystemModel other = HandPairBuilder(p, SpurCore(p)).Build();
  EXPECT_THROWS_MESSAGE(AssembleStiffness(other, dense, 0.0), InvalidInput, "another model");
}

TEST(WorkspaceTest, SliceCoreAssemblesItsAllLoadedLimit) {
  const HandPairParams p;
  const int n = 4;
  VectorX sigma(n), ks(n);
  sigma << -0.75 * p.b, -0.25 * p.b, 0.25 * p.b, 0.75 * p.b;
  ks.setConstant(p.k / n);
  const SliceMeshCore slices(sigma, ConstantCoefficient(ks), p.b);
  const SystemModel model = HandPairBuilder(p, slices).Build();
  EXPECT_EQ(model.time_dependence(), TimeDependence::kNonlinear);
  SystemWorkspace ws(model);
  Matrix2 k2;
  k2 << ks.sum(), -ks.dot(sigma), -ks.dot(sigma), ks.dot(sigma.cwiseAbs2());
  const Matrix2x12 G = HandPairJacobian(p);
  EXPECT_MATRIX_NEAR(AssembleStiffness(model, ws, 0.7),
                     model.DenseConstantStiffness() + MatrixX(G.transpose() * k2 * G), kTol);
}

TEST(WorkspaceTest, KernelsDoNotAllocate) {
  if (!GEARDYN_HAVE_ALLOCATION_COUNTER) GTEST_SKIP() << "no allocation counter in this build";
  const HandPairParams p;
  const SystemModel model = HandPairBuilder(p, VaryingCore(p, 500.0)).Build();
  SystemWorkspace dense(model, StorageKind::kDense);
  SystemWorkspace sparse(model, StorageKind::kSparse);
  double sink = 0.0;
  const long count = test::CountAllocations([&] {
    for (double theta = 0.0; theta < 7.0; theta += 0.5) {
      sink += AssembleStiffness(model, dense, theta)(0, 0);
      sink += AssembleDamping(model, dense, theta)(0, 0);
      sink += AssembleLoad(model, dense, theta)(0);
      sink += AssembleStiffnessSparse(model, sparse, theta).coeff(0, 0);
      sink += AssembleDampingSparse(model, sparse, theta).coeff(0, 0);
    }
    sink += AssembleMeanStiffness(model, dense)(0, 0);
  });
  EXPECT_EQ(count, 0);
  EXPECT_TRUE(std::isfinite(sink));
}

}  // namespace
}  // namespace geardyn
