/// @file
/// @brief Time integration of a NonlinearMeshCore with an internal coordinate (a test double of
/// the spec-03 tooth bodies) against its closed form: the torsional pair (relative coordinate
/// δ = r1 θ1 + r2 θ2, m_e) whose mesh is a compliant tooth — an internal coordinate u (tooth
/// deflection, mass m_t, root spring k_b, damper c_b) in series with a unilateral contact spring
/// k_c and damper c_c on the compression c = δ − u − ε(θ), ε = e1 cos θ. Loaded so that the
/// contact never opens, the equations are linear (f_c = k_c c + c_c ċ):
/// \f[ m_e \ddot δ + f_c = T/r_1, \qquad m_t \ddot u + c_b \dot u + k_b u − f_c = 0, \f]
/// a 2-DOF forced response in closed form. Also checks the power identity bookkeeping (E, D, P
/// of the core) through the energy balance, the InternalMass and the switching function.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <complex>
#include <memory>
#include <numbers>
#include <utility>
#include <vector>

#include "geardyn/analyses/time_response.hpp"
#include "lib/system/hand_pair.hpp"

namespace geardyn {
namespace {

constexpr double kPi = std::numbers::pi;

struct ToothParams {
  double r1 = 0.04, r2 = 0.09;  // base radii of the hand pair [m]
  double k_c = 1.2e9;           // contact stiffness [N/m]
  double k_b = 8e8;             // tooth root stiffness [N/m]
  double c_b = 300.0;           // tooth damper [N·s/m]
  double c_c = 1500.0;          // contact damper [N·s/m] (ζ ≈ 0.05 of the mesh mode)
  double m_t = 0.2;             // tooth mass [kg] (tooth mode ≈ 16 kHz)
  double e1 = 2e-7;             // ε amplitude [m]
};

class ToothCore final : public NonlinearMeshCore {
 public:
  explicit ToothCore(ToothParams p) : p_(p) {}
  int num_coordinates() const override { return 13; }
  int num_internal_coordinates() const override { return 1; }
  std::unique_ptr<NonlinearMeshCoreWorkspace> MakeWorkspace() const override {
    return std::make_unique<NonlinearMeshCoreWorkspace>();
  }
  MatrixX InternalMass() const override {
    MatrixX m = MatrixX::Zero(13, 13);
    m(12, 12) = p_.m_t;
    return m;
  }
  int num_switching_functions() const override { return 1; }
  std::vector<std::string> channel_names() const override { return {"contact_force [N]"}; }

 protected:
  void DoCalcForces(NonlinearMeshCoreWorkspace&, double theta, double theta_rate,
                    const Eigen::Ref<const VectorX>& x, const Eigen::Ref<const VectorX>& v,
                    bool with_jacobians, NonlinearMeshCoreOutput* out) const override {
    // δ = y_i − y_j + r1 θz_i + r2 θz_j (hand_pair.hpp's G, row η).
    Vector12 g = Vector12::Zero();
    g(1) = 1.0;
    g(5) = p_.r1;
    g(7) = -1.0;
    g(11) = p_.r2;
    const double delta = g.dot(x.head(12));
    const double u = x(12), du = v(12);
    const double eps = p_.e1 * std::cos(theta), deps = -p_.e1 * std::sin(theta);
    const double c = delta - u - eps;
    const double dc_dt = g.dot(v.head(12)) - du - deps * theta_rate;
    // Unilateral contact, spring and damper in parallel while closed.
    const double fc = c > 0.0 ? p_.k_c * c + p_.c_c * dc_dt : 0.0;
    out->force.setZero();
    out->force.head(12) = -fc * g;
    out->force(12) = fc - p_.k_b * u - p_.c_b * du;
    out->energy = 0.5 * p_.k_b * u * u + (c > 0.0 ? 0.5 * p_.k_c * c * c : 0.0);
    out->dissipation_power = p_.c_b * du * du + (c > 0.0 ? p_.c_c * dc_dt * dc_dt : 0.0);
    // The work of the prescribed motion on the contact (spring and damper): f_c (−ε') θ̇.
    out->phase_power = fc * (-deps) * theta_rate;
    out->num_contacts = c > 0.0 ? 1 : 0;
    out->switching(0) = c;
    out->channels(0) = fc;
    if (with_jacobians) {
      out->stiffness.setZero();
      out->damping.setZero();
      VectorX dc = VectorX::Zero(13);  // ∂c/∂x
      dc.head(12) = g;
      dc(12) = -1.0;
      if (c > 0.0) {
        // force = −k_c c ∂c/∂x on every coordinate (the u row: −k_c c·(−1) = +k_c c).
        out->stiffness += p_.k_c * dc * dc.transpose();
        out->damping += p_.c_c * dc * dc.transpose();
      }
      out->stiffness(12, 12) += p_.k_b;
      out->damping(12, 12) = p_.c_b;
    }
  }

