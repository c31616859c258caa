/// @file
/// @brief SimulateQuasiStatic (time_response.hpp) where the flanks start apart, on a torsional pair
/// whose mesh is a test double of a contact core with backlash: the force k·(δ − g)⁺ along
/// δ = r1 θ1 + r2 θ2 (g the gap, θ-dependent where stated). Closed forms: under the torque T the
/// contact closes at δ = g + F/k with F = T/r1, the tangent is k, the force pair F and the LTV
/// transmission error ε = δ − F/k = g; with no torque every position in the gap is an equilibrium
/// (free play); where no pair can touch the load cannot be carried (a clear status, no NaN). Also
/// the per-mesh sampling (the mesh's own phase θ_k = rθ + φ), the mesh force of a contact core
/// (= T/r1, the torque balance of the pinion) and EstimateTimeRun against the 1-DOF closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <optional>

#include "geardyn/analyses/time_response.hpp"
#include "geardyn/system/system_builder.hpp"

namespace geardyn {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kR1 = 0.04, kR2 = 0.09;    // base radii [m]
constexpr double kI1 = 9e-4, kI2 = 2.4e-2;  // polar inertias [kg m²]
constexpr double kK = 4e8;                  // contact stiffness [N/m]
constexpr double kGap = 50e-6;              // backlash-like gap [m] (≫ F/k_stand-in = 2.5 µm)

// k·(δ − g(θ))⁺; `stiffness_wave` a: k(θ) = k(1 + a cos θ); `half_cycle`: no pair in reach for
// θ mod 2π in [π, 2π) (contact ratio 1/2).
class GapCore final : public NonlinearMeshCore {
 public:
  GapCore(double stiffness_wave, bool half_cycle) : a_(stiffness_wave), half_(half_cycle) {}
  int num_coordinates() const override { return 12; }
  std::unique_ptr<NonlinearMeshCoreWorkspace> MakeWorkspace() const override {
    return std::make_unique<NonlinearMeshCoreWorkspace>();
  }

 protected:
  void DoCalcForces(NonlinearMeshCoreWorkspace&, double theta, double,
                    const Eigen::Ref<const VectorX>& x, const Eigen::Ref<const VectorX>&,
                    bool with_jacobians, NonlinearMeshCoreOutput* out) const override {
    VectorX g = VectorX::Zero(12);
    g(5) = kR1;
    g(11) = kR2;
    const double delta = g.dot(x);
    const double phase = std::fmod(std::fmod(theta, 2.0 * kPi) + 2.0 * kPi, 2.0 * kPi);
    const bool reach = !half_ || phase < kPi;
    const double k = kK * (1.0 + a_ * std::cos(theta));
    const double c = reach ? delta - kGap : -1.0;
    const double f = c > 0.0 ? k * c : 0.0;
    out->force = -f * g;
    out->energy = c > 0.0 ? 0.5 * k * c * c : 0.0;
    out->num_contacts = c > 0.0 ? 1 : 0;
    if (with_jacobians) {
      out->stiffness = (c > 0.0 ? k : 0.0) * g * g.transpose();
      out->damping.setZero();
    }
  }

