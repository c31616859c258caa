// MassSolver (analyses/src/time_domain/mass_solver.hpp): the block (Schur complement) solve of
// the arrow-shaped tooth-body mass against the residual M a − f (an invariant, no solver in the
// truth), the choice of path, and the dense fallback for a general internal mass.
#include "../../../analyses/src/time_domain/mass_solver.hpp"

#include <gtest/gtest.h>

#include <random>

#include "geardyn/models/contact/contact_mesh_core.hpp"
#include "support/contact_pairs.hpp"

namespace geardyn {
namespace {

// Two gear bodies of the Kim rig's order (m 2.6 kg, transverse inertia, J 0.0085 kg m²) plus the
// teeth's arrow blocks (tooth_body.hpp AssembleToothMass) on [q1; q2; teeth].
MatrixX RigMass(ToothBodyType type) {
  const auto setup = test::MakeContactPair(test::KimRigPair());
  ContactMeshDef def;
  def.teeth = type;
  def.bending_stiffness = 11.5e3;
  const ContactMeshCore core(setup.pair, setup.frame, def);
  MatrixX m = core.InternalMass();
  const double body[6] = {2.6, 2.6, 2.6, 0.005, 0.005, 0.0085};
  for (int i = 0; i < 12; ++i) m(i, i) += body[i % 6];
  return m;
}

double RelativeResidual(const MatrixX& m, const internal::MassSolver& s) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  VectorX f(m.rows());
  for (Eigen::Index i = 0; i < f.size(); ++i) f(i) = u(rng);
  VectorX a;
  s.Solve(f, &a);
  return (m * a - f).norm() / f.norm();
}

TEST(MassSolverTest, ToothBodyMassIsSolvedByBlocks) {
  // Blocks of M_ii (tooth_body.hpp M_k): type A one 1×1 (φ) per tooth; type B u_r alone (no
  // coupling in M_k) and (u_t, φ) together: two per tooth.
  for (const auto& [type, blocks] :
       {std::pair{ToothBodyType::kRevolute, 100}, std::pair{ToothBodyType::kBushing, 200}}) {
    const MatrixX m = RigMass(type);
    const internal::MassSolver s(m, 12);
    ASSERT_TRUE(s.ok());
    EXPECT_TRUE(s.is_block()) << ToString(type);
    EXPECT_EQ(s.num_blocks(), blocks) << ToString(type);
    EXPECT_LT(RelativeResidual(m, s), 1e-12) << ToString(type);
  }
}

TEST(MassSolverTest, GeneralInternalMassTakesTheDensePath) {
  // A full SPD internal block (one block of 30 > kMaxBlock) and none at all.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  MatrixX a(42, 42);
  for (Eigen::Index i = 0; i < a.size(); ++i) a.data()[i] = u(rng);
  const MatrixX m = a * a.transpose() + 42.0 * MatrixX::Identity(42, 42);
  const internal::MassSolver full(m, 12);
  ASSERT_TRUE(full.ok());
  EXPECT_FALSE(full.is_block());
  EXPECT_LT(RelativeResidual(m, full), 1e-12);
  const internal::MassSolver none(m, 42);
  ASSERT_TRUE(none.ok());
  EXPECT_FALSE(none.is_block());
  EXPECT_LT(RelativeResidual(m, none), 1e-12);
}

TEST(MassSolverTest, IndefiniteMassIsReported) {
  MatrixX m = RigMass(ToothBodyType::kRevolute);
  m(5, 5) = -1.0;  // a negative trunk inertia
  EXPECT_FALSE(internal::MassSolver(m, 12).ok());
  MatrixX d = MatrixX::Identity(3, 3);
  d(1, 1) = -1.0;
  EXPECT_FALSE(internal::MassSolver(d, 3).ok());
}

}  // namespace
}  // namespace geardyn
