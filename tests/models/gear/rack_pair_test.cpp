// The gear–rack pair (issue 19): geometry, ISO 6336-1 stiffness and the mesh frame of a pinion
// meshing with a rack, against independent truths —
// * the rack is the limit of a gear with z_2 → ∞ (x_2 = 0): contact ratio, path of contact,
//   pressure angle, backlash and stiffness of z_2 = 10³, 10⁴, 10⁵ converge to the rack's;
// * the textbook contact ratio of a rack and pinion (KHK Gear Technical Reference, "contact
//   ratio of a rack and gear": ε_α = [√(r_a1² − r_b1²) − r_1 sin α_t + (h_a − x_1) m_n / sin α_t]
//   / (π m_t cos α_t));
// * the closed-form torsional–translational frequency of a pinion on a rack,
//   ω² = K cos²β_b (r_b1² / J + cos²α_t / m), and its limit from a gear whose mass sits on its
//   pitch circle.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include "geardyn/analyses/modal.hpp"
#include "geardyn/common/errors.hpp"
#include "geardyn/common/units.hpp"
#include "geardyn/models/gear/gear_geometry.hpp"
#include "geardyn/models/gear/iso_stiffness.hpp"
#include "geardyn/models/mesh/mesh_frame.hpp"
#include "geardyn/models/mesh/mesh_jacobian.hpp"
#include "geardyn/system/system_builder.hpp"
#include "support/expect_throws.hpp"

