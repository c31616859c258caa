// Tests of CalcIsoMeshStiffness: the q' sum recomputed independently from the ISO 6336-1 table,
// the factors C_M, C_R, C_B, the line-load scaling, the ISO index swap, internal pairs, and the
// typical values c' ≈ 14, c_γα ≈ 20 N/(mm·µm) the standard gives for standard gears.
//
// The q' values are recomputed term by term from the standard's constants and the result is
// checked against the standard's typical values; published and commercial worked examples (ISO/TR
// 6336-30, a KISSsoft report) are in tests/reference/iso_6336_stiffness_test.cpp.
#include "geardyn/models/gear/iso_stiffness.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>

#include "geardyn/common/errors.hpp"
#include "geardyn/common/units.hpp"
#include "support/expect_throws.hpp"

namespace geardyn {
namespace {

constexpr double kMm = 1e-3;
constexpr double kNPerMmUm = 1e9;  // 1 N/(mm·µm) in N/m²
// The library and the tests evaluate the same closed forms in a different order.
constexpr double kRoundOff = 1e-12;

GearPairSpec SpurSpec(double module_mm, int z1, int z2, double x1, double x2, double b_mm) {
  GearPairSpec s;
  s.normal_module = module_mm * kMm;
  s.normal_pressure_angle = DegToRad(20.0);
  s.pinion.teeth = z1;
  s.gear.teeth = z2;
  s.pinion.profile_shift = x1;
  s.gear.profile_shift = x2;
  s.pinion.face_width = b_mm * kMm;
  s.gear.face_width = b_mm * kMm;
  return s;
}

// q' [mm·µm/N] written out term by term from ISO 6336-1 method B (index 1 = fewer teeth).
double QPrimeByHand(double zn1, double zn2, double x1, double x2) {
  return 0.04723 + 0.15551 / zn1 + 0.25791 / zn2 - 0.00635 * x1 - 0.11654 * x1 / zn1 -
         0.00193 * x2 - 0.24188 * x2 / zn2 + 0.00529 * x1 * x1 + 0.00182 * x2 * x2;
}

TEST(IsoStiffnessTest, KimRigSingleAndMeshStiffness) {
  GearPairSpec s = SpurSpec(3.0, 50, 50, 0.0, 0.0, 20.0);
  s.center_distance = 150.0 * kMm;
  const GearPairGeometry g = CalcGearPairGeometry(s);
  const IsoMeshStiffness k = CalcIsoMeshStiffness(g);
  // Spur, x = 0: z_n = z = 50, q' = 0.04723 + (0.15551 + 0.25791)/50 mm·µm/N.
  const double q = 0.04723 + (0.15551 + 0.25791) / 50.0;
  EXPECT_NEAR(k.q_prime, q * 1e-9, kRoundOff * 1e-9);
  EXPECT_NEAR(k.theoretical_single_pair / kNPerMmUm, 1.0 / q, kRoundOff);
  EXPECT_DOUBLE_EQ(k.blank_factor, 0.8);
  EXPECT_DOUBLE_EQ(k.rim_factor, 1.0);
  // ISO 6336-1: C_B = 0.975 for the standard rack h_fP = 1.25 m_n, α_Pn = 20°.
  EXPECT_NEAR(k.basic_rack_factor, 0.975, kRoundOff);
  const double c_prime = 0.8 * 0.975 / q;  // = 14.05 N/(mm·µm)
  EXPECT_NEAR(k.single_pair / kNPerMmUm, c_prime, kRoundOff);
  EXPECT_NEAR(k.mesh_alpha / kNPerMmUm, c_prime * (0.75 * g.transverse_contact_ratio + 0.25),
              kRoundOff);
  EXPECT_NEAR(k.mesh_beta, 0.85 * k.mesh_alpha, kRoundOff * kNPerMmUm);
  // ISO 6336-1 (and DIN 3990) quote c' ≈ 14 and c_γ ≈ 20 N/(mm·µm) as the typical values for
  // standard steel spur gears (used directly by the simplified method). c' within 10 %; c_γα
  // within 15 %, because the rig's ε_α = 1.75 is higher than the ε_α ≈ 1.5 behind the typical
  // 20 (factor (0.75 ε_α + 0.25) larger by 13 %).
  EXPECT_NEAR(k.single_pair / kNPerMmUm, 14.0, 0.10 * 14.0);
  EXPECT_NEAR(k.mesh_alpha / kNPerMmUm, 20.0, 0.15 * 20.0);
  EXPECT_TRUE(k.warnings.empty());
  EXPECT_FALSE(k.iso_pinion_is_spec_gear);
}

TEST(IsoStiffnessTest, HelicalPairUsesVirtualTeethAndFewerTeethAsIndexOne) {
  // The ISO 21771 worked pair (see gear_geometry_test): z 31/30, β = 21°; the spec's *gear* has
  // fewer teeth, so it is ISO's index 1.
  GearPairSpec s = SpurSpec(3.5, 31, 30, 0.291, 0.360877131252, 40.0);
  s.helix_angle = DegToRad(21.0);
  s.pinion_hand = HelixHand::kRight;
  const GearPairGeometry g = CalcGearPairGeometry(s);
  const IsoMeshStiffness k = CalcIsoMeshStiffness(g);
  EXPECT_TRUE(k.iso_pinion_is_spec_gear);
  // z_n = z / (cos² β_b cos β) with sin β_b = sin β cos α_n (independent identity).
  const double sb = std::sin(DegToRad(21.0)) * std::cos(DegToRad(20.0));
  const double zn = 1.0 / ((1.0 - sb * sb) * std::cos(DegToRad(21.0)));
  const double q = QPrimeByHand(30.0 * zn, 31.0 * zn, 0.360877131252, 0.291);
  EXPECT_NEAR(k.q_prime / 1e-9, q, kRoundOff);
  EXPECT_NEAR(k.single_pair / kNPerMmUm, 0.8 * 0.975 * std::cos(DegToRad(21.0)) / q, kRoundOff);
  // Naming the members the other way round changes nothing.
  GearPairSpec m = s;
  std::swap(m.pinion, m.gear);
  m.pinion_hand = HelixHand::kLeft;
  const IsoMeshStiffness km = CalcIsoMeshStiffness(CalcGearPairGeometry(m));
  EXPECT_FALSE(km.iso_pinion_is_spec_gear);
  EXPECT_NEAR(km.q_prime, k.q_prime, kRoundOff * 1e-9);
  EXPECT_NEAR(km.mesh_alpha, k.mesh_alpha, kRoundOff * kNPerMmUm);
}

TEST(IsoStiffnessTest, InternalPairDropsTheRingTermsOfQPrime) {
  // ISO 6336-1: for internal gears z_n2 = ∞, so C3/z_n2 and C7 x2/z_n2 vanish; the ring's x2
  // (ISO sign: −0.5 here, KHK +0.5) stays in C6 x2 + C9 x2².
  GearPairSpec s = SpurSpec(14.0, 17, 96, 0.2, -0.5, 100.0);
  s.gear.kind = GearKind::kInternal;
  const IsoMeshStiffness k = CalcIsoMeshStiffness(CalcGearPairGeometry(s));
  const double q = 0.04723 + 0.15551 / 17.0 - 0.00635 * 0.2 - 0.11654 * 0.2 / 17.0 -
                   0.00193 * (-0.5) + 0.00529 * 0.04 + 0.00182 * 0.25;
  EXPECT_NEAR(k.q_prime / 1e-9, q, kRoundOff);
  // x1 = 0.2 ≥ x2 = −0.5 and −0.5 ≤ x1 + x2 = −0.3: inside the fit range, no warning.
  EXPECT_TRUE(k.warnings.empty());
}

TEST(IsoStiffnessTest, LineLoadBelow100NPerMmScalesSinglePairStiffness) {
  GearPairSpec s = SpurSpec(3.0, 50, 50, 0.0, 0.0, 20.0);
  const GearPairGeometry g = CalcGearPairGeometry(s);
  const IsoMeshStiffness full = CalcIsoMeshStiffness(g);
  IsoStiffnessOptions o;
  o.line_load = 50.0e3;  // 50 N/mm
  const IsoMeshStiffness half = CalcIsoMeshStiffness(g, o);
  EXPECT_NEAR(half.line_load_factor, std::pow(0.5, 0.25), kRoundOff);
  EXPECT_NEAR(half.single_pair / full.single_pair, std::pow(0.5, 0.25), kRoundOff);
  EXPECT_NEAR(half.theoretical_single_pair, full.theoretical_single_pair, 0.0);
  o.line_load = 150.0e3;  // above 100 N/mm: no change
  EXPECT_DOUBLE_EQ(CalcIsoMeshStiffness(g, o).single_pair, full.single_pair);
}

TEST(IsoStiffnessTest, RimAndBasicRackFactors) {
  GearPairSpec s = SpurSpec(3.0, 30, 90, 0.0, 0.0, 40.0);
  s.gear.web_thickness = 20.0 * kMm;  // b_s/b = 0.5
  s.gear.rim_thickness = 9.0 * kMm;   // s_R/m_n = 3
  const IsoMeshStiffness k = CalcIsoMeshStiffness(CalcGearPairGeometry(s));
  // ISO 6336-1: C_R = 1 + ln(b_s/b) / (5 e^{s_R/(5 m_n)}) = 1 + ln 0.5 / (5 e^0.6).
  const double c_r = 1.0 + std::log(0.5) / (5.0 * std::exp(0.6));
  EXPECT_NEAR(k.rim_factor, c_r, kRoundOff);
  EXPECT_NEAR(k.rim_factor, 0.92392, 1e-5);
  // Both blanks webbed: one C_R for the mesh, the more flexible blank's (here the pinion's).
  s.pinion.web_thickness = 8.0 * kMm;  // b_s/b = 0.2
  s.pinion.rim_thickness = 3.0 * kMm;  // s_R/m_n = 1
  const IsoMeshStiffness k2 = CalcIsoMeshStiffness(CalcGearPairGeometry(s));
  EXPECT_NEAR(k2.rim_factor, 1.0 + std::log(0.2) / (5.0 * std::exp(0.2)), kRoundOff);
  EXPECT_LT(k2.rim_factor, c_r);
  EXPECT_TRUE(k2.warnings.empty());
  // Out-of-range b_s/b and s_R/m_n are clamped to 0.2 and 1 with warnings.
  s.pinion.web_thickness = 2.0 * kMm;
  s.pinion.rim_thickness = 1.5 * kMm;
  const IsoMeshStiffness k3 = CalcIsoMeshStiffness(CalcGearPairGeometry(s));
  EXPECT_NEAR(k3.rim_factor, k2.rim_factor, kRoundOff);
  ASSERT_EQ(k3.warnings.size(), 2u);
  EXPECT_NE(k3.warnings[0].find("pinion.web_thickness"), std::string::npos);
  EXPECT_NE(k3.warnings[1].find("pinion.rim_thickness"), std::string::npos);

  // C_B = [1 + 0.5 (1.2 − h_fP*)] [1 − 0.02 (20 − α_Pn/°)], averaged over the two racks.
  GearPairSpec r = SpurSpec(3.0, 30, 90, 0.0, 0.0, 40.0);
  r.normal_pressure_angle = DegToRad(25.0);
  r.pinion.dedendum_coefficient = 1.2;
  r.gear.dedendum_coefficient = 1.4;
  r.gear.root_radius_coefficient = 0.3;
  const IsoMeshStiffness kb = CalcIsoMeshStiffness(CalcGearPairGeometry(r));
  EXPECT_NEAR(kb.basic_rack_factor, 0.5 * (1.0 + 0.9) * 1.1, kRoundOff);
}

TEST(IsoStiffnessTest, WarnsOutsideTheValidityRange) {
  // x1 < x2 (index 1 = fewer teeth) lies outside the q' fit range; ε_α < 1.2 too.
  GearPairSpec s = SpurSpec(3.0, 30, 90, -0.2, 0.4, 40.0);
  s.pinion.tip_diameter = 2.0 * (45.0 + 0.5 * 3.0) * kMm;  // short tips: ε_α ≈ 1.09
  s.gear.tip_diameter = 2.0 * (135.0 + 0.9 * 3.0) * kMm;
  const GearPairGeometry g = CalcGearPairGeometry(s);
  ASSERT_LT(g.transverse_contact_ratio, 1.2);
  const IsoMeshStiffness k = CalcIsoMeshStiffness(g);
  ASSERT_EQ(k.warnings.size(), 2u);
  EXPECT_NE(k.warnings[0].find("q_prime"), std::string::npos);
  EXPECT_NE(k.warnings[1].find("mesh_alpha"), std::string::npos);
}

TEST(IsoStiffnessTest, RejectsBadOptionsAndIncompleteBlanks) {
  GearPairSpec s = SpurSpec(3.0, 30, 90, 0.0, 0.0, 40.0);
  const GearPairGeometry g = CalcGearPairGeometry(s);
  IsoStiffnessOptions o;
  o.blank_factor = 0.0;
  EXPECT_THROWS_MESSAGE(CalcIsoMeshStiffness(g, o), InvalidInput, "^blank_factor: ");
  o = {};
  o.line_load = -1.0;
  EXPECT_THROWS_MESSAGE(CalcIsoMeshStiffness(g, o), InvalidInput, "^line_load: ");
  s.pinion.web_thickness = 10.0 * kMm;
  EXPECT_THROWS_MESSAGE(CalcIsoMeshStiffness(CalcGearPairGeometry(s)), InvalidInput,
                        "^pinion\\.rim_thickness: required");
}

}  // namespace
}  // namespace geardyn
