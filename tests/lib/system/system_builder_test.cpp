#include "geardyn/system/system_builder.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "geardyn/system/workspace.hpp"
#include "hand_pair.hpp"
#include "support/expect_throws.hpp"
#include "support/matrix_compare.hpp"

namespace geardyn {
namespace {

using test::DiagMass;
using test::HandPairBuilder;
using test::HandPairJacobian;
using test::HandPairParams;
using test::SpurCore;

TEST(SystemBuilderTest, RejectsAsymmetricElementNamingIt) {
  SystemBuilder b;
  const BodyIndex a = b.AddBody("a", DiagMass(1, 1, 1));
  MatrixX k = MatrixX::Identity(6, 6);
  k(0, 1) = 0.5;
  EXPECT_THROWS_MESSAGE(b.AddElement("shaft-1", ElementKind::kShaft, {a}, k), InvalidInput,
                        "shaft 'shaft-1' stiffness: not symmetric");
}

TEST(SystemBuilderTest, RejectsIndefiniteAndNonFiniteElements) {
  SystemBuilder b;
  const BodyIndex a = b.AddBody("a", DiagMass(1, 1, 1));
  MatrixX k = MatrixX::Identity(6, 6);
  k(2, 2) = -1.0;
  EXPECT_THROWS_MESSAGE(b.AddElement("spring", ElementKind::kSpring, {a}, k), InvalidInput,
                        "spring 'spring' stiffness: not positive semi-definite");
  k(2, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROWS_MESSAGE(b.AddElement("spring", ElementKind::kSpring, {a}, k), InvalidInput,
                        "spring 'spring' stiffness: non-finite");
  MatrixX c = MatrixX::Identity(6, 6);
  c(1, 1) = std::numeric_limits<double>::infinity();
  EXPECT_THROWS_MESSAGE(
      b.AddElement("bearing", ElementKind::kBearing, {a}, MatrixX::Identity(6, 6), c), InvalidInput,
      "bearing 'bearing' damping: non-finite");
  Matrix6 m = DiagMass(1, 1, 1);
  m(0, 0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROWS_MESSAGE(b.AddBody("b", m), InvalidInput, "body 'b' mass: non-finite");
}

TEST(SystemBuilderTest, RejectsUnknownBodiesDuplicatesAndSizes) {
  SystemBuilder b;
  const BodyIndex a = b.AddBody("a", DiagMass(1, 1, 1));
  const BodyIndex c = b.AddBody("c", DiagMass(1, 1, 1));
  EXPECT_THROWS_MESSAGE(b.AddBody("a", DiagMass(1, 1, 1)), InvalidInput,
                        "body 'a': duplicate name");
  EXPECT_THROWS_MESSAGE(
      (b.AddElement("k", ElementKind::kCoupling, {a, BodyIndex(7)}, MatrixX::Identity(12, 12))),
      InvalidInput, "coupling 'k': unknown body index 7");
  EXPECT_THROWS_MESSAGE(
      (b.AddElement("k", ElementKind::kCoupling, {a, c}, MatrixX::Identity(6, 6))), InvalidInput,
      "coupling 'k' stiffness: size 6×6, expected 12×12");
  b.AddElement("k", ElementKind::kCoupling, {a, c}, MatrixX::Identity(12, 12));
  EXPECT_THROWS_MESSAGE((b.AddElement("k", ElementKind::kSpring, {a}, MatrixX::Identity(6, 6))),
                        InvalidInput, "spring 'k': duplicate element name");
  const HandPairParams p;
  b.AddMesh("m", a, c, HandPairJacobian(p), SpurCore(p));
  EXPECT_THROWS_MESSAGE(b.AddMesh("m", a, c, HandPairJacobian(p), SpurCore(p)), InvalidInput,
                        "mesh 'm': duplicate mesh name");
  EXPECT_THROWS_MESSAGE(b.AddMesh("n", a, BodyIndex(5), HandPairJacobian(p), SpurCore(p)),
                        InvalidInput, "mesh 'n': unknown body index 5");
  EXPECT_THROWS_MESSAGE(b.AddMesh("n", a, a, HandPairJacobian(p), SpurCore(p)), InvalidInput,
                        "mesh 'n': meshes body 'a' with itself");
  EXPECT_THROWS_MESSAGE(b.AddTorque(BodyIndex(9), Vector6::Zero(), "t"), InvalidInput,
                        "load 't': unknown body index 9");
}

TEST(SystemBuilderTest, RejectsUnreferencedMasslessDof) {
  SystemBuilder b;
  Matrix6 m = DiagMass(1, 1, 1);
  m(4, 4) = 0.0;  // θy without inertia, nothing acts on it
  b.AddBody("hub", m);
  EXPECT_THROWS_MESSAGE(b.Build(), InvalidInput,
                        "DOF hub.θy: zero mass and no element or mesh references it");
  Vector6 kd = Vector6::Ones();
  b.AddElement("support", ElementKind::kBearing, {BodyIndex(0)}, MatrixX(kd.asDiagonal()));
  EXPECT_THROWS_MESSAGE(b.Build(), InvalidInput, "DOF hub.θy: zero mass \\(referenced");
  SystemBuilder empty;
  EXPECT_THROWS_MESSAGE(empty.Build(), InvalidInput, "no bodies");
}

TEST(SystemBuilderTest, EquivalentMassAndDampingRatio) {
  const HandPairParams p;
  const double zeta = 0.07;
  const LinearMeshCore core(MeshCoreLevel::kBlankenshipSingh,
                            ConstantCoefficient(Vector3(p.k, 0.0, p.k * p.b * p.b / 3.0)), p.b,
                            std::nullopt, MeshDamping::FromRatio(zeta));
  const SystemModel model = HandPairBuilder(p, core).Build();
  // G row η = (y_i: 1, θz_i: r1, y_j: −1, θz_j: r2) with diagonal masses.
  const double m_e = 1.0 / (1.0 / p.m1 + p.r1 * p.r1 / p.I1 + 1.0 / p.m2 + p.r2 * p.r2 / p.I2);
  EXPECT_NEAR(model.meshes()[0].equivalent_mass, m_e, 1e-12 * m_e);
  EXPECT_NEAR(model.meshes()[0].damping_coefficient, 2.0 * zeta * std::sqrt(p.k * m_e),
              1e-9 * std::sqrt(p.k * m_e));
}

TEST(SystemBuilderTest, ModalDampingGivesTheRatioOnEveryMode) {
  const HandPairParams p;
  SystemBuilder b = HandPairBuilder(p, SpurCore(p));
  const double zeta = 0.03;
  b.SetModalDampingRatio(zeta);
  EXPECT_THROWS_MESSAGE(b.SetRayleighDamping(1.0, 0.0), InvalidInput, "modal damping");
  const SystemModel model = b.Build();
  SystemWorkspace ws(model);
  const MatrixX K = AssembleMeanStiffness(model, ws);
  const MatrixX M = model.DenseMass();
  Eigen::GeneralizedSelfAdjointEigenSolver<MatrixX> eig(K, M);
  const MatrixX phi = eig.eigenvectors();
  const MatrixX modal_c = phi.transpose() * model.DenseConstantDamping() * phi;
  for (int r = 0; r < model.num_dofs(); ++r) {
    const double omega = std::sqrt(std::max(eig.eigenvalues()(r), 0.0));
    EXPECT_NEAR(modal_c(r, r), 2.0 * zeta * omega, 1e-8 * (1.0 + omega)) << "mode " << r;
  }
}

TEST(SystemBuilderTest, RayleighDampingUsesMassAndMeanStiffness) {
  const HandPairParams p;
  SystemBuilder b = HandPairBuilder(p, SpurCore(p));
  b.SetRayleighDamping(2.0, 1e-6);
  const SystemModel model = b.Build();
  SystemWorkspace ws(model);
  const MatrixX expected = 2.0 * model.DenseMass() + 1e-6 * AssembleMeanStiffness(model, ws);
  EXPECT_MATRIX_NEAR(model.DenseConstantDamping(), expected, 1e-14);
  EXPECT_THROWS_MESSAGE(b.SetRayleighDamping(-1.0, 0.0), InvalidInput, "rayleigh alpha");
}

}  // namespace
}  // namespace geardyn