namespace geardyn {
namespace {

constexpr double kModule = 2e-3;

GearPairSpec RackSpec(double helix_deg = 0.0, int pinion_teeth = 20, double x1 = 0.2) {
  GearPairSpec s;
  s.normal_module = kModule;
  s.normal_pressure_angle = DegToRad(20.0);
  s.helix_angle = DegToRad(helix_deg);
  s.pinion_hand = helix_deg > 0.0 ? HelixHand::kRight : HelixHand::kNone;
  s.pinion.teeth = pinion_teeth;
  s.pinion.face_width = 0.02;
  s.pinion.profile_shift = x1;
  s.gear.kind = GearKind::kRack;
  s.gear.face_width = 0.025;
  return s;
}

// The same pinion with an external gear of z_2 teeth (x_2 = 0) in place of the rack.
GearPairSpec GearSpec(const GearPairSpec& rack, int z2) {
  GearPairSpec s = rack;
  s.gear.kind = GearKind::kExternal;
  s.gear.teeth = z2;
  s.center_distance.reset();
  return s;
}

TEST(RackPairTest, ContactRatioIsTheTextbookClosedForm) {
  for (double helix : {0.0, 15.0}) {
    const GearPairSpec spec = RackSpec(helix);
    const GearPairGeometry g = CalcGearPairGeometry(spec);
    ASSERT_TRUE(g.rack);
    const double m_t = kModule / std::cos(spec.helix_angle);
    const double alpha_t =
        std::atan(std::tan(spec.normal_pressure_angle) / std::cos(spec.helix_angle));
    const double r1 = 0.5 * spec.pinion.teeth * m_t;
    const double rb1 = r1 * std::cos(alpha_t);
    const double ra1 = r1 + kModule * (1.0 + spec.pinion.profile_shift);
    const double eps = (std::sqrt(ra1 * ra1 - rb1 * rb1) - r1 * std::sin(alpha_t) +
                        (1.0 - spec.pinion.profile_shift) * kModule / std::sin(alpha_t)) /
                       (std::numbers::pi * m_t * std::cos(alpha_t));
    EXPECT_NEAR(g.transverse_contact_ratio, eps, 1e-12) << helix;
    EXPECT_DOUBLE_EQ(g.operating_pressure_angle, alpha_t);
    EXPECT_DOUBLE_EQ(g.pinion.operating_pitch_radius, r1);
    EXPECT_DOUBLE_EQ(g.zero_backlash_center_distance, r1 + spec.pinion.profile_shift * kModule);
    EXPECT_EQ(g.backlash_normal, 0.0);
    EXPECT_EQ(g.hunting_period_meshes, spec.pinion.teeth);
    EXPECT_TRUE(std::isinf(g.gear.base_radius));
  }
}

TEST(RackPairTest, RackIsTheLimitOfAGrowingGear) {
  for (double helix : {0.0, 15.0}) {
    const GearPairSpec rack_spec = RackSpec(helix);
    const GearPairGeometry rack = CalcGearPairGeometry(rack_spec);
    const IsoMeshStiffness rack_k = CalcIsoMeshStiffness(rack);
    double previous = 1.0;
    for (int z2 : {1000, 10000, 100000}) {
      const GearPairGeometry gear = CalcGearPairGeometry(GearSpec(rack_spec, z2));
      const IsoMeshStiffness gear_k = CalcIsoMeshStiffness(gear);
      const double error = std::max(
          {std::abs(gear.transverse_contact_ratio - rack.transverse_contact_ratio),
           std::abs(gear.operating_pressure_angle - rack.operating_pressure_angle),
           std::abs(gear.path_start_from_pinion_tangent - rack.path_start_from_pinion_tangent) /
               kModule,
           std::abs(gear_k.mesh_alpha - rack_k.mesh_alpha) / rack_k.mesh_alpha});
      // First order in 1/z_2: the pinion's side of the path is exact, the gear's flank differs
      // from the rack's straight flank by its curvature, O(z_1/z_2) (measured ≈ 1.0 z_1/z_2).
      EXPECT_LT(error, 0.2 * previous) << "z2 = " << z2 << ", helix " << helix;
      EXPECT_LT(error, 2.0 * rack_spec.pinion.teeth / z2) << "z2 = " << z2 << ", helix " << helix;
      previous = error;
      EXPECT_DOUBLE_EQ(gear.path_end_from_pinion_tangent, rack.path_end_from_pinion_tangent);
    }
  }
}

// A rack moved out by Δ opens j_bn = 2Δ sin α_n (each flank moves Δ tan α_t on the pitch line),
// the limit of a gear pair whose centre distance grows by Δ.
TEST(RackPairTest, BacklashOfAMovedRackIsTheGearLimit) {
  GearPairSpec spec = RackSpec(15.0);
  const double delta = 0.1e-3;
  const double a0 = CalcGearPairGeometry(spec).zero_backlash_center_distance;
  spec.center_distance = a0 + delta;
  const GearPairGeometry rack = CalcGearPairGeometry(spec);
  EXPECT_NEAR(rack.backlash_normal, 2.0 * delta * std::sin(spec.normal_pressure_angle), 1e-15);
  GearPairSpec gear_spec = GearSpec(spec, 100000);
  gear_spec.center_distance = CalcGearPairGeometry(gear_spec).zero_backlash_center_distance + delta;
  const GearPairGeometry gear = CalcGearPairGeometry(gear_spec);
  EXPECT_NEAR(gear.backlash_normal, rack.backlash_normal, 1e-4 * rack.backlash_normal);
  // Moving the rack out shortens the path of contact from the rack's side only.
  EXPECT_LT(rack.transverse_contact_ratio,
            CalcGearPairGeometry(RackSpec(15.0)).transverse_contact_ratio);
}

TEST(RackPairTest, BadRackInputIsRefusedByName) {
  GearPairSpec spec = RackSpec();
  spec.gear.profile_shift = 0.1;
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(spec), InvalidInput, "gear.profile_shift");
  spec = RackSpec();
  spec.gear.tip_diameter = 0.1;
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(spec), InvalidInput, "gear.tip_diameter");
  spec = RackSpec();
  std::swap(spec.pinion, spec.gear);
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(spec), InvalidInput, "pinion.kind");
  spec = RackSpec();
  spec.center_distance = CalcGearPairGeometry(spec).zero_backlash_center_distance - 0.1e-3;
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(spec), InvalidInput, "center_distance");
  // 8 teeth without shift: the rack tip meets the pinion below its base circle.
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(RackSpec(0.0, 8, 0.0)), InvalidInput,
                        "gear.tip_interference");
  spec = RackSpec();
  spec.gear.addendum_coefficient = 2.0;  // top land π/2 − 4 tan 20° < 0.2
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(spec), InvalidInput, "tip");
  spec = RackSpec();
  spec.center_distance = CalcGearPairGeometry(spec).zero_backlash_center_distance + 3e-3;
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(spec), InvalidInput, "transverse_contact_ratio");
  spec.center_distance = *spec.center_distance + 3e-3;  // the rack's tips below the pinion's
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(spec), InvalidInput, "center_distance");
}

