#include "geardyn/system/static_deflection.hpp"

#include <gtest/gtest.h>

#include "hand_pair.hpp"
#include "support/expect_throws.hpp"

namespace geardyn {
namespace {

using test::HandPairBuilder;
using test::HandPairParams;
using test::SpurCore;

Vector6 Torque(double t) {
  Vector6 f = Vector6::Zero();
  f(5) = t;
  return f;
}

// Torsional pair on bearings: T on the pinion, T r2/r1 on the wheel (balanced through the mesh);
// mean mesh deflection δ_η = T / (r_b1 k̄).
TEST(StaticDeflectionTest, TorsionalPairMeshDeflectionMatchesClosedForm) {
  const HandPairParams p;
  const double T = 150.0;
  SystemBuilder builder = HandPairBuilder(p, SpurCore(p));
  builder.AddTorque(BodyIndex(0), Torque(T), "input");
  builder.AddTorque(BodyIndex(1), Torque(T * p.r2 / p.r1), "output");
  const StaticDeflectionResult r = SolveStaticDeflection(builder.Build());
  ASSERT_TRUE(r.summary.ok()) << r.summary.BriefReport();
  EXPECT_EQ(r.num_rigid_modes, 1);  // the conjugate rotation
  ASSERT_EQ(r.meshes.size(), 1u);
  EXPECT_NEAR(r.meshes[0].delta_eta, T / (p.r1 * p.k), 1e-10 * T / (p.r1 * p.k));
  EXPECT_NEAR(r.meshes[0].force_eta, T / p.r1, 1e-9 * T / p.r1);
  EXPECT_NEAR(r.meshes[0].delta_zeta, 0.0, 1e-15);
  EXPECT_FALSE(r.meshes[0].contact_open);
  EXPECT_LE(r.unbalanced_load, 1e-8 * T);
  // Bearing forces: the pinion bearing reacts the mesh force along y (−F on the pinion).
  ASSERT_EQ(r.element_forces.size(), 2u);
  EXPECT_NEAR(r.element_forces[0](1), -T / p.r1, 1e-9 * T / p.r1);
  EXPECT_NEAR(r.element_forces[1](1), T / p.r1, 1e-9 * T / p.r1);
  for (const std::string& w : r.summary.warnings) {
    EXPECT_EQ(w.find("open"), std::string::npos) << w;
  }
}

TEST(StaticDeflectionTest, ReversedTorqueOpensTheContact) {
  const HandPairParams p;
  const double T = -80.0;
  SystemBuilder builder = HandPairBuilder(p, SpurCore(p));
  builder.AddTorque(BodyIndex(0), Torque(T));
  builder.AddTorque(BodyIndex(1), Torque(T * p.r2 / p.r1));
  const StaticDeflectionResult r = SolveStaticDeflection(builder.Build());
  ASSERT_EQ(r.meshes.size(), 1u);
  EXPECT_TRUE(r.meshes[0].contact_open);
  bool warned = false;
  for (const std::string& w : r.summary.warnings) {
    warned = warned || w.find("mesh 'mesh': the mean load would open the contact") == 0;
  }
  EXPECT_TRUE(warned);
}

TEST(StaticDeflectionTest, UnbalancedTorqueIsReported) {
  const HandPairParams p;
  SystemBuilder builder = HandPairBuilder(p, SpurCore(p));
  builder.AddTorque(BodyIndex(0), Torque(100.0));
  const StaticDeflectionResult r = SolveStaticDeflection(builder.Build());
  EXPECT_GT(r.unbalanced_load, 0.0);
  bool warned = false;
  for (const std::string& w : r.summary.warnings) {
    warned = warned || w.find("not balanced") != std::string::npos;
  }
  EXPECT_TRUE(warned);
  EXPECT_TRUE(r.deflection.allFinite());
}

TEST(StaticDeflectionTest, RejectsInvalidOptions) {
  const HandPairParams p;
  StaticDeflectionOptions options;
  options.samples_per_period = 0;
  EXPECT_THROWS_MESSAGE(SolveStaticDeflection(HandPairBuilder(p, SpurCore(p)).Build(), options),
                        InvalidInput, "samples_per_period");
}

}  // namespace
}  // namespace geardyn
