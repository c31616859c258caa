// The one rigid-body criterion (geardyn/numerics/rigid_modes.hpp) as the four analyses use it:
// modes (ComputeModes), linear HB (counter "rigid_body_modes"), nonlinear system HB
// (SystemNhbProblem::rigid_modes) and Floquet (counter "num_rigid_modes") must agree on the same
// scenes, and a real soft mode must keep its frequency.
//
// Independent truths:
// * the built-in helical pair has no torsional support: exactly one rigid-body mode (the pair
//   turning together), by its construction (both bearings' rz rows are zero);
// * with the pinion's axial support removed as well, the pinion can slide axially while both
//   gears turn so that the helical mesh stays undeformed: exactly two rigid-body modes;
// * with an axial bearing of k = 0.3 N/m on the pinion, the lowest flexible mode is that slide
//   against the soft spring. Every other stiffness is ≥ 10⁵ times larger, so in the limit the
//   stiff springs are constraints and the mode is a 1-DOF oscillator (closed form below).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "geardyn/analyses/floquet.hpp"
#include "geardyn/analyses/harmonic_balance.hpp"
#include "geardyn/analyses/modal.hpp"
#include "geardyn/analyses/system_nonlinear_hb.hpp"
#include "geardyn/models/gear/gear_geometry.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"
#include "geardyn/numerics/rigid_modes.hpp"

