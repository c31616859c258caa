// ContactMeshCore's optional sparse Jacobians (NonlinearMeshCoreOutput::want_triplets): the
// summed triplets against central differences of the force (the same truth as the dense
// Jacobians of contact_mesh_core_test.cpp), and the dense matrices left untouched.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "geardyn/models/contact/contact_mesh_core.hpp"
#include "support/contact_pairs.hpp"

namespace geardyn {
namespace {

using test::KimRigPair;
using test::MakeContactPair;

struct State {
  VectorX x, v;
  double theta = 0.0, theta_rate = 0.0;
};

// A loaded state: the pinion turned ahead by 3 µm along the line of action, small random body
// and tooth coordinates and velocities (as contact_mesh_core_test.cpp).
State LoadedState(const ContactMeshCore& core, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n = core.num_coordinates();
  State s;
  s.x = VectorX::Zero(n);
  s.v = VectorX::Zero(n);
  for (int i = 0; i < 12; ++i) {
    s.x(i) = (i % 6 < 3 ? 1e-7 : 1e-7 / 0.07) * u(rng);
    s.v(i) = (i % 6 < 3 ? 1e-3 : 1e-3 / 0.07) * u(rng);
  }
  s.x(5) += 3e-6 / core.kinematics().pinion().base_radius;
  for (int i = 12; i < n; ++i) {
    s.x(i) = 2e-6 * u(rng);
    s.v(i) = 1e-2 * u(rng);
  }
  s.theta = 0.3 + 0.5 * u(rng);
  s.theta_rate = 2.0 * std::acos(-1.0) * 2000.0;
  return s;
}

VectorX Force(const ContactMeshCore& core, NonlinearMeshCoreWorkspace& ws, const State& s) {
  NonlinearMeshCoreOutput out = core.MakeOutput();
  core.CalcForces(ws, s.theta, s.theta_rate, s.x, s.v, false, &out);
  return out.force;
}

MatrixX Summed(int n, const std::vector<Eigen::Triplet<double>>& t) {
  SparseMatrix s(n, n);
  s.setFromTriplets(t.begin(), t.end());
  return MatrixX(s);
}

TEST(ContactCoreTripletsTest, TripletJacobiansMatchFiniteDifferences) {
  const auto setup = MakeContactPair(KimRigPair());
  for (const ToothBodyType type :
       {ToothBodyType::kRigid, ToothBodyType::kRevolute, ToothBodyType::kBushing}) {
    ContactMeshDef def;
    def.teeth = type;
    def.bending_stiffness = 11.5e3;  // Kim Table 3 in SI
    def.bending_damping = 2e-4;
    def.friction_coefficient = 0.06;
    const ContactMeshCore core(setup.pair, setup.frame, def);
    auto ws = core.MakeWorkspace();
    const State s = LoadedState(core, 11);
    const int n = core.num_coordinates();
    NonlinearMeshCoreOutput out = core.MakeOutput();
    out.stiffness.setConstant(7.0);  // must stay untouched
    out.want_triplets = true;
    core.CalcForces(*ws, s.theta, s.theta_rate, s.x, s.v, true, &out);
    ASSERT_TRUE(out.has_triplets);
    ASSERT_GT(out.num_contacts, 0);
    EXPECT_EQ(out.stiffness(0, 0), 7.0);
    EXPECT_EQ(out.stiffness(n - 1, n - 1), 7.0);
    const MatrixX k = Summed(n, out.stiffness_triplets), c = Summed(n, out.damping_triplets);
    MatrixX fd_k(n, n), fd_c(n, n);
    for (int j = 0; j < n; ++j) {
      const double hx = j < 12 ? (j % 6 < 3 ? 1e-10 : 1e-9) : 1e-9, hv = 1e-4;
      State p = s, m = s;
      p.x(j) += hx;
      m.x(j) -= hx;
      fd_k.col(j) = -(Force(core, *ws, p) - Force(core, *ws, m)) / (2 * hx);
      p = s;
      m = s;
      p.v(j) += hv;
      m.v(j) -= hv;
      fd_c.col(j) = -(Force(core, *ws, p) - Force(core, *ws, m)) / (2 * hv);
    }
    // Omitted geometric terms of relative size f/(k L) (contact_mesh_core.hpp): 1e-3.
    EXPECT_LT((k - fd_k).cwiseAbs().maxCoeff(), 1e-3 * fd_k.cwiseAbs().maxCoeff())
        << ToString(type);
    EXPECT_LT((c - fd_c).cwiseAbs().maxCoeff(), 1e-3 * fd_c.cwiseAbs().maxCoeff())
        << ToString(type);
    // Without want_triplets the dense form is filled and the lists stay empty.
    NonlinearMeshCoreOutput dense = core.MakeOutput();
    core.CalcForces(*ws, s.theta, s.theta_rate, s.x, s.v, true, &dense);
    EXPECT_FALSE(dense.has_triplets);
    EXPECT_TRUE(dense.stiffness_triplets.empty());
  }
}

}  // namespace
}  // namespace geardyn
