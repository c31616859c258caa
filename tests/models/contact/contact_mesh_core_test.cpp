// ContactMeshCore (contact_mesh_core.hpp): analytic Jacobians against finite differences, the
// power identity at random states (E by finite differences along the motion), the forces on the
// bodies against an independent sum over all tooth pairs with the kinematics' own contact chain,
// and the tangent mesh stiffness of rigid teeth with the linear law against the slice model of
// the same pair (the contact-line stiffness).
#include "geardyn/models/contact/contact_mesh_core.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <random>
#include <utility>
#include <vector>

#include "geardyn/common/errors.hpp"
#include "geardyn/models/contact/biarc_profile.hpp"
#include "geardyn/models/mesh/mesh_cores.hpp"
#include "geardyn/models/mesh/mesh_jacobian.hpp"
#include "support/contact_pairs.hpp"
#include "support/expect_throws.hpp"

namespace geardyn {
namespace {

using test::KimRigPair;
using test::MakeContactPair;

ContactMeshDef RevoluteDef() {
  ContactMeshDef def;
  def.teeth = ToothBodyType::kRevolute;
  def.bending_stiffness = 11.5e3;  // Kim Table 3 in SI
  def.bending_damping = 2e-4;
  def.friction_coefficient = 0.06;
  return def;
}

// A loaded state: the pinion turned ahead by `approach` along the line of action (drive flanks
// in contact), small random body and tooth coordinates, random velocities.
struct State {
  VectorX x, v;
  double theta = 0.0, theta_rate = 0.0;
};
State LoadedState(const ContactMeshCore& core, unsigned seed, double approach) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n = core.num_coordinates();
  State s;
  s.x = VectorX::Zero(n);
  s.v = VectorX::Zero(n);
  const double rb1 = core.kinematics().pinion().base_radius;
  for (int i = 0; i < 12; ++i) {
    s.x(i) = (i % 6 < 3 ? 1e-7 : 1e-7 / 0.07) * u(rng);  // 0.1 µm, the rotations alike
    s.v(i) = (i % 6 < 3 ? 1e-3 : 1e-3 / 0.07) * u(rng);
  }
  s.x(5) += approach / rb1;
  for (int i = 12; i < n; ++i) {
    s.x(i) = 2e-6 * u(rng);  // tooth rotations of µrad
    s.v(i) = 1e-2 * u(rng);
  }
  s.theta = 0.3 + 0.5 * u(rng);
  s.theta_rate = 2.0 * std::acos(-1.0) * 2000.0;  // 2 kHz mesh frequency
  return s;
}

NonlinearMeshCoreOutput Eval(const ContactMeshCore& core, NonlinearMeshCoreWorkspace& ws,
                             const State& s, bool jac) {
  NonlinearMeshCoreOutput out = core.MakeOutput();
  core.CalcForces(ws, s.theta, s.theta_rate, s.x, s.v, jac, &out);
  return out;
}

TEST(ContactMeshCoreTest, DofCountsAndMassAreKims) {
  const auto setup = MakeContactPair(KimRigPair());
  ContactMeshDef a = RevoluteDef();
  const ContactMeshCore core_a(setup.pair, setup.frame, a);
  EXPECT_EQ(core_a.num_coordinates(), 112);  // 12 + 100 (Kim: 2 + 100 on the torsional rig)
  a.teeth = ToothBodyType::kBushing;
  const ContactMeshCore core_b(setup.pair, setup.frame, a);
  EXPECT_EQ(core_b.num_coordinates(), 312);
  EXPECT_EQ(core_b.InternalMass().rows(), 312);
  EXPECT_EQ(core_b.channel_names().size(), 100u + 50u + 300u);
}

// −∂force/∂x and −∂force/∂v by central differences; the omitted geometric terms are of relative
// size f/(k L) (contact_mesh_core.hpp), so columns agree to 1e-3 of the largest entry.
TEST(ContactMeshCoreTest, JacobiansMatchFiniteDifferences) {
  const auto setup = MakeContactPair(KimRigPair());
  for (const ToothBodyType type :
       {ToothBodyType::kRigid, ToothBodyType::kRevolute, ToothBodyType::kBushing}) {
    for (const ContactProfile profile : {ContactProfile::kInvolute, ContactProfile::kBiarc}) {
      ContactMeshDef def = RevoluteDef();
      def.teeth = type;
      def.profile = profile;
      def.arcs = 3;
      const ContactMeshCore core(setup.pair, setup.frame, def);
      auto ws = core.MakeWorkspace();
      const State s = LoadedState(core, 7, 3e-6);
      const NonlinearMeshCoreOutput out = Eval(core, *ws, s, true);
      ASSERT_GT(out.num_contacts, 0) << ToString(type);
      const int n = core.num_coordinates();
      MatrixX fd_k(n, n), fd_c(n, n);
      for (int j = 0; j < n; ++j) {
        const double hx = j < 12 ? (j % 6 < 3 ? 1e-10 : 1e-9) : 1e-9;
        State p = s, m = s;
        p.x(j) += hx;
        m.x(j) -= hx;
        fd_k.col(j) =
            -(Eval(core, *ws, p, false).force - Eval(core, *ws, m, false).force) / (2 * hx);
        const double hv = 1e-4;
        p = s;
        m = s;
        p.v(j) += hv;
        m.v(j) -= hv;
        fd_c.col(j) =
            -(Eval(core, *ws, p, false).force - Eval(core, *ws, m, false).force) / (2 * hv);
      }
      const double scale_k = fd_k.cwiseAbs().maxCoeff();
      const double scale_c = fd_c.cwiseAbs().maxCoeff();
      EXPECT_LT((out.stiffness - fd_k).cwiseAbs().maxCoeff(), 1e-3 * scale_k) << ToString(type);
      EXPECT_LT((out.damping - fd_c).cwiseAbs().maxCoeff(), 1e-3 * scale_c) << ToString(type);
    }
  }
}

// force·v = −dE/dt + P − D with dE/dt = (E(x + h v, θ + h θ̇) − E(x − h v, θ − h θ̇))/(2h).
TEST(ContactMeshCoreTest, PowerIdentityHoldsAtRandomStates) {
  const auto setup = MakeContactPair(KimRigPair());
  for (const ToothBodyType type :
       {ToothBodyType::kRigid, ToothBodyType::kRevolute, ToothBodyType::kBushing}) {
    for (const ContactProfile profile : {ContactProfile::kInvolute, ContactProfile::kBiarc}) {
      ContactMeshDef def = RevoluteDef();
      def.teeth = type;
      def.profile = profile;
      def.arcs = 3;
      const ContactMeshCore core(setup.pair, setup.frame, def);
      auto ws = core.MakeWorkspace();
      for (unsigned seed = 1; seed <= 5; ++seed) {
        const State s = LoadedState(core, seed, 2e-6);
        const NonlinearMeshCoreOutput out = Eval(core, *ws, s, false);
        ASSERT_GT(out.num_contacts, 0);
        const double h = 1e-9;  // s: the state moves by ≈ 1e-12 m, below the kinks' spacing
        State p = s, m = s;
        p.x += h * s.v;
        m.x -= h * s.v;
        p.theta += h * s.theta_rate;
        m.theta -= h * s.theta_rate;
        const double de =
            (Eval(core, *ws, p, false).energy - Eval(core, *ws, m, false).energy) / (2 * h);
        const double lhs = out.force.dot(s.v);
        const double rhs = -de + out.phase_power - out.dissipation_power;
        const double scale = std::abs(lhs) + std::abs(out.phase_power) + out.dissipation_power;
        EXPECT_NEAR(lhs, rhs, 1e-5 * scale) << ToString(type) << " seed " << seed;
        EXPECT_GE(out.dissipation_power, 0.0);
      }
    }
  }
}

// Rigid teeth, the linear law without damping: the forces on the 12 body coordinates are
// −Σ k δ⁺ ∂δ/∂q over ALL tooth pairs, slices and flanks evaluated by the kinematics' own chain
// (EvalToothPair): no pre-search, a different code path.
TEST(ContactMeshCoreTest, BodyForcesEqualTheSumOverAllToothPairs) {
  for (const GearPairSpec& spec : {KimRigPair(150.05), test::UnequalSpurPair()}) {  // backlash
    for (const int slices : {1, 3}) {
      const auto setup = MakeContactPair(spec, 1, 0.3);
      ContactMeshDef def;
      def.law = LinearContactLaw(4e8, 0.0);
      def.face_slices = slices;
      const ContactMeshCore core(setup.pair, setup.frame, def);
      auto ws = core.MakeWorkspace();
      const int z1 = setup.pair.pinion.teeth, z2 = setup.pair.gear.teeth;
      // Drive contact; coast contact after the backlash j_bn is closed.
      for (const double approach : {3e-6, -(setup.pair.backlash_normal + 3e-6)}) {
        for (const unsigned seed : {3u, 4u}) {
          State s = LoadedState(core, seed, approach);
          s.v.setZero();
          const NonlinearMeshCoreOutput out = Eval(core, *ws, s, false);
          ASSERT_GT(out.num_contacts, 0) << approach;
          Vector12 ref = Vector12::Zero();
          const Vector12 q = s.x.head<12>();
          const ContactMeshKinematics& kin = core.kinematics();
          for (int slice = 0; slice < slices; ++slice) {
            for (int i1 = 0; i1 < z1; ++i1) {
              for (int i2 = 0; i2 < z2; ++i2) {
                for (const FlankSide side : {FlankSide::kDrive, FlankSide::kCoast}) {
                  const SliceToothContact c = kin.EvalToothPair(q, s.theta, slice, i1, i2, side);
                  if (!c.transverse.found || !c.transverse.valid || c.penetration <= 0.0) {
                    continue;
                  }
                  ref -= (4e8 / slices) * c.penetration * c.d_penetration;
                }
              }
            }
          }
          EXPECT_LT((out.force.head<12>() - ref).norm(), 1e-9 * ref.norm())
              << z1 << "/" << z2 << " approach " << approach << " seed " << seed;
        }
      }
    }
  }
}

// Rigid teeth with the linear law k δ at a state where every tooth pair of the zone is loaded:
// the tangent stiffness along the pinion rotation, K(5,5)/G(0,5)², is Σ k over the loaded
// contacts, and equals the contact-line model's K(θ) = k_l L(θ) with k_l = k/B (the slice core's
// Σ k_s, built from the contact lines of the same pair). The phases keep ≥ 0.2 rad from the
// 1↔2-pair changes (ε_α = 1.755: |θ| = 0.77): within ≈ 0.1 rad of them the loaded contact model
// already touches with the entering tooth's tip corner (premature contact under the 1 µm approach,
// which the contact-line model does not have: at 0.7 rad it finds two pairs, the lines one).
TEST(ContactMeshCoreTest, RigidLinearStiffnessEqualsTheContactLineModel) {
  const auto setup = MakeContactPair(KimRigPair());
  const double k = 4e8, b = setup.pair.face_width;
  ContactMeshDef def;
  def.law = LinearContactLaw(k, 0.0);
  const ContactMeshCore core(setup.pair, setup.frame, def);
  auto ws = core.MakeWorkspace();
  const SliceMeshCore slices =
      MakeSliceMeshCore(MakeMeshCoreSource(setup.pair, StiffnessPerUnitLength{k / b}, 1), 4);
  SliceMeshWorkspace sws(slices);
  const Matrix2x12 g = CalcMeshJacobian(setup.frame);
  for (const double theta : {-2.5, -1.0, 0.0, 0.5, 2.0}) {
    State s;
    s.x = VectorX::Zero(core.num_coordinates());
    s.v = VectorX::Zero(core.num_coordinates());
    s.x(5) = 1e-6 / core.kinematics().pinion().base_radius;  // 1 µm along the line of action
    s.theta = theta;
    const NonlinearMeshCoreOutput out = Eval(core, *ws, s, true);
    const double k_eta = out.stiffness(5, 5) / (g(0, 5) * g(0, 5));
    const double k_lines = EvalSliceChannels(slices, sws, theta)(0);
    EXPECT_NEAR(k_eta, k_lines, 1e-6 * k_lines) << "theta " << theta;
  }
}

// Static load sharing of rigid unmodified involutes (law of gearing: a rigid rotation of the
// pinion by δ/r_b1 gives every pair on the line of action the same penetration δ): in the
// two-pair zone two pinion teeth carry k δ each, in the one-pair zone one tooth carries it, and
// the moment on the pinion is −Σ f r_b1.
TEST(ContactMeshCoreTest, RigidTeethShareTheStaticLoadEqually) {
  const auto setup = MakeContactPair(KimRigPair());
  const double k = 4e8, delta = 1e-6;
  ContactMeshDef def;
  def.law = LinearContactLaw(k, 0.0);
  const ContactMeshCore core(setup.pair, setup.frame, def);
  auto ws = core.MakeWorkspace();
  const double rb1 = core.kinematics().pinion().base_radius;
  for (const auto& [theta, pairs] : {std::pair{0.0, 1}, std::pair{2.0, 2}, std::pair{-2.2, 2}}) {
    State s;
    s.x = VectorX::Zero(core.num_coordinates());
    s.v = VectorX::Zero(core.num_coordinates());
    s.x(5) = delta / rb1;
    s.theta = theta;
    const NonlinearMeshCoreOutput out = Eval(core, *ws, s, false);
    int loaded = 0;
    for (int t = 0; t < 50; ++t) {
      const double f = out.channels(t);  // pinion tooth t [N]
      if (f == 0.0) continue;
      ++loaded;
      EXPECT_NEAR(f, k * delta, 1e-9 * k * delta) << "theta " << theta << " tooth " << t;
      EXPECT_EQ(out.channels(100 + t), 1.0);  // status: drive flank
      // Switching function of (slice 0, drive, tooth t): the signed gap −δ.
      EXPECT_NEAR(out.switching(t), -delta, 1e-12) << "theta " << theta << " tooth " << t;
    }
    EXPECT_EQ(loaded, pairs) << "theta " << theta;
    EXPECT_NEAR(out.force(5), -pairs * k * delta * rb1, 1e-9 * k * delta * rb1);
  }
}

// Biarc flanks converge to the exact involute: the body forces of rigid teeth under the linear law
// over a mesh cycle (one- and two-pair zones, 1 µm approach) differ from the exact core's by at
// most k·(deviation of both flanks) per loaded pair, and the difference falls at the order of
// the profile deviation (≈ 3, biarc_profile.hpp) as N doubles.
TEST(ContactMeshCoreTest, BiarcForcesConvergeToTheExactInvoluteAtTheDeviationsOrder) {
  const auto setup = MakeContactPair(KimRigPair());
  const double k = 4e8;
  ContactMeshDef def;
  def.law = LinearContactLaw(k, 0.0);
  const ContactMeshCore exact(setup.pair, setup.frame, def);
  auto ws = exact.MakeWorkspace();
  const double rb1 = exact.kinematics().pinion().base_radius;
  std::vector<double> errors, devs;
  for (const int n : {4, 8, 16, 32}) {
    def.profile = ContactProfile::kBiarc;
    def.arcs = n;
    const ContactMeshCore biarc(setup.pair, setup.frame, def);
    const double dev = BiarcFlank(exact.kinematics().pinion(), -1, n).max_deviation() +
                       BiarcFlank(exact.kinematics().gear(), -1, n).max_deviation();
    double err = 0.0;
    for (int i = 0; i < 400; ++i) {
      State s;
      s.x = VectorX::Zero(exact.num_coordinates());
      s.v = VectorX::Zero(exact.num_coordinates());
      s.x(5) = 1e-6 / rb1;
      s.theta = -std::acos(-1.0) + 2.0 * std::acos(-1.0) * (i + 0.5) / 400.0;
      const NonlinearMeshCoreOutput fe = Eval(exact, *ws, s, false);
      const NonlinearMeshCoreOutput fb = Eval(biarc, *ws, s, false);
      // Near a pair change a contact can be closed in one profile and open by < dev in the other.
      const int pairs = std::max(fe.num_contacts, fb.num_contacts);
      // Moment about the pinion axis: Σ f r_b1 (lever errors are O(h²) relative, far smaller).
      const double diff = std::abs(fb.force(5) - fe.force(5)) / rb1;
      EXPECT_LE(diff, pairs * k * dev * 1.05) << "N " << n << " theta " << s.theta;
      err += diff * diff / 400.0;
    }
    errors.push_back(std::sqrt(err));
    devs.push_back(dev);
  }
  RecordProperty("force_errors_N", ::testing::PrintToString(errors));
  // Each halving gains at least second order; over N = 4 → 32 the force error falls at the order
  // the deviation itself falls (the RMS over the cycle mixes the smooth O(h³) part with the pair
  // changes, where a contact is closed in one profile only, so single steps scatter: 2.6–4.2).
  for (size_t i = 1; i < errors.size(); ++i) {
    EXPECT_GT(std::log2(errors[i - 1] / errors[i]), 2.0) << "N " << (4 << i);
  }
  const double order = std::log2(errors.front() / errors.back()) / 3.0;
  const double order_dev = std::log2(devs.front() / devs.back()) / 3.0;
  EXPECT_NEAR(order, order_dev, 0.35) << "force " << order << " deviation " << order_dev;
}

// Quasi-static transmission error of rigid teeth under Kim's law at the rig's 100 N·m: the pinion
// rotation that carries the torque, found by Newton on the moment for each profile. A rigid
// rotation changes every pair's δ by the same amount (law of gearing), and the biarc δ lies within
// dev = dev₁ + dev₂ of the exact δ, so the static TE of the two differs by at most dev; the
// mesh stiffness dF/dTE by at most (m1 − 1)·dev/δ relative (Kim's f = k δ^m1).
TEST(ContactMeshCoreTest, BiarcStaticTransmissionErrorWithinTheDeviation) {
  const auto setup = MakeContactPair(KimRigPair());
  ContactMeshDef def;  // Kim's law, rigid teeth
  const ContactMeshCore exact(setup.pair, setup.frame, def);
  auto ws = exact.MakeWorkspace();
  const double rb1 = exact.kinematics().pinion().base_radius, torque = 100.0;
  // Static TE [m] along the line of action and the tangent stiffness [N/m] at phase θ.
  auto solve = [&](const ContactMeshCore& core, double theta) {
    State s;
    s.x = VectorX::Zero(core.num_coordinates());
    s.v = VectorX::Zero(core.num_coordinates());
    s.theta = theta;
    s.x(5) = 1e-6 / rb1;
    double kt = 0.0, residual = torque;
    for (int it = 0; it < 50 && std::abs(residual) > 1e-10 * torque; ++it) {
      const NonlinearMeshCoreOutput out = Eval(core, *ws, s, true);
      residual = -out.force(5) - torque;  // moment of the contacts = load
      kt = out.stiffness(5, 5);
      s.x(5) -= residual / kt;
    }
    EXPECT_LT(std::abs(residual), 1e-10 * torque) << "Newton on the moment, theta " << theta;
    return std::pair{s.x(5) * rb1, kt / (rb1 * rb1)};
  };
  for (const int n : {2, 4, 8}) {
    def.profile = ContactProfile::kBiarc;
    def.arcs = n;
    const ContactMeshCore biarc(setup.pair, setup.frame, def);
    const double dev = BiarcFlank(exact.kinematics().pinion(), -1, n).max_deviation() +
                       BiarcFlank(exact.kinematics().gear(), -1, n).max_deviation();
    for (const double theta : {-2.5, -1.0, 0.0, 0.5, 2.0}) {
      const auto [te_e, k_e] = solve(exact, theta);
      const auto [te_b, k_b] = solve(biarc, theta);
      EXPECT_LE(std::abs(te_b - te_e), 1.02 * dev) << "N " << n << " theta " << theta;
      EXPECT_LE(std::abs(k_b - k_e),
                (def.law.stiffness_exponent - 1.0) * dev / (te_e * 0.5) * k_e + 1e-6 * k_e)
          << "N " << n << " theta " << theta;
    }
  }
}

// A non-finite coordinate has no contact answer. The kernels alone would call it "no contact"
// (a zero force, indistinguishable from an open mesh); the core passes the NaN on instead, so the
// caller's finiteness checks see it. Truth: the loaded state has contacts and a non-zero force.
TEST(ContactMeshCoreTest, NonFiniteStateGivesNaNNotAnOpenMesh) {
  const auto setup = MakeContactPair(KimRigPair());
  const ContactMeshCore core(setup.pair, setup.frame, RevoluteDef());
  auto ws = core.MakeWorkspace();
  State s = LoadedState(core, 3, 3e-6);
  const NonlinearMeshCoreOutput loaded = Eval(core, *ws, s, false);
  ASSERT_GT(loaded.num_contacts, 0);
  ASSERT_GT(loaded.force.norm(), 0.0);
  for (const int i : {5, 20}) {  // a body rotation, a tooth coordinate
    State bad = s;
    bad.x(i) = std::numeric_limits<double>::quiet_NaN();
    const NonlinearMeshCoreOutput out = Eval(core, *ws, bad, true);
    EXPECT_TRUE(out.force.array().isNaN().all()) << i;
    EXPECT_TRUE(std::isnan(out.energy)) << i;
    EXPECT_TRUE(out.switching.array().isNaN().all()) << i;
  }
  State bad_v = s;
  bad_v.v(0) = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(Eval(core, *ws, bad_v, false).force.array().isNaN().all());
}

TEST(ContactMeshCoreTest, UnsupportedOptionsAreRefused) {
  const auto helical = MakeContactPair(test::HelicalPair());
  EXPECT_THROWS_MESSAGE(ContactMeshCore(helical.pair, helical.frame, RevoluteDef()), InvalidInput,
                        "def.teeth");
  const auto spur = MakeContactPair(KimRigPair());
  ContactMeshDef def;
  def.profile = ContactProfile::kBiarc;
  EXPECT_THROWS_MESSAGE(ContactMeshCore(helical.pair, helical.frame, def), InvalidInput,
                        "def.profile: \"biarc\" flanks need a spur pair");
  def.arcs = 0;
  EXPECT_THROWS_MESSAGE(ContactMeshCore(spur.pair, spur.frame, def), InvalidInput,
                        "def.arcs: 0 must lie in");
}

// Tooth-shift symmetry (symmetry_period_meshes, ApplySymmetryShift): the teeth of a member are
// identical, and in mesh cycle n pinion tooth n mod z1 meets gear tooth n mod z2 (mesh_kinematics
// numbering), so one mesh cycle later tooth k + 1 stands where tooth k stood. Truth: the
// equivariance f(S x, S v, θ + 2π) = S f(x, v, θ) (body forces, energy, powers unchanged), with S
// built here by hand ((S y)_{k+1} = y_k per member), at loaded random states of the Kim pair and
// of an unequal pair (z 23/41: two different cycles).
TEST(ContactMeshCoreTest, ToothShiftOfOneMeshCycleIsASymmetry) {
  for (const GearPairSpec& spec : {KimRigPair(), test::UnequalSpurPair()}) {
    const auto setup = MakeContactPair(spec);
    for (const ToothBodyType type : {ToothBodyType::kRevolute, ToothBodyType::kBushing}) {
      ContactMeshDef def = RevoluteDef();
      def.teeth = type;
      const ContactMeshCore core(setup.pair, setup.frame, def);
      EXPECT_EQ(core.symmetry_period_meshes(), 1);
      EXPECT_EQ(core.period_meshes(), std::lcm<std::int64_t>(spec.pinion.teeth, spec.gear.teeth));
      const int d = ToothDofs(type);
      const int z[2] = {spec.pinion.teeth, spec.gear.teeth};
      const auto by_hand = [&](const VectorX& y) {
        VectorX s = y;
        int first = 12;
        for (int m = 0; m < 2; ++m) {
          for (int k = 0; k < z[m]; ++k) {
            s.segment(first + ((k + 1) % z[m]) * d, d) = y.segment(first + k * d, d);
          }
          first += z[m] * d;
        }
        return s;
      };
      auto ws = core.MakeWorkspace();
      for (unsigned seed = 1; seed <= 3; ++seed) {
        const State s = LoadedState(core, seed, 2e-6);
        State t = s;
        t.x = by_hand(s.x);
        t.v = by_hand(s.v);
        VectorX lib_x = s.x;  // the core's own shift agrees with the hand-made S
        auto internal = lib_x.tail(core.num_internal_coordinates());
        core.ApplySymmetryShift(internal);
        EXPECT_EQ(lib_x, t.x);
        t.theta = s.theta + 2.0 * std::acos(-1.0);
        const NonlinearMeshCoreOutput a = Eval(core, *ws, s, true);
        const NonlinearMeshCoreOutput b = Eval(core, *ws, t, true);
        ASSERT_GT(a.num_contacts, 0);
        EXPECT_EQ(a.num_contacts, b.num_contacts);
        const double f = a.force.lpNorm<Eigen::Infinity>();
        EXPECT_LT((b.force - by_hand(a.force)).lpNorm<Eigen::Infinity>(), 1e-9 * f)
            << ToString(type) << " z " << z[0] << "/" << z[1] << " seed " << seed;
        EXPECT_NEAR(b.energy, a.energy, 1e-9 * std::abs(a.energy));
        EXPECT_NEAR(b.dissipation_power, a.dissipation_power, 1e-9 * a.dissipation_power);
        EXPECT_NEAR(b.phase_power, a.phase_power, 1e-9 * std::abs(a.phase_power) + 1e-12);
        // The tangent too: K(S x) = S K(x) Sᵀ, i.e. row/column permuted.
        MatrixX k = a.stiffness;
        for (Eigen::Index c = 0; c < k.cols(); ++c) k.col(c) = by_hand(k.col(c));
        for (Eigen::Index r = 0; r < k.rows(); ++r)
          k.row(r) = by_hand(k.row(r).transpose()).transpose();
        EXPECT_LT((b.stiffness - k).lpNorm<Eigen::Infinity>(),
                  1e-9 * a.stiffness.lpNorm<Eigen::Infinity>());
      }
    }
  }
}

}  // namespace
}  // namespace geardyn
