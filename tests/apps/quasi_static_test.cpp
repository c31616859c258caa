// ComputeQuasiStatic (apps/geardyn/quasi_static.hpp) on a contact-like NonlinearMeshCore with an
// internal coordinate: a tooth body u in series between the mesh deflection and the gear, energy
// E = ½k₁(δ_η − u)² + ½k₂u². Closed forms: the mesh stiffness seen from δ_η is the series
// stiffness k₁k₂/(k₁ + k₂) (the condensation of u), the mesh force is T/r₁ (torque balance of a
// pinion held only by the mesh), the loaded STE is F/K and the exported ε is 0.
#include "geardyn/quasi_static.hpp"

#include <gtest/gtest.h>

#include "geardyn/analyses/time_response.hpp"
#include "geardyn/common/errors.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"
#include "geardyn/system/system_builder.hpp"

namespace geardyn::app {
namespace {

constexpr double kK1 = 4e8;               // [N/m]
constexpr double kK2 = 6e8;               // [N/m]
constexpr double kR1 = 0.05, kR2 = 0.08;  // base radii [m]
constexpr double kTorque = 120.0;         // [N·m] on the pinion
constexpr double kTol = 1e-9;             // Newton on a linear problem, 12×12 condensation

// δ_η = g·x₁₂ with g = r₁ on the pinion's θz, r₂ on the gear's (column 5 and 11).
class SeriesToothCore final : public NonlinearMeshCore {
 public:
  int num_coordinates() const override { return 13; }
  int num_internal_coordinates() const override { return 1; }
  std::unique_ptr<NonlinearMeshCoreWorkspace> MakeWorkspace() const override {
    return std::make_unique<NonlinearMeshCoreWorkspace>();
  }
  MatrixX InternalMass() const override {
    MatrixX m = MatrixX::Zero(13, 13);
    m(12, 12) = 0.01;  // [kg]
    return m;
  }

 protected:
  void DoCalcForces(NonlinearMeshCoreWorkspace&, double, double, const Eigen::Ref<const VectorX>& x,
                    const Eigen::Ref<const VectorX>&, bool with_jacobians,
                    NonlinearMeshCoreOutput* out) const override {
    VectorX g = VectorX::Zero(13);
    g(5) = kR1;
    g(11) = kR2;
    const double delta = g.head(12).dot(x.head(12));
    const double u = x(12);
    const double f1 = kK1 * (delta - u);
    out->force = -f1 * g;
    out->force(12) = f1 - kK2 * u;
    out->energy = 0.5 * kK1 * (delta - u) * (delta - u) + 0.5 * kK2 * u * u;
    out->num_contacts = 1;
    if (with_jacobians) {
      g(12) = -1.0;
      out->stiffness = kK1 * g * g.transpose();
      out->stiffness(12, 12) += kK2;
      out->damping.setZero();
    }
  }
};

SystemModel SeriesToothPair() {
  SystemBuilder b;
  const Matrix6 mass = Vector6(1.0, 1.0, 1.0, 1e-3, 1e-3, 2e-3).asDiagonal();
  const BodyIndex pinion = b.AddBody("pinion", mass);
  const BodyIndex gear = b.AddBody("gear", mass);
  // Supports: everything held but the pinion's rotation; the gear's held by a torsional spring.
  MatrixX k = Vector6(1e9, 1e9, 1e9, 1e7, 1e7, 0.0).asDiagonal();
  b.AddElement("pinion-support", ElementKind::kBearing, {pinion}, k);
  k(5, 5) = 1e5;
  b.AddElement("gear-support", ElementKind::kBearing, {gear}, k);
  Matrix2x12 G = Matrix2x12::Zero();
  G(0, 5) = kR1;
  G(0, 11) = kR2;
  b.AddMesh("m", pinion, gear, G, std::make_shared<const SeriesToothCore>(), 1.0);
  Vector6 torque = Vector6::Zero();
  torque(5) = kTorque;
  b.AddTorque(pinion, torque, "input");
  return b.Build();
}

TEST(QuasiStaticTest, SeriesToothCoreGivesTheSeriesStiffness) {
  const QuasiStaticResult r = ComputeQuasiStatic(SeriesToothPair(), {0.01}, 8);
  ASSERT_TRUE(r.summary.ok()) << r.summary.message;
  ASSERT_EQ(r.meshes.size(), 1u);
  const double k_series = kK1 * kK2 / (kK1 + kK2);
  const double force = kTorque / kR1;
  const QuasiStaticMesh& m = r.meshes[0];
  ASSERT_EQ(m.parameters.stiffness.size(), 8u);
  for (int s = 0; s < 8; ++s) {
    EXPECT_NEAR(m.parameters.stiffness[s], k_series, kTol * k_series) << s;
    EXPECT_NEAR(m.force[s], force, kTol * force) << s;
    EXPECT_NEAR(m.loaded_ste[s], force / k_series, kTol * force / k_series) << s;
    EXPECT_NEAR(m.parameters.transmission_error[s], 0.0, kTol * force / k_series) << s;
  }
  EXPECT_EQ(r.summary.counters.at("static_solves"), 8);
}

TEST(QuasiStaticTest, SampleCountOutOfRangeNamesTheOption) {
  const SystemModel model = SeriesToothPair();
  EXPECT_THROW(
      {
        try {
          ComputeQuasiStatic(model, {0.01}, 0);
        } catch (const InvalidInput& e) {
          EXPECT_NE(std::string(e.what()).find("--samples-per-period"), std::string::npos);
          throw;
        }
      },
      InvalidInput);
}

// The engine's own slow roll (SimulateQuasiStatic, time_response.hpp: each static solve started
// from the previous one, its own tangent code) on the slice rig gives the same K(θ) and loaded
// STE: two implementations of the same definition.
TEST(QuasiStaticTest, EqualsTheEnginesSlowRollOnTheSliceRig) {
  const SystemModel model = MakeSystemModel(
      LoadScene("builtin:kahraman-blankenship-rig", {"mesh.pinion-wheel.model=slices"}));
  constexpr int kSamples = 16;
  const QuasiStaticResult mine = ComputeQuasiStatic(model, {0.01}, kSamples);
  QuasiStaticOptions options;
  options.samples_per_mesh = kSamples;
  const geardyn::QuasiStaticResult engine = SimulateQuasiStatic(model, options);
  ASSERT_TRUE(mine.summary.ok()) << mine.summary.message;
  ASSERT_TRUE(engine.summary.ok()) << engine.summary.message;
  ASSERT_EQ(engine.meshes.size(), 1u);
  ASSERT_EQ(engine.meshes[0].loaded_te.size(), kSamples);
  for (int s = 0; s < kSamples; ++s) {
    const double k = engine.meshes[0].stiffness(0, s);
    const double te = engine.meshes[0].loaded_te(s);
    EXPECT_NEAR(mine.meshes[0].parameters.stiffness[s], k, 1e-9 * k) << s;
    EXPECT_NEAR(mine.meshes[0].loaded_ste[s], te, 1e-8 * std::abs(te)) << s;
  }
}

}  // namespace
}  // namespace geardyn::app