namespace geardyn {
namespace {

// The soft-mode closed form neglects k_soft/k_stiff ≈ 0.3/2e7 ≈ 1e-8; the dense solve gives ω²
// to ≈ ε·λ_max ≈ 2e-16 · 1e10 rad²/s² absolute, ≈ 1e-5 of ω² = 0.31 rad²/s² (observed 1.2e-6 in f).
constexpr double kSoftModeTol = 2e-5;

// The pinion's drive-end bearing of examples/scenes/helical-pair.toml with axial stiffness k_z.
std::string PinionDriveEndWithAxial(double k_z) {
  return "bearing.pinion-drive-end.stiffness=[[5.0e8, 0.0, 0.0, 0.0, 3.0e7, 0.0], "
         "[0.0, 5.0e8, 0.0, -3.0e7, 0.0, 0.0], [0.0, 0.0, " +
         std::to_string(k_z) +
         ", 0.0, 0.0, 0.0], [0.0, -3.0e7, 0.0, 1.8e6, 0.0, 0.0], "
         "[3.0e7, 0.0, 0.0, 0.0, 1.8e6, 0.0], [0.0, 0.0, 0.0, 0.0, 0.0, 0.0]]";
}

std::vector<std::string> HelicalOverrides(double k_z, bool slices) {
  std::vector<std::string> o = {PinionDriveEndWithAxial(k_z)};
  if (slices) {
    o.push_back("mesh.pinion-wheel.model=\"slices\"");
    o.push_back("mesh.pinion-wheel.slices=10");
    o.push_back("mesh.pinion-wheel.damping_ratio=0.05");
  }
  return o;
}

struct RigidCounts {
  int modes = -1, hb = -1, nhb = -1, floquet = -1;
};

RigidCounts CountRigidModes(double k_z) {
  RigidCounts c;
  const Scene scene = LoadScene("builtin:helical-pair", HelicalOverrides(k_z, false));
  const SystemModel model = BuildSceneSystem(scene).model;
  const double f_m = scene.MeshFrequencyHz(scene.meshes[0]);

  ModalOptions modal;
  modal.method = ModalMethod::kDense;
  c.modes = ComputeModes(model, modal).num_rigid_body_modes;

  HbOptions hb;
  hb.harmonics = 4;
  const HbResult h = SolveHarmonicBalance(model, hb, f_m);
  c.hb = static_cast<int>(h.summary.counters.at("rigid_body_modes"));

  FloquetOptions fl;
  fl.mesh_frequency_hz = f_m;
  fl.tolerance = 1e-6;
  fl.split_blocks = false;  // one state system: one count
  const FloquetResult r = ComputeFloquet(model, fl);
  c.floquet = static_cast<int>(r.summary.counters.at("num_rigid_modes"));

  const Scene sliced = LoadScene("builtin:helical-pair", HelicalOverrides(k_z, true));
  c.nhb = MakeSystemNhbProblem(BuildSceneSystem(sliced).model).rigid_modes;
  return c;
}

TEST(RigidModeCriterionTest, FreeTorsionIsTheOnlyRigidModeInAllFourAnalyses) {
  const RigidCounts c = CountRigidModes(3.0e8);  // the scene's own axial bearing
  EXPECT_EQ(c.modes, 1);
  EXPECT_EQ(c.hb, 1);
  EXPECT_EQ(c.nhb, 1);
  EXPECT_EQ(c.floquet, 1);
}

TEST(RigidModeCriterionTest, SoftAxialBearingIsFlexibleInAllFourAnalyses) {
  const RigidCounts c = CountRigidModes(0.3);
  EXPECT_EQ(c.modes, 1);
  EXPECT_EQ(c.hb, 1);
  EXPECT_EQ(c.nhb, 1);
  EXPECT_EQ(c.floquet, 1);
}

TEST(RigidModeCriterionTest, NoAxialSupportGivesTwoRigidModesInAllFourAnalyses) {
  const RigidCounts c = CountRigidModes(0.0);
  EXPECT_EQ(c.modes, 2);
  EXPECT_EQ(c.hb, 2);
  EXPECT_EQ(c.nhb, 2);
  EXPECT_EQ(c.floquet, 2);
}

// The lowest flexible mode with k_z = 0.3 N/m. In the constrained limit the pinion slides by z
// and both gears turn so that the mesh deflection δ = cos β_b (r_b1 θ1 + r_b2 θ2) ± sin β_b z
// stays zero; the kinetic energy is smallest (the free pair rotation takes the rest) when
// θ_i ∝ r_bi/I_i, which adds tan²β_b·m_eq, 1/m_eq = r_b1²/I1 + r_b2²/I2, to the pinion mass:
//   f = √(k_z / (m1 + tan²β_b·m_eq)) / 2π.
TEST(RigidModeCriterionTest, SoftAxialBearingModeMatchesTheConstrainedClosedForm) {
  const Scene scene = LoadScene("builtin:helical-pair", HelicalOverrides(0.3, false));
  const SystemModel model = BuildSceneSystem(scene).model;
  ModalOptions options;
  options.method = ModalMethod::kDense;
  const ModalResult r = ComputeModes(model, options);
  ASSERT_TRUE(r.summary.ok()) << r.summary.message;
  ASSERT_EQ(r.num_rigid_body_modes, 1);
  ASSERT_GE(r.frequencies_hz.size(), 2);
  EXPECT_EQ(r.frequencies_hz(0), 0.0);

  // Mass properties and geometry of examples/scenes/helical-pair.toml.
  const double m1 = 0.92925, I1 = 7.0029e-4, I2 = 2.4822e-2, k_z = 0.3;
  GearPairSpec spec;
  spec.normal_module = 0.003;
  spec.normal_pressure_angle = 20.0 * std::numbers::pi / 180.0;
  spec.helix_angle = 15.0 * std::numbers::pi / 180.0;
  spec.pinion_hand = HelixHand::kRight;
  spec.pinion.teeth = 25;
  spec.gear.teeth = 61;
  spec.pinion.face_width = spec.gear.face_width = 0.025;
  const GearPairGeometry g = CalcGearPairGeometry(spec);
  const double rb1 = g.pinion.base_radius, rb2 = g.gear.base_radius;
  const double tan_bb = std::tan(g.base_helix_angle);
  const double m_eq = 1.0 / (rb1 * rb1 / I1 + rb2 * rb2 / I2);
  const double f_closed = std::sqrt(k_z / (m1 + tan_bb * tan_bb * m_eq)) / (2.0 * std::numbers::pi);
  EXPECT_NEAR(r.frequencies_hz(1) / f_closed, 1.0, kSoftModeTol)
      << "f = " << r.frequencies_hz(1) << " Hz, closed form " << f_closed << " Hz";
  EXPECT_NEAR(f_closed, 0.089, 0.001);  // the "0.09 Hz mode" of issue 12
}

// The criterion itself: μ(φ) = |φᵀKφ|/φᵀ diag(K) φ, at its edge τ.
TEST(RigidModeCriterionTest, ScaledQuotientIsUnitFreeAndSharpAtTheThreshold) {
  // Two DOFs in very different units: a spring k between them plus a support s on the second.
  // φ = (1, 1): φᵀKφ = s, φᵀDφ = 2k + s, so μ = s/(2k + s) — whatever the scale of k.
  for (const double k : {1.0, 1e9, 1e-6}) {
    for (const double ratio : {0.5 * kRigidNullTol, 2.0 * kRigidNullTol}) {
      const double s = 2.0 * k * ratio / (1.0 - ratio);  // μ = ratio exactly
      MatrixX K(2, 2);
      K << k, -k, -k, k + s;
      const VectorX phi = VectorX::Ones(2);
      const VectorX d = RigidScaling(K.diagonal());
      EXPECT_NEAR(ScaledStiffnessQuotient(phi.dot(K * phi), d, phi) / ratio, 1.0, 1e-6);
      EXPECT_EQ(IsRigidBodyPattern(phi.dot(K * phi), d, phi), ratio < kRigidNullTol);
      EXPECT_EQ(ComputeRigidBodyModes(K).count(), ratio < kRigidNullTol ? 1 : 0);
    }
  }
}

}  // namespace
}  // namespace geardyn
