// Harmonic loads Re(F e^{imθ}) of SystemBuilder::AddHarmonicLoad: validation, restriction, and
// their place in f(θ) (AssembleLoad) and in the load harmonics (ExpandSystemHarmonics), against
// the closed form of the cosine they stand for.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <limits>

#include "geardyn/common/errors.hpp"
#include "geardyn/system/system_builder.hpp"
#include "geardyn/system/system_harmonics.hpp"
#include "geardyn/system/workspace.hpp"

namespace geardyn {
namespace {

using Complex = std::complex<double>;
constexpr double kTol = 1e-12;  // a few flops on O(1) numbers

// Body "a" (x kept) on a constant mesh to body "b" (fixed): a 1-DOF system with f0 = 3,
// a harmonic load F cos(2θ + arg F) and a second one of order 1 on y (held fixed).
SystemModel OneDof(const Complex& f2) {
  SystemBuilder b;
  const BodyIndex a = b.AddBody("a", Matrix6::Identity());
  const BodyIndex g = b.AddBody("b", Matrix6::Identity());
  Matrix2x12 G = Matrix2x12::Zero();
  G(0, 0) = 1.0;
  G(0, 6) = -1.0;
  b.AddMesh("m", a, g, G,
            LinearMeshCore(MeshCoreLevel::kTorsional,
                           ConstantCoefficient(Eigen::Vector3d(100.0, 0.0, 0.0)), 1.0));
  Vector6 f0 = Vector6::Zero();
  f0(0) = 3.0;
  b.AddTorque(a, f0);
  Vector6c F = Vector6c::Zero();
  F(0) = f2;
  b.AddHarmonicLoad(a, F, 2, "second");
  Vector6c Fy = Vector6c::Zero();
  Fy(1) = 5.0;
  b.AddHarmonicLoad(a, Fy, 1, "on y");
  return b.Build().Restrict({0});
}

TEST(HarmonicLoadTest, SurvivesRestrictionOnTheKeptDofsOnly) {
  const SystemModel model = OneDof(Complex(2.0, 1.0));
  ASSERT_EQ(model.num_dofs(), 1);
  ASSERT_EQ(model.harmonic_loads().size(), 2u);  // both touch body "a", whose x is kept
  EXPECT_EQ(model.harmonic_loads()[0].name, "second");
  EXPECT_EQ(model.harmonic_loads()[0].order, 2);
  EXPECT_EQ(model.harmonic_loads()[0].dofs[0], 0);
  for (int c = 1; c < 6; ++c) EXPECT_EQ(model.harmonic_loads()[0].dofs[c], -1);
  EXPECT_EQ(model.period_meshes(), 1);  // integer orders keep the period
}

TEST(HarmonicLoadTest, AssembleLoadIsTheCosine) {
  const Complex F(2.0, 1.0);
  const SystemModel model = OneDof(F);
  SystemWorkspace ws(model, StorageKind::kDense);
  for (double theta : {0.0, 0.7, 2.9, -4.1}) {
    const double truth = 3.0 + std::abs(F) * std::cos(2.0 * theta + std::arg(F));
    EXPECT_NEAR(AssembleLoad(model, ws, theta)(0), truth, kTol) << theta;
  }
  EXPECT_NEAR(AssembleMeanLoad(model, ws, 64)(0), 3.0, kTol);  // mean zero
}

TEST(HarmonicLoadTest, LoadHarmonicsHoldHalfTheAmplitudeAtTheOrder) {
  const Complex F(2.0, 1.0);
  const SystemHarmonics h = ExpandSystemHarmonics(OneDof(F), 4);
  ASSERT_EQ(h.num_harmonics(), 4);
  EXPECT_NEAR(std::abs(h.load[0](0) - Complex(3.0, 0.0)), 0.0, kTol);
  EXPECT_NEAR(std::abs(h.load[1](0)), 0.0, kTol);
  EXPECT_NEAR(std::abs(h.load[2](0) - 0.5 * F), 0.0, kTol);
  EXPECT_NEAR(std::abs(h.load[3](0)), 0.0, kTol);
}

TEST(HarmonicLoadTest, BadInputThrowsNamingTheLoad) {
  SystemBuilder b;
  const BodyIndex a = b.AddBody("a", Matrix6::Identity());
  Vector6c F = Vector6c::Zero();
  EXPECT_THROW(b.AddHarmonicLoad(a, F, 0, "zero"), InvalidInput);
  try {
    b.AddHarmonicLoad(a, F, -1, "neg");
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("harmonic load 'neg' order"), std::string::npos);
  }
  F(2) = Complex(std::numeric_limits<double>::infinity(), 0.0);
  EXPECT_THROW(b.AddHarmonicLoad(a, F, 1, "inf"), InvalidInput);
  EXPECT_THROW(b.AddHarmonicLoad(BodyIndex(7), Vector6c::Zero(), 1, "nobody"), InvalidInput);
}

}  // namespace
}  // namespace geardyn