 private:
  ToothParams p_;
};

/// The hand pair restricted to the rotations (θz_i, θz_j) with the tooth core; torque T on the
/// pinion and T r2/r1 on the wheel (the free rotation unloaded).
SystemModel ToothPair(const ToothParams& tp, double torque) {
  test::HandPairParams p;
  p.r1 = tp.r1;
  p.r2 = tp.r2;
  const MeshCore core = std::shared_ptr<const NonlinearMeshCore>(std::make_shared<ToothCore>(tp));
  SystemBuilder builder = test::HandPairBuilder(p, core);
  Vector6 t = Vector6::Zero();
  t(5) = torque;
  builder.AddTorque(BodyIndex(0), t, "drive");
  t(5) = torque * p.r2 / p.r1;
  builder.AddTorque(BodyIndex(1), t, "brake");
  return builder.Build().Restrict({5, 11});
}

TEST(NonlinearCoreTime, CompliantToothSteadyStateEqualsClosedForm) {
  const ToothParams tp;
  const test::HandPairParams hp;
  const double torque = 100.0;
  const SystemModel model = ToothPair(tp, torque);
  const double m_e = 1.0 / (tp.r1 * tp.r1 / hp.I1 + tp.r2 * tp.r2 / hp.I2);
  // Generalized-α at one frequency only: at the tolerance the energy balance needs it takes
  // ~10⁶ steps (second order, the 50 kHz tooth mode resolved).
  const std::vector<std::pair<TimeIntegrator, double>> runs = {
      {TimeIntegrator::kRungeKutta, 2000.0},
      {TimeIntegrator::kRungeKutta, 8000.0},
      {TimeIntegrator::kGeneralizedAlpha, 8000.0}};
  for (const auto& [method, f] : runs) {
    {
      TimeResponseOptions o;
      o.integration.integrator = method;
      o.integration.relative_tolerance = o.integration.absolute_tolerance =
          method == TimeIntegrator::kRungeKutta ? 1e-10 : 1e-9;
      // Above the period-to-period noise of the adaptive steps at that tolerance.
      o.steady.tolerance = method == TimeIntegrator::kRungeKutta ? 1e-8 : 1e-6;
      // ρ∞ = 1: no algorithmic dissipation of the 16 kHz tooth mode, which the energy balance
      // would report as an error (it is one: the numerical damping of generalized-α).
      o.integration.spectral_radius = 1.0;
      const TimeResponse r = SimulateSteadyState(model, f, o);
      ASSERT_TRUE(r.summary.ok()) << r.summary.BriefReport();
      // Closed form: mean δ̄ = (T/r1)(1/k_c + 1/k_b); harmonic D of [δ; u] from the 2×2 system.
      const double w = 2.0 * kPi * f;
      const std::complex<double> z(tp.k_c, w * tp.c_c);  // contact impedance
      Eigen::Matrix2cd a;
      a << z - m_e * w * w, -z, -z, z + std::complex<double>(tp.k_b - tp.m_t * w * w, w * tp.c_b);
      const Eigen::Vector2cd rhs(z * tp.e1, -z * tp.e1);
      const Eigen::Vector2cd du = a.partialPivLu().solve(rhs);
      const double mean = torque / tp.r1 * (1.0 / tp.k_c + 1.0 / tp.k_b);
      const double rms = std::abs(du(0)) / std::sqrt(2.0);
      const MeshTimeHistory& m = r.meshes.at(0);
      EXPECT_NEAR(m.mean_dte, mean, 1e-5 * mean) << ToString(method) << " " << f;
      EXPECT_NEAR(m.rms_dte, rms, 1e-4 * rms) << ToString(method) << " " << f;
      EXPECT_EQ(m.contact_loss_fraction, 0.0);
      EXPECT_LT(r.max_energy_error, 1e-4) << ToString(method) << " " << f;
      ASSERT_EQ(m.channel_names.size(), 1u);
      ASSERT_EQ(m.channels.cols(), o.integration.samples_per_period);
      // Contact force k_c c: its mean balances the load T/r1.
      EXPECT_NEAR(m.channels.row(0).mean(), torque / tp.r1, 1e-4 * torque / tp.r1);
      EXPECT_EQ(r.final_state.size(), 2 * 3);  // 2 DOF + 1 internal coordinate
    }
  }
}

// Slow roll: the tooth and contact springs in series carry T/r1, so the loaded TE is
// δ = ε(θ) + (T/r1)(1/k_c + 1/k_b) and the condensed tangent along η is k_c k_b/(k_c + k_b).
TEST(NonlinearCoreTime, QuasiStaticCompliantToothEqualsClosedForm) {
  const ToothParams tp;
  const double torque = 100.0;
  QuasiStaticOptions o;
  o.samples_per_mesh = 8;
  const QuasiStaticResult r = SimulateQuasiStatic(ToothPair(tp, torque), o);
  ASSERT_TRUE(r.summary.ok()) << r.summary.BriefReport();
  const QuasiStaticMesh& m = r.meshes.at(0);
  const double series = tp.k_c * tp.k_b / (tp.k_c + tp.k_b);
  for (Eigen::Index s = 0; s < r.theta.size(); ++s) {
    const double te = tp.e1 * std::cos(r.theta(s)) + torque / tp.r1 / series;
    EXPECT_NEAR(m.loaded_te(s), te, 1e-9 * te);
    EXPECT_NEAR(m.stiffness(0, s), series, 1e-9 * series);
    EXPECT_NEAR(m.stiffness(1, s), 0.0, 1e-9 * series * 0.01);
  }
}

}  // namespace
}  // namespace geardyn
