/// @file
/// @brief The steady-state test modulo the cores' symmetry (NonlinearMeshCore::
/// symmetry_period_meshes / ApplySymmetryShift, time_response.hpp "Period") on a test double of
/// identical tooth bodies: a ring of z teeth (internal coordinates u_k, mass m_t, root spring k_b,
/// damper c_b) of which tooth k carries the mesh with the weight
/// w_k(θ) = [(1 + cos((θ − 2πk)/z))/2]^4 — period 2πz (the hunting period) while
/// w_{k+1}(θ + 2π) = w_k(θ): one mesh cycle later tooth k + 1 plays tooth k's role. Compression
/// c_k = δ − u_k − ε(θ), ε = e1 cos θ, force w_k (k_c c_k + c_c ċ_k): a linear periodic system
/// whose steady response satisfies x(t + T_m) = S x(t), (S y)_{k+1} = y_k.
/// Truths (none uses the engine's shift):
/// * the steady RMS/mean DTE over one mesh cycle (symmetry period) equals that over the full
///   z-cycle period found by the unshifted test (a different method);
/// * from the steady state A, the dynamics give S² A after two mesh cycles and A after 2z cycles
///   (S^z = I), S applied here by hand;
/// * two meshes with phase ratios 1 and 2: P_S = 1 and mesh 2 shifted twice per cycle (state
///   after two cycles: S₁² S₂⁴ A, z 3/5); an irrational ratio falls back to the full period lcm(z₁,
///   z₂).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <optional>
#include <vector>

#include "geardyn/analyses/time_response.hpp"
#include "lib/system/hand_pair.hpp"

namespace geardyn {
namespace {

constexpr double kPi = std::numbers::pi;

struct RingParams {
  int z = 3;            // teeth in the ring [-]
  double r1 = 0.04;     // pinion base radius [m]
  double r2 = 0.09;     // wheel base radius [m]
  double k_c = 1.2e9;   // contact stiffness [N/m]
  double c_c = 1500.0;  // contact damper [N·s/m]
  double k_b = 8e8;     // tooth root stiffness [N/m]
  double c_b = 300.0;   // tooth damper [N·s/m]
  double m_t = 0.2;     // tooth mass [kg]
  double e1 = 2e-7;     // ε amplitude [m]
};

class RingCore final : public NonlinearMeshCore {
 public:
  explicit RingCore(RingParams p) : p_(p) {}
  int num_coordinates() const override { return 12 + p_.z; }
  int num_internal_coordinates() const override { return p_.z; }
  std::int64_t period_meshes() const override { return p_.z; }
  std::int64_t symmetry_period_meshes() const override { return 1; }
  void ApplySymmetryShift(Eigen::Ref<VectorX> y) const override {
    const double last = y(p_.z - 1);
    for (int k = p_.z - 1; k > 0; --k) y(k) = y(k - 1);
    y(0) = last;
  }
  std::unique_ptr<NonlinearMeshCoreWorkspace> MakeWorkspace() const override {
    return std::make_unique<NonlinearMeshCoreWorkspace>();
  }
  MatrixX InternalMass() const override {
    MatrixX m = MatrixX::Zero(num_coordinates(), num_coordinates());
    for (int k = 0; k < p_.z; ++k) m(12 + k, 12 + k) = p_.m_t;
    return m;
  }

 protected:
  void DoCalcForces(NonlinearMeshCoreWorkspace&, double theta, double theta_rate,
                    const Eigen::Ref<const VectorX>& x, const Eigen::Ref<const VectorX>& v,
                    bool with_jacobians, NonlinearMeshCoreOutput* out) const override {
    Vector12 g = Vector12::Zero();  // δ = y_i − y_j + r1 θz_i + r2 θz_j (hand_pair.hpp)
    g(1) = 1.0;
    g(5) = p_.r1;
    g(7) = -1.0;
    g(11) = p_.r2;
    const double delta = g.dot(x.head(12)), ddelta = g.dot(v.head(12));
    const double eps = p_.e1 * std::cos(theta), deps = -p_.e1 * std::sin(theta);
    out->force.setZero();
    out->energy = 0.0;
    out->dissipation_power = 0.0;
    out->phase_power = 0.0;
    if (with_jacobians) {
      out->stiffness.setZero();
      out->damping.setZero();
    }
    const double zd = static_cast<double>(p_.z);
    for (int k = 0; k < p_.z; ++k) {
      const double a = (theta - 2.0 * kPi * k) / zd;
      const double h = 0.5 * (1.0 + std::cos(a)), dh = -0.5 * std::sin(a) / zd;
      const double w = std::pow(h, 4), dw = 4.0 * std::pow(h, 3) * dh;  // w, ∂w/∂θ
      const double u = x(12 + k), du = v(12 + k);
      const double c = delta - u - eps, dc = ddelta - du - deps * theta_rate;
      const double f = w * (p_.k_c * c + p_.c_c * dc);
      out->force.head(12) -= f * g;
      out->force(12 + k) = f - p_.k_b * u - p_.c_b * du;
      out->energy += 0.5 * p_.k_b * u * u + 0.5 * w * p_.k_c * c * c;
      out->dissipation_power += p_.c_b * du * du + w * p_.c_c * dc * dc;
      // ∂E/∂θ θ̇ at fixed x plus the work of ε on the contact: (½ w' k_c c² − f ε') θ̇.
      out->phase_power += (0.5 * dw * p_.k_c * c * c - f * deps) * theta_rate;
      if (with_jacobians) {
        VectorX gc = VectorX::Zero(num_coordinates());  // ∂c_k/∂x
        gc.head(12) = g;
        gc(12 + k) = -1.0;
        out->stiffness += w * p_.k_c * gc * gc.transpose();
        out->damping += w * p_.c_c * gc * gc.transpose();
        out->stiffness(12 + k, 12 + k) += p_.k_b;
        out->damping(12 + k, 12 + k) += p_.c_b;
      }
    }
    out->num_contacts = p_.z;
  }