 private:
  double a_;
  bool half_;
};

// Pinion and wheel rotations only; torque T on the pinion, T r2/r1 against it on the wheel (a
// balanced free train); the mesh at phase θ_k = rθ + φ.
SystemModel GapPair(double torque, double wave = 0.0, bool half = false, double ratio = 1.0,
                    double offset = 0.0) {
  SystemBuilder b;
  const Vector6 m1 = Vector6(1.0, 1.0, 1.0, 1e-3, 1e-3, kI1);
  const Vector6 m2 = Vector6(5.0, 5.0, 5.0, 1e-2, 1e-2, kI2);
  const BodyIndex i = b.AddBody("pinion", Matrix6(m1.asDiagonal()));
  const BodyIndex j = b.AddBody("wheel", Matrix6(m2.asDiagonal()), Vector3(kR1 + kR2, 0, 0));
  Matrix2x12 G = Matrix2x12::Zero();
  G(0, 5) = kR1;
  G(0, 11) = kR2;
  G(1, 3) = 1.0;
  G(1, 9) = -1.0;
  b.AddMesh("mesh", i, j, G,
            std::shared_ptr<const NonlinearMeshCore>(std::make_shared<GapCore>(wave, half)),
            std::nullopt, ratio, offset);
  Vector6 t = Vector6::Zero();
  t(5) = torque;
  b.AddTorque(i, t, "drive");
  t(5) = torque * kR2 / kR1;
  b.AddTorque(j, t, "brake");
  return b.Build().Restrict({5, 11});
}

// Under load from a start with the flanks 47.5 µm apart (the stand-in guess): the contact found,
// δ = g + F/k, K = k, F = T/r1 (the contact core's mesh force), ε = g.
TEST(QuasiStaticFlanks, StartWithFlanksApartFindsTheContact) {
  constexpr double kTorque = 100.0;
  QuasiStaticOptions o;
  o.samples_per_mesh = 8;
  const QuasiStaticResult r = SimulateQuasiStatic(GapPair(kTorque), o);
  ASSERT_TRUE(r.summary.ok()) << r.summary.message;
  EXPECT_GE(r.summary.counters.at("regularised_starts"), 1);
  const QuasiStaticMesh& m = r.meshes.at(0);
  const double force = kTorque / kR1;
  ASSERT_EQ(m.loaded_te.size(), 8);
  for (Eigen::Index s = 0; s < 8; ++s) {
    EXPECT_NEAR(m.loaded_te(s), kGap + force / kK, 1e-9 * kGap) << s;
    EXPECT_NEAR(m.stiffness(0, s), kK, 1e-9 * kK) << s;
    EXPECT_NEAR(m.force(s), force, 1e-9 * force) << s;
    EXPECT_NEAR(m.force_pair(0, s), force, 1e-9 * force) << s;
    EXPECT_NEAR(m.transmission_error(s), kGap, 1e-9 * kGap) << s;
    EXPECT_EQ(m.contacts(s), 1) << s;
  }
}

// No torque: the rest position inside the gap is an equilibrium (free play) — success, K = 0,
// ε = δ = 0, a warning, no NaN.
TEST(QuasiStaticFlanks, ZeroTorqueInTheGapIsFreePlay) {
  QuasiStaticOptions o;
  o.samples_per_mesh = 4;
  const QuasiStaticResult r = SimulateQuasiStatic(GapPair(0.0), o);
  ASSERT_TRUE(r.summary.ok()) << r.summary.message;
  EXPECT_EQ(r.summary.counters.at("free_play_samples"), 4);
  ASSERT_FALSE(r.summary.warnings.empty());
  EXPECT_NE(r.summary.warnings[0].find("free play"), std::string::npos);
  const QuasiStaticMesh& m = r.meshes.at(0);
  ASSERT_EQ(m.loaded_te.size(), 4);
  for (Eigen::Index s = 0; s < 4; ++s) {
    EXPECT_EQ(m.stiffness(0, s), 0.0);
    EXPECT_EQ(m.loaded_te(s), 0.0);
    EXPECT_EQ(m.transmission_error(s), 0.0);
    EXPECT_EQ(m.contacts(s), 0);
  }
}

// Contact ratio 1/2: at θ ∈ [π, 2π) no pair is in reach and the torque cannot be carried —
// status kNotConverged naming the flanks, the samples before kept, all finite.
TEST(QuasiStaticFlanks, NoPairInReachIsAClearStatusNotANaN) {
  QuasiStaticOptions o;
  o.samples_per_mesh = 8;
  const QuasiStaticResult r = SimulateQuasiStatic(GapPair(100.0, 0.0, true), o);
  EXPECT_EQ(r.summary.status, Status::kNotConverged);
  EXPECT_NE(r.summary.message.find("flanks apart"), std::string::npos) << r.summary.message;
  const QuasiStaticMesh& m = r.meshes.at(0);
  EXPECT_EQ(m.loaded_te.size(), 4);  // θ = 0, π/4, π/2, 3π/4 solved; π is not
  EXPECT_TRUE(m.loaded_te.allFinite());
  EXPECT_TRUE(m.stiffness.allFinite());
  EXPECT_TRUE(m.transmission_error.allFinite());
}

// kMeshCycle samples the mesh's own phase: with θ_k = 3θ + 0.4 and k(θ_k) = k(1 + 0.3 cos θ_k),
// sample s has K = k(1 + 0.3 cos(2πs/S)) and system phase θ = (2πs/S − 0.4)/3.
TEST(QuasiStaticFlanks, MeshCycleSamplingUsesTheMeshsOwnPhase) {
  constexpr int kSamples = 12;
  constexpr double kRatio = 3.0, kOffset = 0.4, kWave = 0.3, kTorque = 80.0;
  QuasiStaticOptions o;
  o.samples_per_mesh = kSamples;
  o.sampling = QuasiStaticSampling::kMeshCycle;
  const QuasiStaticResult r =
      SimulateQuasiStatic(GapPair(kTorque, kWave, false, kRatio, kOffset), o);
  ASSERT_TRUE(r.summary.ok()) << r.summary.message;
  const QuasiStaticMesh& m = r.meshes.at(0);
  ASSERT_EQ(m.loaded_te.size(), kSamples);
  EXPECT_TRUE(std::isnan(m.next_cycle_change));  // P = 1: not checked
  const double force = kTorque / kR1;
  for (int s = 0; s < kSamples; ++s) {
    const double phase = 2.0 * kPi * s / kSamples;
    const double k = kK * (1.0 + kWave * std::cos(phase));
    EXPECT_NEAR(m.mesh_phase(s), phase, 1e-12) << s;
    EXPECT_NEAR(m.theta(s), (phase - kOffset) / kRatio, 1e-12) << s;
    EXPECT_NEAR(m.stiffness(0, s), k, 1e-9 * k) << s;
    EXPECT_NEAR(m.loaded_te(s), kGap + force / k, 1e-9 * kGap) << s;
  }
}

// EstimateTimeRun on the gap pair under load: the highest frequency is the mesh mode,
// ω² = k (r1²/I1 + r2²/I2); δ = g + F/k; the fewest periods with the defaults (min 2,
// 3 consecutive, 1 recorded) are 2 + 3 − 1 + 1 = 5.
TEST(QuasiStaticFlanks, TimeRunEstimateEqualsTheOneDofClosedForm) {
  constexpr double kTorque = 100.0, kFm = 50.0;
  const TimeRunEstimate e = EstimateTimeRun(GapPair(kTorque), kFm, TimeResponseOptions{});
  ASSERT_TRUE(e.summary.ok()) << e.summary.message;
  const double f_mesh = std::sqrt(kK * (kR1 * kR1 / kI1 + kR2 * kR2 / kI2)) / (2.0 * kPi);  // [Hz]
  EXPECT_NEAR(e.highest_frequency_hz, f_mesh, 1e-6 * f_mesh);
  ASSERT_EQ(e.static_deflection.size(), 1u);
  EXPECT_NEAR(e.static_deflection[0], kGap + kTorque / kR1 / kK, 1e-9 * kGap);
  EXPECT_EQ(e.min_periods, 5);
  EXPECT_NEAR(e.min_simulated_time_s, 5.0 / kFm, 1e-12);
  EXPECT_NEAR(e.highest_mode_cycles, f_mesh * 5.0 / kFm, 1e-6 * f_mesh * 5.0 / kFm);
}

}  // namespace
}  // namespace geardyn
