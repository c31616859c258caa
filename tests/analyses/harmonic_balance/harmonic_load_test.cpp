// Harmonic loads (SystemBuilder::AddHarmonicLoad) in the linear harmonic balance and the time
// domain, against the closed-form FRF of a 1-DOF spring–mass–damper: m x'' + c x' + k x =
// f0 + Re(F1 e^{iθ}) + Re(F2 e^{2iθ}), θ = ω t. The mass sits on a constant linear mesh to a held
// body, so the mesh's DTE is x itself.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>

#include "geardyn/analyses/harmonic_balance.hpp"
#include "geardyn/analyses/time_response.hpp"
#include "geardyn/system/system_builder.hpp"

namespace geardyn {
namespace {

using Complex = std::complex<double>;
constexpr double kMass = 2.0, kStiffness = 2.0 * 4.0 * std::numbers::pi * std::numbers::pi;
constexpr double kDamping = 2.0 * 0.1 * 2.0 * std::numbers::pi * 2.0;  // ζ = 0.1 at f_n = 1 Hz
constexpr double kMean = 0.3;
const Complex kF1(0.5, 0.2), kF2(-0.1, 0.3);

SystemModel SpringMass() {
  SystemBuilder b;
  const BodyIndex a = b.AddBody("a", kMass * Matrix6::Identity());
  const BodyIndex g = b.AddBody("ground", Matrix6::Identity());
  Matrix6 c = Matrix6::Zero();
  c(0, 0) = kDamping;
  b.AddElement("damper", ElementKind::kSpring, {a}, Matrix6::Zero(), c);
  Matrix2x12 G = Matrix2x12::Zero();
  G(0, 0) = 1.0;
  G(0, 6) = -1.0;
  b.AddMesh("spring", a, g, G,
            LinearMeshCore(MeshCoreLevel::kTorsional,
                           ConstantCoefficient(Eigen::Vector3d(kStiffness, 0.0, 0.0)), 1.0));
  Vector6 f0 = Vector6::Zero();
  f0(0) = kMean;
  b.AddTorque(a, f0);
  Vector6c F = Vector6c::Zero();
  F(0) = kF1;
  b.AddHarmonicLoad(a, F, 1);
  F(0) = kF2;
  b.AddHarmonicLoad(a, F, 2);
  return b.Build().Restrict({0});
}

// X_m = F_m / (k − m (mω)² + i c mω): the complex amplitude of x at harmonic m.
Complex Frf(const Complex& F, int m, double omega) {
  const double w = m * omega;
  return F / Complex(kStiffness - kMass * w * w, kDamping * w);
}

TEST(HarmonicLoadHbTest, LinearHbEqualsTheClosedFormFrf) {
  const SystemModel model = SpringMass();
  HbOptions options;
  options.harmonics = 4;
  options.keep_harmonics = true;
  for (double f : {0.3, 0.5, 0.97, 1.6}) {
    const double omega = 2.0 * std::numbers::pi * f;
    const HbResult r = SolveHarmonicBalance(model, options, f);
    ASSERT_TRUE(r.summary.ok()) << r.summary.BriefReport();
    const Complex x1 = Frf(kF1, 1, omega), x2 = Frf(kF2, 2, omega);
    // One-sided Q_k = X_k / 2 (q = Q_0 + 2 Re Σ Q_k e^{ikθ}).
    EXPECT_NEAR(std::abs(r.response_harmonics(0, 1) - 0.5 * x1), 0.0, 1e-12 * std::abs(x1));
    EXPECT_NEAR(std::abs(r.response_harmonics(0, 2) - 0.5 * x2), 0.0, 1e-12 * std::abs(x2));
    EXPECT_NEAR(std::abs(r.response_harmonics(0, 3)), 0.0, 1e-14);
    EXPECT_NEAR(r.meshes[0].mean_dte, kMean / kStiffness, 1e-14);
    const double rms = std::sqrt(0.5 * (std::norm(x1) + std::norm(x2)));
    EXPECT_NEAR(r.meshes[0].rms_dte, rms, 1e-10 * rms);
  }
}

TEST(HarmonicLoadHbTest, TimeDomainSteadyStateEqualsTheFrfWithExactEnergyBalance) {
  const SystemModel model = SpringMass();
  TimeResponseOptions options;
  options.integration.integrator = TimeIntegrator::kRungeKutta;
  options.integration.relative_tolerance = 1e-11;
  options.integration.absolute_tolerance = 1e-11;
  options.steady.tolerance = 1e-9;
  for (double f : {0.5, 1.6}) {
    const double omega = 2.0 * std::numbers::pi * f;
    const TimeResponse r = SimulateSteadyState(model, f, options);
    ASSERT_TRUE(r.summary.ok()) << r.summary.BriefReport();
    const Complex x1 = Frf(kF1, 1, omega), x2 = Frf(kF2, 2, omega);
    const double rms = std::sqrt(0.5 * (std::norm(x1) + std::norm(x2)));
    EXPECT_NEAR(r.meshes[0].rms_dte, rms, 1e-6 * rms) << f;
    EXPECT_NEAR(r.meshes[0].mean_dte, kMean / kStiffness, 1e-6 * rms) << f;
    EXPECT_LT(r.max_energy_error, 1e-6) << f;
  }
}

}  // namespace
}  // namespace geardyn