 private:
  RingParams p_;
};

MeshCore Ring(const RingParams& p) {
  return std::shared_ptr<const NonlinearMeshCore>(std::make_shared<RingCore>(p));
}

/// The hand pair (rotations only) with one ring mesh, or a second ring mesh with phase ratio r.
SystemModel RingPair(const RingParams& p, const RingParams* second = nullptr, double ratio = 1.0) {
  test::HandPairParams hp;
  hp.r1 = p.r1;
  hp.r2 = p.r2;
  SystemBuilder builder = test::HandPairBuilder(hp, Ring(p));
  if (second != nullptr) {
    builder.AddMesh("mesh-2", BodyIndex(0), BodyIndex(1), test::HandPairJacobian(hp), Ring(*second),
                    std::nullopt, ratio);
  }
  const double torque = 100.0;
  Vector6 t = Vector6::Zero();
  t(5) = torque;
  builder.AddTorque(BodyIndex(0), t, "drive");
  t(5) = torque * hp.r2 / hp.r1;
  builder.AddTorque(BodyIndex(1), t, "brake");
  return builder.Build().Restrict({5, 11});
}

TimeResponseOptions Options(bool symmetry) {
  TimeResponseOptions o;
  o.integration.integrator = TimeIntegrator::kRungeKutta;
  o.integration.relative_tolerance = o.integration.absolute_tolerance = 1e-10;
  o.steady.tolerance = 1e-8;
  o.steady.use_symmetry = symmetry;
  return o;
}

/// Continues from a run's final state for exactly two periods (max_periods 1 + 1 recorded).
TimeResponse Continue(const SystemModel& model, double f, const TimeResponse& from, bool symmetry) {
  TimeResponseOptions o = Options(symmetry);
  o.start_from_static = false;
  o.initial_state = from.final_state;
  o.initial_phase = from.final_phase;
  o.steady.max_periods = 1;
  o.steady.min_periods = 0;
  return SimulateSteadyState(model, f, o);
}

/// (S^count y) on the internal block [first, first + z) of a state part, by hand.
VectorX ShiftByHand(const VectorX& y, int first, int z, int count) {
  VectorX s = y;
  for (int k = 0; k < z; ++k) s(first + (k + count) % z) = y(first + k);
  return s;
}

double RelativeDifference(const VectorX& a, const VectorX& b) {
  return (a - b).lpNorm<Eigen::Infinity>() / b.lpNorm<Eigen::Infinity>();
}

TEST(SymmetryTime, ShiftedSteadyStateEqualsTheFullPeriodOne) {
  const RingParams p;
  const SystemModel model = RingPair(p);
  ASSERT_EQ(model.period_meshes(), p.z);
  constexpr double kF = 2500.0;
  const TimeResponse sym = SimulateSteadyState(model, kF, Options(true));
  const TimeResponse full = SimulateSteadyState(model, kF, Options(false));
  ASSERT_TRUE(sym.summary.ok()) << sym.summary.BriefReport();
  ASSERT_TRUE(full.summary.ok()) << full.summary.BriefReport();
  EXPECT_EQ(sym.period_meshes, 1);
  EXPECT_EQ(full.period_meshes, p.z);
  EXPECT_EQ(sym.steady, SteadyVerdict::kSteady);
  EXPECT_EQ(full.steady, SteadyVerdict::kSteady);
  EXPECT_EQ(sym.summary.counters.count("symmetry_shift"), 1u);
  EXPECT_EQ(full.summary.counters.count("symmetry_shift"), 0u);
  const MeshTimeHistory &a = sym.meshes.at(0), &b = full.meshes.at(0);
  EXPECT_GT(a.rms_dte, 1e-3 * std::abs(a.mean_dte));  // a genuine vibration
  EXPECT_NEAR(a.rms_dte, b.rms_dte, 1e-6 * b.rms_dte);
  EXPECT_NEAR(a.mean_dte, b.mean_dte, 1e-7 * std::abs(b.mean_dte));
  EXPECT_NEAR(a.peak_to_peak_dte, b.peak_to_peak_dte, 1e-5 * b.peak_to_peak_dte);
  EXPECT_LT(sym.periods * sym.period_meshes, full.periods * full.period_meshes);
  EXPECT_LT(sym.max_energy_error, 1e-4);

  // The dynamics from the steady state A: S² A after two mesh cycles (the symmetric test's
  // continuation) and A after 2z cycles (the full period's, with no shift anywhere).
  const int n = static_cast<int>(sym.final_state.size()) / 2;
  const int first = n - p.z;  // the ring's coordinates come after the 2 DOFs
  const VectorX x_a = sym.final_state.head(n), v_a = sym.final_state.tail(n);
  const TimeResponse two = Continue(model, kF, sym, true);
  ASSERT_EQ(two.final_state.size(), 2 * n);
  EXPECT_LT(RelativeDifference(two.final_state.head(n), ShiftByHand(x_a, first, p.z, 2)), 1e-6);
  EXPECT_LT(RelativeDifference(two.final_state.tail(n), ShiftByHand(v_a, first, p.z, 2)), 1e-6);
  // The state really moved between: S² A ≠ A (the teeth carry different loads).
  EXPECT_GT(RelativeDifference(ShiftByHand(x_a, first, p.z, 2), x_a), 1e-3);
  const TimeResponse cycle = Continue(model, kF, sym, false);
  EXPECT_LT(RelativeDifference(cycle.final_state.head(n), x_a), 1e-6);
  EXPECT_LT(RelativeDifference(cycle.final_state.tail(n), v_a), 1e-6);
}

// The pre-run estimate counts the periods the steady test will use: with the symmetry one mesh
// cycle each, without it the hunting period z (min periods with the defaults: 2 + 3 − 1 + 1 = 5).
// A low-speed warning computed from the hunting period would be z times too pessimistic.
TEST(SymmetryTime, RunEstimateCountsTheSymmetryPeriod) {
  const RingParams p;
  const SystemModel model = RingPair(p);
  constexpr double kF = 2500.0;
  const TimeRunEstimate sym = EstimateTimeRun(model, kF, Options(true));
  const TimeRunEstimate full = EstimateTimeRun(model, kF, Options(false));
  ASSERT_TRUE(sym.summary.ok()) << sym.summary.message;
  ASSERT_TRUE(full.summary.ok()) << full.summary.message;
  ASSERT_EQ(sym.min_periods, full.min_periods);
  EXPECT_NEAR(sym.min_simulated_time_s, static_cast<double>(sym.min_periods) / kF, 1e-12);
  EXPECT_NEAR(full.min_simulated_time_s, static_cast<double>(full.min_periods * p.z) / kF, 1e-12);
}

TEST(SymmetryTime, SeveralMeshesCombineTheirShiftsWithThePhaseRatios) {
  RingParams p1, p2;
  p1.z = 3;
  p2.z = 5;
  p2.e1 = 1e-7;
  constexpr double kF = 1500.0;
  {
    // Ratio 2: mesh 2 advances two of its cycles per system cycle, P_S = 1.
    const SystemModel model = RingPair(p1, &p2, 2.0);
    const TimeResponse r = SimulateSteadyState(model, kF, Options(true));
    ASSERT_TRUE(r.summary.ok()) << r.summary.BriefReport();
    EXPECT_EQ(r.period_meshes, 1);
    const int n = static_cast<int>(r.final_state.size()) / 2;
    ASSERT_EQ(n, 2 + p1.z + p2.z);
    const TimeResponse two = Continue(model, kF, r, true);
    // Two cycles: mesh 1 shifted twice, mesh 2 four times (S₂⁴ ≠ I for z = 5).
    const auto expected = [&](const VectorX& y) {
      return ShiftByHand(ShiftByHand(y, 2, p1.z, 2), 2 + p1.z, p2.z, 4);
    };
    EXPECT_LT(RelativeDifference(two.final_state.head(n), expected(r.final_state.head(n))), 1e-6);
    EXPECT_LT(RelativeDifference(two.final_state.tail(n), expected(r.final_state.tail(n))), 1e-6);
  }
  {
    // An irrational ratio: no whole number of cycles of both meshes below lcm(3, 5) = 15 (nor at
    // it: the run keeps today's full period, unshifted).
    const SystemModel model = RingPair(p1, &p2, std::sqrt(2.0));
    TimeResponseOptions o = Options(true);
    o.steady.max_periods = 1;
    o.steady.min_periods = 0;
    const TimeResponse r = SimulateSteadyState(model, kF, o);
    EXPECT_EQ(r.period_meshes, 15);
    EXPECT_EQ(r.summary.counters.count("symmetry_shift"), 0u);
  }
}

}  // namespace
}  // namespace geardyn