// The rack below the pinion (γ = −90°) runs along Z × (0, −1, 0) = +X.
TEST(RackPairTest, MeshFrameTouchesThePinionBaseCircleAndIsTheGearLimit) {
  for (double helix : {0.0, 15.0}) {
    for (int drive : {1, -1}) {
      const GearPairGeometry rack = CalcGearPairGeometry(RackSpec(helix));
      const Vector3 c_i(0.01, 0.02, 0.0);
      const MeshFrame f = CalcMeshFrame(rack, c_i, -0.5 * std::numbers::pi, drive);
      ASSERT_TRUE(f.rack);
      const double a_i = rack.pinion.base_radius;
      EXPECT_NEAR(f.u.dot(f.reference_point - c_i), a_i, 1e-15);  // tangent to the base circle
      EXPECT_NEAR((f.reference_point - c_i).norm(), rack.pinion.reference_radius, 1e-15);
      EXPECT_LT(f.gear_lever_arm.norm(), 1e-15);
      EXPECT_NEAR(f.eta.dot(f.zeta), 0.0, 1e-15);
      // The transverse force on the rack pushes it away from the pinion and along the drive.
      EXPECT_NEAR(f.v.dot(Vector3(0, -1, 0)), std::sin(rack.operating_pressure_angle), 1e-15);
      EXPECT_NEAR(f.v.dot(Vector3::UnitX()), drive * std::cos(rack.operating_pressure_angle),
                  1e-15);
      const Matrix2x12 G = CalcMeshJacobian(f);
      EXPECT_LT((G.block<1, 3>(0, 9).norm()), 1e-15);  // the rack's rotations: δ_ζ only
      // The same directions from a pinion with a 10⁵-tooth gear below it.
      const GearPairGeometry gear = CalcGearPairGeometry(GearSpec(RackSpec(helix), 100000));
      const MeshFrame fg = CalcMeshFrame(gear, c_i, -0.5 * std::numbers::pi, drive);
      EXPECT_LT((fg.eta - f.eta).norm(), 1e-4);
      EXPECT_LT((fg.u - f.u).norm(), 1e-4);
      EXPECT_LT((fg.reference_point - f.reference_point).norm(), 1e-4 * kModule);
      EXPECT_LT((fg.pinion_lever_arm - f.pinion_lever_arm).norm(), 1e-4 * kModule);
    }
  }
}

// A pinion turning about its axis (inertia J) and a rack sliding on its guide (mass m), joined by
// a mesh of constant stiffness K along η: δ_η = s r_b1 cos β_b θ_z − s cos α_t cos β_b x, so the
// one flexible mode has ω² = K cos²β_b (r_b1²/J + cos²α_t/m) (and one rigid mode: rolling).
// A gear of z_2 teeth whose mass m sits on its pitch circle (J_2 = m r_w2²) has
// ω² = K cos²β_b (r_b1²/J + cos²α_wt/m) with its own ISO stiffness: it tends to the rack's.
TEST(RackPairTest, TorsionalTranslationalFrequencyIsTheClosedFormAndTheGearLimit) {
  constexpr double kJ = 2e-4, kMass = 1.5;  // [kg m²], [kg]
  const auto frequency = [&](const GearPairGeometry& geometry, bool rack_member) {
    const MeshFrame f = CalcMeshFrame(geometry, Vector3::Zero(), -0.5 * std::numbers::pi, 1);
    const double K = CalcIsoMeshStiffness(geometry).mesh_alpha * geometry.face_width;
    VectorX channels(3);
    channels << K, 0.0, K * geometry.face_width * geometry.face_width / 12.0;
    const LinearMeshCore core(MeshCoreLevel::kBlankenshipSingh, ConstantCoefficient(channels),
                              0.5 * geometry.face_width);
    SystemBuilder builder;
    Matrix6 m_pinion = Matrix6::Identity();
    m_pinion(5, 5) = kJ;
    Matrix6 m_other = kMass * Matrix6::Identity();
    if (!rack_member) m_other(5, 5) = kMass * std::pow(geometry.gear.operating_pitch_radius, 2);
    const BodyIndex i = builder.AddBody("pinion", m_pinion);
    const BodyIndex j = builder.AddBody("other", m_other, f.gear_center);
    builder.AddMesh("mesh", i, j, CalcMeshJacobian(f), core);
    // The pinion's θz and the rack's x along its axis, or the gear's θz.
    const SystemModel model = builder.Build().Restrict({5, rack_member ? 6 : 11});
    const ModalResult modes = ComputeModes(model);
    EXPECT_TRUE(modes.summary.ok());
    EXPECT_EQ(modes.num_rigid_body_modes, 1);
    return std::pair{modes.frequencies_hz(1), K};
  };
  for (double helix : {0.0, 15.0}) {
    const GearPairGeometry rack = CalcGearPairGeometry(RackSpec(helix));
    const auto [f_rack, K] = frequency(rack, true);
    const double cb = std::cos(rack.base_helix_angle), ca = std::cos(rack.operating_pressure_angle);
    const double rb = rack.pinion.base_radius;
    const double closed =
        std::sqrt(K * cb * cb * (rb * rb / kJ + ca * ca / kMass)) / (2.0 * std::numbers::pi);
    EXPECT_NEAR(f_rack, closed, 1e-10 * closed) << helix;
    double previous = 1.0;
    for (int z2 : {1000, 10000}) {
      const double f_gear =
          frequency(CalcGearPairGeometry(GearSpec(RackSpec(helix), z2)), false).first;
      const double error = std::abs(f_gear - f_rack) / f_rack;
      EXPECT_LT(error, 0.2 * previous) << z2;
      EXPECT_LT(error, 2.0 * 20 / z2) << z2;  // O(z_1/z_2), as the geometry
      previous = error;
    }
  }
}

}  // namespace
}  // namespace geardyn
