// Tests of CalcGearPairGeometry against published worked examples, independent closed forms,
// invariants and a brute-force contact-line sum.
#include "geardyn/models/gear/gear_geometry.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "geardyn/common/errors.hpp"
#include "geardyn/common/units.hpp"
#include "support/expect_throws.hpp"

namespace geardyn {
namespace {

constexpr double kMm = 1e-3;
// Published tables print rounded numbers: allow half a unit of the last printed digit (plus a
// hair for the binary representation of the printed value).
double PrintedTolerance(int decimals) { return 0.5 * std::pow(10.0, -decimals) * (1.0 + 1e-9); }
// Identities that hold exactly up to floating-point round-off of a few operations.
constexpr double kRoundOff = 1e-12;

// Independent inverse involute by bisection (the library uses Newton).
double InvInvBisect(double v) {
  double lo = 0.0;
  double hi = 0.5 * kPi - 1e-12;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (std::tan(mid) - mid < v ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}
double Inv(double a) { return std::tan(a) - a; }

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

// Kim et al. 2015 / Kahraman–Blankenship rig (spec 03): m 3, z 50/50, α 20°, x 0, b 20 mm.
GearPairSpec KimRigSpec() {
  GearPairSpec s = SpurSpec(3.0, 50, 50, 0.0, 0.0, 20.0);
  s.center_distance = 150.0 * kMm;
  return s;
}

// KHK profile-shifted spur pair (see ProfileShiftedSpurMatchesKhkTable) with its published,
// shortened tip diameters.
GearPairSpec KhkSpurSpec() {
  GearPairSpec s = SpurSpec(3.0, 12, 24, 0.6, 0.36, 20.0);
  s.pinion.tip_diameter = 44.840 * kMm;
  s.gear.tip_diameter = 79.400 * kMm;
  return s;
}

// Internal pair in the ISO 21771 sign convention from a table in KHK/SDP-SI convention
// (x_ISO = −x_KHK for the ring).
GearPairSpec InternalSpec(double module_mm, int z1, int z2, double x1, double x2_khk) {
  GearPairSpec s = SpurSpec(module_mm, z1, z2, x1, -x2_khk, 10.0);
  s.gear.kind = GearKind::kInternal;
  return s;
}

// Brute force of spec 01 §4.1: contact lines in the plane of action, inclined at β_b, one
// transverse base pitch apart, clipped to the zone (length g_α along the line of action, width b).
// Returns {min, max, mean} of the total length over `samples` phases of one base pitch.
struct LineStats {
  double min, max, mean, max_slope;
};
LineStats BruteForceContactLines(const GearPairGeometry& g, int samples) {
  const double p = g.transverse_base_pitch;
  const double len = g.line_of_action_length;
  const double b = g.face_width;
  const double tb = std::tan(g.base_helix_angle);
  const double cb = std::cos(g.base_helix_angle);
  LineStats st{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
               0.0, 0.0};
  const int kmax = static_cast<int>(std::ceil((len + b * tb) / p)) + 2;
  for (int i = 0; i < samples; ++i) {
    const double phase = p * (static_cast<double>(i) + 0.5) / static_cast<double>(samples);
    double total = 0.0;
    for (int k = -kmax; k <= kmax; ++k) {
      // Line: s(y) = s0 − y tan β_b, y ∈ [0, b]; keep 0 ≤ s ≤ len.
      const double s0 = phase + static_cast<double>(k) * p;
      double y_lo = 0.0;
      double y_hi = b;
      if (tb > 0.0) {
        y_lo = std::max(y_lo, (s0 - len) / tb);
        y_hi = std::min(y_hi, s0 / tb);
      } else if (s0 < 0.0 || s0 > len) {
        y_hi = y_lo;
      }
      total += std::max(0.0, y_hi - y_lo) / cb;
    }
    st.min = std::min(st.min, total);
    st.max = std::max(st.max, total);
    st.mean += total / static_cast<double>(samples);
  }
  // Each line end moves along the zone edge at most at |ds/dphase| / tan β_b; at most
  // 2 (ε_α + ε_β + 2) ends are active, each changing the length at rate 1/(sin β_b).
  const double ends = 2.0 * (g.total_contact_ratio + 2.0);
  st.max_slope = tb > 0.0 ? ends / std::sin(g.base_helix_angle) : 0.0;
  return st;
}

// ---------------------------------------------------------------------------------------------
TEST(GearGeometryTest, KimRigMatchesPublishedRadii) {
  // Kim et al., J. Mech. Sci. Technol. 29(7) 2713–2719, 2015 (spec 03): pitch radius 75 mm,
  // tip 78 mm, base 70.477 mm, root 71.25 mm, centre distance 150 mm.
  const GearPairGeometry g = CalcGearPairGeometry(KimRigSpec());
  for (const GearGeometry* gg : {&g.pinion, &g.gear}) {
    EXPECT_NEAR(gg->reference_radius / kMm, 75.0, PrintedTolerance(3));
    EXPECT_NEAR(gg->tip_radius / kMm, 78.0, PrintedTolerance(3));
    EXPECT_NEAR(gg->base_radius / kMm, 70.477, PrintedTolerance(3));
    EXPECT_NEAR(gg->root_radius / kMm, 71.25, PrintedTolerance(3));
    EXPECT_EQ(gg->hand, HelixHand::kNone);
  }
  // Standard pair at its standard centre distance: α_wt = α_n, zero backlash, r_w = r.
  EXPECT_NEAR(g.operating_pressure_angle, DegToRad(20.0), kRoundOff);
  EXPECT_NEAR(g.zero_backlash_center_distance / kMm, 150.0, kRoundOff);
  EXPECT_NEAR(g.backlash_circumferential / kMm, 0.0, kRoundOff);
  EXPECT_NEAR(g.pinion.operating_pitch_radius / kMm, 75.0, 1e-9);
  // ε_α by the classical angle form (z1 (tan α_a1 − tan α_w) + z2 (tan α_a2 − tan α_w)) / 2π.
  const double alpha_a = std::acos(70.47694655894313 / 78.0);
  const double eps = 2.0 * 50.0 * (std::tan(alpha_a) - std::tan(DegToRad(20.0))) / (2.0 * kPi);
  EXPECT_NEAR(g.transverse_contact_ratio, eps, 1e-12);
  EXPECT_DOUBLE_EQ(g.overlap_contact_ratio, 0.0);
  // Spur contact lines: one or two full-face lines.
  EXPECT_NEAR(g.min_contact_line_length / kMm, 20.0, kRoundOff);
  EXPECT_NEAR(g.max_contact_line_length / kMm, 40.0, kRoundOff);
  EXPECT_NEAR(g.mean_contact_line_length / kMm, 20.0 * eps, 1e-9);
  // Equal tooth counts: the hunting period is one turn.
  EXPECT_EQ(g.teeth_gcd, 50);
  EXPECT_EQ(g.hunting_period_meshes, 50);
  EXPECT_EQ(g.pinion_turns_per_hunting_period, 1);
  EXPECT_EQ(g.gear_turns_per_hunting_period, 1);
}

TEST(GearGeometryTest, ProfileShiftedSpurMatchesKhkTable) {
  // KHK Gear Technical Reference, "profile shifted spur gears" table, reproduced at
  // http://bolsover.com/utilitiesforalibre/profile-shifted-external-spur-gears.html:
  // m 3, α 20°, z 12/24, x 0.6/0.36, working centre distance 56.500 mm →
  // inv α_w = 0.034317, α_w = 26.0888°, d_b = 33.8289/67.6579, d_w = 37.667/75.333,
  // d_a = 44.840/79.400 (tips shortened by y m), d_f = 32.100/66.660, ε_α = 1.202.
  GearPairSpec s = KhkSpurSpec();
  s.center_distance = 56.500 * kMm;
  const GearPairGeometry g = CalcGearPairGeometry(s);
  EXPECT_NEAR(Inv(g.operating_pressure_angle), 0.034317, PrintedTolerance(6));
  EXPECT_NEAR(RadToDeg(g.operating_pressure_angle), 26.0888, PrintedTolerance(4));
  EXPECT_NEAR(2.0 * g.pinion.base_radius / kMm, 33.8289, PrintedTolerance(4));
  EXPECT_NEAR(2.0 * g.gear.base_radius / kMm, 67.6579, PrintedTolerance(4));
  EXPECT_NEAR(2.0 * g.pinion.operating_pitch_radius / kMm, 37.667, PrintedTolerance(3));
  EXPECT_NEAR(2.0 * g.gear.operating_pitch_radius / kMm, 75.333, PrintedTolerance(3));
  EXPECT_NEAR(2.0 * g.pinion.root_radius / kMm, 32.100, PrintedTolerance(3));
  EXPECT_NEAR(2.0 * g.gear.root_radius / kMm, 66.660, PrintedTolerance(3));
  EXPECT_NEAR(g.transverse_contact_ratio, 1.202, PrintedTolerance(3));
  // The zero-backlash centre distance rounds to the table's 56.500 mm; KHK's own table prints
  // α_w = 26.0886° and a = 56.4999 mm for it (values recalled from KHK's printed table).
  EXPECT_NEAR(g.zero_backlash_center_distance / kMm, 56.500, PrintedTolerance(3));
  EXPECT_NEAR(g.zero_backlash_center_distance / kMm, 56.4999, PrintedTolerance(4));
  GearPairSpec s0 = s;
  s0.center_distance.reset();
  const GearPairGeometry g0 = CalcGearPairGeometry(s0);
  EXPECT_NEAR(RadToDeg(g0.operating_pressure_angle), 26.0886, PrintedTolerance(4));
  EXPECT_NEAR(g0.backlash_circumferential, 0.0, 1e-15);
  // 56.5 mm lies above the zero-backlash distance, so the given pair has a small backlash.
  EXPECT_GT(g.backlash_normal, 0.0);
}

TEST(GearGeometryTest, NewtonAgreesWithBisectionForTheWorkingPressureAngle) {
  // inv α_w = inv α + 2 tan α (x1 + x2)/(z1 + z2) solved independently by bisection.
  const GearPairGeometry g = CalcGearPairGeometry(KhkSpurSpec());
  const double alpha = DegToRad(20.0);
  const double v = Inv(alpha) + 2.0 * std::tan(alpha) * 0.96 / 36.0;
  EXPECT_NEAR(g.operating_pressure_angle, InvInvBisect(v), 1e-13);
  EXPECT_NEAR(g.center_distance, 54.0 * kMm * std::cos(alpha) / std::cos(InvInvBisect(v)), 1e-15);
}

TEST(GearGeometryTest, HelicalPairMatchesIso21771WorkedExample) {
  // "Gear Generating Profile Shift Calculations" (ISO 21771:2007 Eq. 62/63 worked sheet,
  // https://www.scribd.com/document/376176518): z 31/30, m_n 3.5 mm, α_n 20°, working centre
  // distance 116.5 mm, reference centre distance 114.3447280708 mm (⇒ β = 21°),
  // α_t = 21.2990642859°, α_wt = 23.8707609654°, inv α_wt = 0.0259052382,
  // Σx = 0.651877131252; normal backlash 0.03 mm ⇒ generating Σx_E = 0.639346541 with pinion
  // x_E1 = 0.2851125484.
  GearPairSpec s = SpurSpec(3.5, 31, 30, 0.291, 0.651877131252 - 0.291, 40.0);
  s.gear.face_width = 38.0 * kMm;
  s.helix_angle = DegToRad(21.0);
  s.pinion_hand = HelixHand::kRight;
  const GearPairGeometry g = CalcGearPairGeometry(s);
  EXPECT_NEAR(g.reference_center_distance / kMm, 114.3447280708, PrintedTolerance(10));
  EXPECT_NEAR(RadToDeg(g.transverse_pressure_angle), 21.2990642859, PrintedTolerance(10));
  EXPECT_NEAR(RadToDeg(g.operating_pressure_angle), 23.8707609654, 2e-9);  // Σx printed to 12
  EXPECT_NEAR(Inv(g.operating_pressure_angle), 0.0259052382, PrintedTolerance(10));
  EXPECT_NEAR(g.zero_backlash_center_distance / kMm, 116.5, 1e-8);
  EXPECT_EQ(g.gear.hand, HelixHand::kLeft);
  // Independent identities: sin β_b = sin β cos α_n; p_bn = p_bt cos β_b; ε_β = b sin β/(π m_n).
  EXPECT_NEAR(std::sin(g.base_helix_angle), std::sin(DegToRad(21.0)) * std::cos(DegToRad(20.0)),
              kRoundOff);
  EXPECT_NEAR(g.normal_base_pitch, g.transverse_base_pitch * std::cos(g.base_helix_angle),
              kRoundOff * kMm);
  EXPECT_NEAR(g.overlap_contact_ratio, 38.0 * std::sin(DegToRad(21.0)) / (kPi * 3.5), kRoundOff);
  EXPECT_NEAR(g.face_width / kMm, 38.0, kRoundOff);

  // Backlash from the generating shifts at a_w = 116.5 mm: j_n = 0.03 mm (the sheet's input).
  GearPairSpec sb = s;
  sb.pinion.profile_shift = 0.2851125484;
  sb.gear.profile_shift = 0.639346541 - 0.2851125484;
  sb.center_distance = 116.5 * kMm;
  const GearPairGeometry gb = CalcGearPairGeometry(sb);
  // Σx_E printed to 9 decimals: |Δj_bn| ≤ 2 m_n sin α_n · 0.5e-9 ≈ 1.2e-9 mm.
  EXPECT_NEAR(gb.backlash_normal / kMm, 0.030, 2e-9);
  EXPECT_NEAR(gb.backlash_normal,
              gb.backlash_circumferential * std::cos(gb.operating_pressure_angle) *
                  std::cos(gb.base_helix_angle),
              kRoundOff * kMm);
}

TEST(GearGeometryTest, HelicalPairMatchesKhkNormalSystemTable) {
  // KHK Gear Technical Reference, "normal system helical gears" calculation table (values as
  // printed there, recalled): m_n 3, α_n 20°, β 30°, z 12/60, x_n 0.09809/0, a = 125 mm →
  // α_t = 22.79588°, α_wt = 23.1126°, d = 41.569/207.846, d_b = 38.322/191.611,
  // d_w = 41.667/208.333.
  GearPairSpec s = SpurSpec(3.0, 12, 60, 0.09809, 0.0, 30.0);
  s.helix_angle = DegToRad(30.0);
  s.pinion_hand = HelixHand::kLeft;
  const GearPairGeometry g = CalcGearPairGeometry(s);
  EXPECT_NEAR(RadToDeg(g.transverse_pressure_angle), 22.79588, PrintedTolerance(5));
  EXPECT_NEAR(RadToDeg(g.operating_pressure_angle), 23.1126, PrintedTolerance(4));
  EXPECT_NEAR(g.zero_backlash_center_distance / kMm, 125.000, PrintedTolerance(3));
  EXPECT_NEAR(2.0 * g.pinion.reference_radius / kMm, 41.569, PrintedTolerance(3));
  EXPECT_NEAR(2.0 * g.gear.reference_radius / kMm, 207.846, PrintedTolerance(3));
  EXPECT_NEAR(2.0 * g.pinion.base_radius / kMm, 38.322, PrintedTolerance(3));
  EXPECT_NEAR(2.0 * g.gear.base_radius / kMm, 191.611, PrintedTolerance(3));
  EXPECT_NEAR(2.0 * g.pinion.operating_pitch_radius / kMm, 41.667, PrintedTolerance(3));
  EXPECT_NEAR(2.0 * g.gear.operating_pitch_radius / kMm, 208.333, PrintedTolerance(3));
  EXPECT_EQ(g.gear.hand, HelixHand::kRight);
}

TEST(GearGeometryTest, InternalPairsMatchSdpSiTable5_4) {
  // SDP/SI "Elements of Metric Gear Technology" (D785) §5.3, Table 5-4
  // (http://www.sdp-si.com/D785/HTML1/D785T043_4.html): internal gear z2 = 50, m = 1, α = 20°,
  // pinion x1 = 0, ring shift x2 (KHK sign) chosen so that neither involute nor trochoid
  // interference occurs; columns z1, x2, α_w, a, ε.
  struct Row {
    int z1;
    double x2_khk, alpha_w_deg, a_mm, eps;
  };
  const Row rows[] = {{49, 1.00, 61.0605, 0.971, 1.105}, {48, 0.60, 46.0324, 1.354, 1.512},
                      {47, 0.40, 37.4155, 1.775, 1.726}, {46, 0.30, 32.4521, 2.227, 1.835},
                      {45, 0.20, 28.2019, 2.666, 1.933}, {44, 0.11, 24.5356, 3.099, 2.014},
                      {43, 0.06, 22.3755, 3.557, 2.053}, {42, 0.01, 20.3854, 4.010, 2.088}};
  for (const Row& row : rows) {
    SCOPED_TRACE(row.z1);
    const GearPairGeometry g = CalcGearPairGeometry(InternalSpec(1.0, row.z1, 50, 0.0, row.x2_khk));
    EXPECT_TRUE(g.internal);
    EXPECT_NEAR(RadToDeg(g.operating_pressure_angle), row.alpha_w_deg, PrintedTolerance(4));
    EXPECT_NEAR(g.center_distance / kMm, row.a_mm, PrintedTolerance(3));
    EXPECT_NEAR(g.transverse_contact_ratio, row.eps, PrintedTolerance(3));
    EXPECT_NEAR(g.backlash_circumferential, 0.0, 1e-15);
    // Internal invariants: r_w2 − r_w1 = a_w, r_w2 / r_w1 = z2 / z1.
    EXPECT_NEAR(g.gear.operating_pitch_radius - g.pinion.operating_pitch_radius, g.center_distance,
                kRoundOff * kMm);
    EXPECT_NEAR(g.gear.operating_pitch_radius / g.pinion.operating_pitch_radius, 50.0 / row.z1,
                kRoundOff);
  }
}

TEST(GearGeometryTest, InternalTrochoidLimitSitsAtTheTabulatedShift) {
  // Same table, row z1 = 44: its x2 = 0.11 clears trochoid interference; the next lower
  // two-decimal shift (0.10) must be rejected, and a standard pair with z2 − z1 = 7 too
  // (the source states standard internal pairs need a tooth-count difference above about 9).
  EXPECT_NO_THROW(CalcGearPairGeometry(InternalSpec(1.0, 44, 50, 0.0, 0.11)));
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(InternalSpec(1.0, 44, 50, 0.0, 0.10)), InvalidInput,
                        "^gear\\.trochoid_interference: .*margin -");
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(InternalSpec(3.0, 53, 60, 0.0, 0.0)), InvalidInput,
                        "^gear\\.trochoid_interference: .*z2 - z1 = 7");
  EXPECT_NO_THROW(CalcGearPairGeometry(InternalSpec(3.0, 50, 60, 0.0, 0.0)));
}

TEST(GearGeometryTest, InternalCentreDistanceMatchesWorkedSheet) {
  // "Centre distance of profile shifted gear calc" sheet (https://scribd.com/doc/92821234):
  // internal pair z1 17, z2 96, m 14, x1 0.20, x2 0.50 (KHK sign), α 20° →
  // working pressure angle 21.1251°, inv α_w = 0.01766871, centre distance 557.0887 mm.
  const GearPairGeometry g = CalcGearPairGeometry(InternalSpec(14.0, 17, 96, 0.2, 0.5));
  EXPECT_NEAR(RadToDeg(g.operating_pressure_angle), 21.1251, PrintedTolerance(4));
  EXPECT_NEAR(Inv(g.operating_pressure_angle), 0.01766871, PrintedTolerance(8));
  EXPECT_NEAR(g.center_distance / kMm, 557.0887, PrintedTolerance(4));
  // Same sheet, external pair z 22/118, m 8, x 0/0.5 → 21.0617°, 563.8999 mm.
  const GearPairGeometry ge = CalcGearPairGeometry(SpurSpec(8.0, 22, 118, 0.0, 0.5, 50.0));
  EXPECT_NEAR(RadToDeg(ge.operating_pressure_angle), 21.0617, PrintedTolerance(4));
  EXPECT_NEAR(ge.center_distance / kMm, 563.8999, PrintedTolerance(4));
}

TEST(GearGeometryTest, BacklashGrowsAsTwiceTheCentreDistanceChangeTimesSinAlpha) {
  // First-order kinematics, independent of the involute-function formulas: separating an
  // external pair by Δa opens a normal backlash j_bn ≈ 2 Δa sin α_wt cos β_b; for an internal
  // pair the centres must come closer by Δa. Truncation O(Δa²/a) → relative tolerance 1e-3.
  const double da = 1e-3 * kMm;
  {
    GearPairSpec s = SpurSpec(2.0, 19, 47, 0.2, -0.1, 20.0);
    s.helix_angle = DegToRad(15.0);
    s.pinion_hand = HelixHand::kRight;
    const GearPairGeometry g0 = CalcGearPairGeometry(s);
    s.center_distance = g0.center_distance + da;
    const GearPairGeometry g = CalcGearPairGeometry(s);
    const double expected =
        2.0 * da * std::sin(g0.operating_pressure_angle) * std::cos(g0.base_helix_angle);
    EXPECT_NEAR(g.backlash_normal / expected, 1.0, 1e-3);
  }
  {
    GearPairSpec s = InternalSpec(2.0, 21, 73, 0.1, 0.2);
    s.helix_angle = DegToRad(12.0);
    s.pinion_hand = HelixHand::kLeft;
    const GearPairGeometry g0 = CalcGearPairGeometry(s);
    EXPECT_EQ(g0.gear.hand, HelixHand::kLeft);  // an internal mate has the same hand
    s.center_distance = g0.center_distance - da;
    const GearPairGeometry g = CalcGearPairGeometry(s);
    const double expected =
        2.0 * da * std::sin(g0.operating_pressure_angle) * std::cos(g0.base_helix_angle);
    EXPECT_NEAR(g.backlash_normal / expected, 1.0, 1e-3);
  }
}

TEST(GearGeometryTest, PathOfContactInvariants) {
  for (const GearPairSpec& s :
       {KimRigSpec(), KhkSpurSpec(), InternalSpec(14.0, 17, 96, 0.2, 0.5)}) {
    const GearPairGeometry g = CalcGearPairGeometry(s);
    // T1A + g_α = T1E, ε_α = g_α / p_bt, pitch point inside the path for these designs.
    EXPECT_NEAR(g.path_start_from_pinion_tangent + g.line_of_action_length,
                g.path_end_from_pinion_tangent, kRoundOff * kMm);
    EXPECT_NEAR(g.transverse_contact_ratio * g.transverse_base_pitch, g.line_of_action_length,
                kRoundOff * kMm);
    EXPECT_GT(g.pitch_point_from_pinion_tangent, g.path_start_from_pinion_tangent);
    EXPECT_LT(g.pitch_point_from_pinion_tangent, g.path_end_from_pinion_tangent);
    EXPECT_NEAR(g.pitch_point_from_pinion_tangent,
                g.pinion.operating_pitch_radius * std::sin(g.operating_pressure_angle),
                kRoundOff * kMm);
    // The mating tip meets each flank between its base and tip circles (the ring: between its
    // tip and its root).
    EXPECT_GE(g.pinion.start_of_active_profile_radius, g.pinion.base_radius);
    EXPECT_LE(g.pinion.start_of_active_profile_radius, g.pinion.operating_pitch_radius);
    if (g.internal) {
      EXPECT_GT(g.gear.start_of_active_profile_radius, g.gear.operating_pitch_radius);
      EXPECT_LT(g.gear.start_of_active_profile_radius, g.gear.root_radius);
    } else {
      EXPECT_GE(g.gear.start_of_active_profile_radius, g.gear.base_radius);
      EXPECT_LE(g.gear.start_of_active_profile_radius, g.gear.operating_pitch_radius);
    }
    // Base circle circumference = z p_bt.
    EXPECT_NEAR(2.0 * kPi * g.pinion.base_radius,
                static_cast<double>(g.pinion.teeth) * g.transverse_base_pitch, kRoundOff * kMm);
  }
}

TEST(GearGeometryTest, TipThicknessMatchesTheStandardToothAtItsTip) {
  // Independent: a standard tooth (x = 0) has half-angle π/(2z) at the reference circle; at the
  // tip its half-angle shrinks by inv α_a − inv α (the involute's polar angle).
  const GearPairGeometry g = CalcGearPairGeometry(KimRigSpec());
  const double alpha_a = std::acos(g.pinion.base_radius / g.pinion.tip_radius);
  const double half_angle = kPi / 100.0 - (Inv(alpha_a) - Inv(DegToRad(20.0)));
  EXPECT_NEAR(g.pinion.tip_thickness_normal, 2.0 * g.pinion.tip_radius * half_angle,
              kRoundOff * kMm);
  EXPECT_NEAR(g.pinion.tooth_thickness_transverse / kMm, 1.5 * kPi, kRoundOff);
}

TEST(GearGeometryTest, HuntingPeriodFacts) {
  const GearPairGeometry a = CalcGearPairGeometry(SpurSpec(2.0, 23, 57, 0.0, 0.0, 10.0));
  EXPECT_EQ(a.teeth_gcd, 1);
  EXPECT_EQ(a.hunting_period_meshes, 23 * 57);
  EXPECT_EQ(a.pinion_turns_per_hunting_period, 57);
  EXPECT_EQ(a.gear_turns_per_hunting_period, 23);
  EXPECT_DOUBLE_EQ(a.gear_ratio, 57.0 / 23.0);
  const GearPairGeometry b = CalcGearPairGeometry(SpurSpec(2.0, 40, 60, 0.0, 0.0, 10.0));
  EXPECT_EQ(b.teeth_gcd, 20);
  EXPECT_EQ(b.hunting_period_meshes, 120);
  EXPECT_EQ(b.pinion_turns_per_hunting_period, 3);
  EXPECT_EQ(b.gear_turns_per_hunting_period, 2);
}

TEST(GearGeometryTest, ContactLineClosedFormsMatchBruteForce) {
  // Helical pairs with fractional and integer overlap ratios, and a spur pair; the brute force
  // samples 20000 phases of one base pitch, so its extremes miss the true ones by at most
  // max_slope × p_bt / 20000 (the total length is piecewise linear in the phase).
  struct Case {
    double beta_deg, b_mm;
  };
  const Case cases[] = {{0.0, 20.0}, {12.0, 20.0}, {20.0, 31.0}, {33.0, 55.0}, {8.0, 7.0}};
  constexpr int kSamples = 20000;
  for (const Case& c : cases) {
    SCOPED_TRACE(c.beta_deg);
    GearPairSpec s = SpurSpec(2.5, 27, 61, 0.15, -0.05, c.b_mm);
    s.helix_angle = DegToRad(c.beta_deg);
    s.pinion_hand = c.beta_deg > 0.0 ? HelixHand::kLeft : HelixHand::kNone;
    const GearPairGeometry g = CalcGearPairGeometry(s);
    const LineStats bf = BruteForceContactLines(g, kSamples);
    const double tol = bf.max_slope * g.transverse_base_pitch / kSamples + 1e-12;
    EXPECT_NEAR(g.min_contact_line_length, bf.min, tol);
    EXPECT_NEAR(g.max_contact_line_length, bf.max, tol);
    // The midpoint rule misses at most one sample width per jump of the spur step function
    // (two jumps per pitch, each one full line b / cos β_b); helical lengths are continuous.
    const double mean_tol = 2.0 * g.face_width / std::cos(g.base_helix_angle) / kSamples + 1e-12;
    EXPECT_NEAR(g.mean_contact_line_length, bf.mean, mean_tol);
  }
}

TEST(GearGeometryTest, IntegerOverlapRatioGivesConstantContactLength) {
  // ε_β = 1 exactly: b = π m_n / sin β. Then min = max = mean = b ε_α / cos β_b.
  GearPairSpec s = SpurSpec(2.5, 27, 61, 0.15, -0.05, 1.0);
  s.helix_angle = DegToRad(20.0);
  s.pinion_hand = HelixHand::kRight;
  s.pinion.face_width = s.gear.face_width = kPi * 2.5 * kMm / std::sin(s.helix_angle);
  const GearPairGeometry g = CalcGearPairGeometry(s);
  EXPECT_NEAR(g.overlap_contact_ratio, 1.0, kRoundOff);
  EXPECT_NEAR(g.min_contact_line_length, g.mean_contact_line_length, 1e-9 * kMm);
  EXPECT_NEAR(g.max_contact_line_length, g.mean_contact_line_length, 1e-9 * kMm);
  const LineStats bf = BruteForceContactLines(g, 2000);
  EXPECT_NEAR(bf.max - bf.min, 0.0, 1e-9 * kMm);
}

// --- Rejections -----------------------------------------------------------------------------
TEST(GearGeometryTest, RejectsBadScalarInputs) {
  GearPairSpec s = KimRigSpec();
  s.pinion.teeth = 0;
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(s), InvalidInput, "^pinion\\.teeth: .*got 0");
  s = KimRigSpec();
  s.gear.teeth = -5;
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(s), InvalidInput, "^gear\\.teeth: .*got -5");
  s = KimRigSpec();
  s.normal_module = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(s), InvalidInput, "^normal_module: ");
  s.normal_module = -3e-3;
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(s), InvalidInput, "^normal_module: ");
  s = KimRigSpec();
  s.gear.face_width = 0.0;
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(s), InvalidInput, "^gear\\.face_width: ");
  s = KimRigSpec();
  s.pinion.face_width = std::numeric_limits<double>::infinity();
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(s), InvalidInput, "^pinion\\.face_width: ");
  s = KimRigSpec();
  s.pinion.profile_shift = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(s), InvalidInput, "^pinion\\.profile_shift: ");
  s = KimRigSpec();
  s.pinion.tip_diameter = -1.0;
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(s), InvalidInput, "^pinion\\.tip_diameter: ");
  s = KimRigSpec();
  s.center_distance = 0.0;
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(s), InvalidInput, "^center_distance: ");
}

TEST(GearGeometryTest, RejectsAnglesAndHandsOutOfRange) {
  GearPairSpec s = KimRigSpec();
  s.normal_pressure_angle = 0.0;
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(s), InvalidInput, "^normal_pressure_angle: .*got 0");
  s.normal_pressure_angle = DegToRad(45.0);
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(s), InvalidInput, "^normal_pressure_angle: .*45");
  s = KimRigSpec();
  s.helix_angle = DegToRad(60.0);
  s.pinion_hand = HelixHand::kRight;
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(s), InvalidInput, "^helix_angle: .*got 60");
  s.helix_angle = -DegToRad(5.0);
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(s), InvalidInput, "^helix_angle: ");
  s = KimRigSpec();
  s.helix_angle = DegToRad(10.0);  // kNone with β > 0
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(s), InvalidInput, "^pinion_hand: kNone given");
  s = KimRigSpec();
  s.pinion_hand = HelixHand::kLeft;  // hand with β = 0
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(s), InvalidInput, "^pinion_hand: a spur pair");
}

TEST(GearGeometryTest, RejectsInternalGearAsPinionOrWithTooFewTeeth) {
  GearPairSpec s = InternalSpec(2.0, 20, 60, 0.0, 0.0);
  s.pinion.kind = GearKind::kInternal;
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(s), InvalidInput, "^pinion\\.kind: ");
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(InternalSpec(2.0, 40, 40, 0.0, 0.0)), InvalidInput,
                        "^gear\\.teeth: .*difference 0");
  // Standard ring with 30 teeth: its tip circle (r − m) lies inside its base circle.
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(InternalSpec(3.0, 12, 30, 0.0, 0.0)), InvalidInput,
                        "^gear\\.tip_radius: .* is not above the base radius .*short by");
  // A large pinion shift against a close ring leaves no zero-backlash centre distance:
  // inv α_wt = inv α − 2 tan α (x1 + x2)/(z2 − z1) < 0.
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(InternalSpec(3.0, 12, 30, 0.5, 0.0)), InvalidInput,
                        "^profile_shift_sum: x1 \\+ x2 = 0\\.5 leaves no zero-backlash");
  // Standard ring with 60 teeth and a 12-tooth pinion: the ring tip meets the pinion below its
  // base circle (involute interference).
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(InternalSpec(3.0, 12, 60, 0.0, 0.0)), InvalidInput,
                        "^gear\\.tip_interference: .*beyond the interference point T1");
}

TEST(GearGeometryTest, RejectsImpossibleCentreDistances) {
  GearPairSpec s = KimRigSpec();
  s.center_distance = 140.0 * kMm;  // below r_b1 + r_b2 = 140.954 mm
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(s), InvalidInput,
                        "^center_distance: 140 mm is not above r_b1 \\+ r_b2 = 140.95.* mm "
                        "\\(short by 0.95");
  s.center_distance = 149.9 * kMm;  // below the zero-backlash 150 mm
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(s), InvalidInput,
                        "^center_distance: 149.9 mm gives negative backlash .*0.1 mm below the "
                        "zero-backlash centre distance 150 mm");
  GearPairSpec si = InternalSpec(14.0, 17, 96, 0.2, 0.5);
  si.center_distance = 558.0 * kMm;  // above the zero-backlash 557.0887 mm
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(si), InvalidInput,
                        "^center_distance: 558 mm gives negative backlash .* above the "
                        "zero-backlash centre distance 557\\.089");
}

// The message of the InvalidInput CalcGearPairGeometry throws, empty if it does not throw.
std::string RejectionOf(const GearPairSpec& s) {
  try {
    (void)CalcGearPairGeometry(s);
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return {};
}

// The number before " mm" that follows `label` in `message` (NaN if absent).
double MmAfter(const std::string& message, const std::string& label) {
  const std::size_t pos = message.find(label);
  if (pos == std::string::npos) return std::numeric_limits<double>::quiet_NaN();
  return std::stod(message.substr(pos + label.size()));
}

// Path of contact of ISO 21771 at centre distance a_w: external
// g_α = ½ (√(d_a1² − d_b1²) + √(d_a2² − d_b2²)) − a_w sin α_wt, internal
// g_α = ½ (√(d_a1² − d_b1²) − √(d_a2² − d_b2²)) + a_w sin α_wt, cos α_wt = (r_b2 ± r_b1) / a_w.
double IsoPathOfContact(double ra1, double rb1, double ra2, double rb2, bool internal, double a_w) {
  const double sigma = internal ? -1.0 : 1.0;
  const double alpha_wt = std::acos((rb2 + sigma * rb1) / a_w);
  return std::sqrt(ra1 * ra1 - rb1 * rb1) + sigma * std::sqrt(ra2 * ra2 - rb2 * rb2) -
         sigma * a_w * std::sin(alpha_wt);
}

TEST(GearGeometryTest, RejectsCentreDistanceWithoutPathOfContact) {
  // External: standard spur pair m 3, z 20/40 (zero backlash at 90 mm). Standard radii:
  // r_b = z m cos α / 2, r_a = (z + 2) m / 2. The path of contact vanishes where
  // a_w sin α_wt = √(a_w² − (r_b1 + r_b2)²) reaches T1E + T2A, i.e. at
  // a_max = √((T1E + T2A)² + (r_b1 + r_b2)²).
  const double alpha = DegToRad(20.0);
  const double rb1 = 30.0 * kMm * std::cos(alpha);
  const double rb2 = 60.0 * kMm * std::cos(alpha);
  const double ra1 = 33.0 * kMm;
  const double ra2 = 63.0 * kMm;
  const double a_max =
      std::hypot(std::sqrt(ra1 * ra1 - rb1 * rb1) + std::sqrt(ra2 * ra2 - rb2 * rb2), rb1 + rb2);
  EXPECT_NEAR(a_max / kMm, 95.92, 0.01);
  EXPECT_NEAR(IsoPathOfContact(ra1, rb1, ra2, rb2, false, a_max), 0.0, 1e-15);
  EXPECT_GT(IsoPathOfContact(ra1, rb1, ra2, rb2, false, a_max * (1.0 - 1e-6)), 0.0);

  GearPairSpec s = SpurSpec(3.0, 20, 40, 0.0, 0.0, 20.0);
  s.center_distance = a_max * (1.0 - 1e-6);  // a sliver of contact: too short, but not this check
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(s), InvalidInput,
                        "^transverse_contact_ratio: [0-9.e-]+ is below 1");
  s.center_distance = a_max * (1.0 + 1e-6);
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(s), InvalidInput,
                        "^center_distance: 95\\.9.* mm exceeds the largest centre distance with a "
                        "positive path of contact, 95\\.9.* mm, by 9.*e-05 mm \\(the tips no "
                        "longer overlap along the line of action: g_α = -");
  s.center_distance = a_max + 2.0 * kMm;
  std::string message = RejectionOf(s);
  EXPECT_EQ(message.rfind("center_distance: ", 0), 0u) << message;
  EXPECT_NEAR(MmAfter(message, "positive path of contact, "), a_max / kMm, 1e-4);
  EXPECT_NEAR(MmAfter(message, ", by "), 2.0, 1e-5);

  // Internal: the SDP/SI pair m 14, z 17/96 (zero backlash at 557.0887 mm). Withdrawing the pinion
  // shortens the path, g_α = T1E − T2A + T1T2, which vanishes at
  // a_min = √((T2A − T1E)² + (r_b2 − r_b1)²) (T2A > T1E here).
  const GearPairSpec si0 = InternalSpec(14.0, 17, 96, 0.2, 0.5);
  const double m = 14.0 * kMm;
  const double rbi1 = 0.5 * 17.0 * m * std::cos(alpha);
  const double rbi2 = 0.5 * 96.0 * m * std::cos(alpha);
  const double rai1 = 0.5 * 17.0 * m + m * (1.0 + 0.2);  // external tip: r + m (h_a* + x)
  const double rai2 = 0.5 * 96.0 * m - m * (1.0 - 0.5);  // ring tip: r − m (h_a* + x_ISO)
  const double t2a = std::sqrt(rai2 * rai2 - rbi2 * rbi2);
  const double t1e = std::sqrt(rai1 * rai1 - rbi1 * rbi1);
  ASSERT_GT(t2a, t1e);
  const double a_min = std::hypot(t2a - t1e, rbi2 - rbi1);
  EXPECT_GT(a_min, rbi2 - rbi1);
  EXPECT_NEAR(IsoPathOfContact(rai1, rbi1, rai2, rbi2, true, a_min), 0.0, 1e-14);
  EXPECT_GT(IsoPathOfContact(rai1, rbi1, rai2, rbi2, true, a_min * (1.0 + 1e-6)), 0.0);

  GearPairSpec si = si0;
  si.center_distance = a_min * (1.0 + 1e-6);
  message = RejectionOf(si);
  EXPECT_NE(message.rfind("center_distance", 0), 0u) << message;
  si.center_distance = a_min - 1.0 * kMm;
  message = RejectionOf(si);
  EXPECT_EQ(message.rfind("center_distance: ", 0), 0u) << message;
  EXPECT_NE(message.find(" is below the smallest centre distance with a positive path of contact"),
            std::string::npos)
      << message;
  EXPECT_NEAR(MmAfter(message, "positive path of contact, "), a_min / kMm, 1e-3);
  EXPECT_NEAR(MmAfter(message, ", by "), 1.0, 1e-5);
  // Without a given centre distance the pair runs at its zero-backlash distance, with contact.
  EXPECT_NO_THROW(CalcGearPairGeometry(si0));
}

TEST(GearGeometryTest, RejectsShortContactRatioAndInterference) {
  GearPairSpec s = KimRigSpec();
  s.pinion.tip_diameter = s.gear.tip_diameter = 153.0 * kMm;  // ε_α ≈ 0.93
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(s), InvalidInput,
                        "^transverse_contact_ratio: 0\\.9[0-9]* is below 1 \\(short by 0\\.0");
  // 14-tooth standard pinion against a 100-tooth standard gear: the gear tip reaches below the
  // pinion's base circle (classical limit z1 ≥ 17 for a rack-like mate).
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(SpurSpec(3.0, 14, 100, 0.0, 0.0, 20.0)), InvalidInput,
                        "^gear\\.tip_interference: ");
  // Mirror: a 100-tooth driver with a 14-tooth driven gear: the pinion tip passes T2.
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(SpurSpec(3.0, 100, 14, 0.0, 0.0, 20.0)), InvalidInput,
                        "^pinion\\.tip_interference: ");
}

TEST(GearGeometryTest, RejectsUndercut) {
  // 14 standard teeth against 14: no tip interference, but the generating rack undercuts:
  // x_min = 1.25 − 0.38 (1 − sin 20°) − 14 sin² 20° / 2 = 0.1812.
  const double x_min = 1.25 - 0.38 * (1.0 - std::sin(DegToRad(20.0))) -
                       14.0 * std::pow(std::sin(DegToRad(20.0)), 2) / 2.0;
  EXPECT_NEAR(x_min, 0.1812, 1e-4);
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(SpurSpec(3.0, 14, 14, 0.0, 0.0, 20.0)), InvalidInput,
                        "^pinion\\.undercut: x = 0 is below the undercut limit x_min = 0\\.181.* "
                        "for z = 14 \\(short by 0\\.181");
  EXPECT_NO_THROW(CalcGearPairGeometry(SpurSpec(3.0, 14, 14, x_min + 1e-9, x_min + 1e-9, 20.0)));
}

TEST(GearGeometryTest, RejectsThinTipsAndBadRadii) {
  GearPairSpec s = KimRigSpec();
  s.min_tip_thickness_factor = 0.8;  // the standard 50-tooth tip is 2.33 mm = 0.78 m_n thick
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(s), InvalidInput,
                        "^pinion\\.tip_thickness_normal: 2\\.32.* mm is below "
                        "min_tip_thickness_factor \\* m_n = 2\\.4 mm \\(short by 0\\.07");
  // A pointed tooth: z 10, x 1.0 with the default tip rule.
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(SpurSpec(3.0, 10, 40, 1.0, 0.0, 20.0)), InvalidInput,
                        "^pinion\\.tip_thickness_normal: ");
  s = KimRigSpec();
  s.pinion.tip_diameter = 140.0 * kMm;  // below the base diameter 140.954 mm
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(s), InvalidInput,
                        "^pinion\\.tip_radius: 70 mm is not above the base radius 70\\.47");
  s = KimRigSpec();
  s.pinion.teeth = 3;
  s.pinion.dedendum_coefficient = 2.0;  // r_f = 4.5 − 6 mm < 0
  s.center_distance.reset();
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(s), InvalidInput,
                        "^pinion\\.root_radius: -1\\.5 mm is not positive");
  s = KimRigSpec();
  s.pinion.tip_diameter = 158.0 * kMm;  // 1 mm longer than standard, clearance is 0.75 mm
  EXPECT_THROWS_MESSAGE(CalcGearPairGeometry(s), InvalidInput,
                        "^pinion\\.tip_clearance: the pinion tip reaches 0\\.25 mm past");
}

}  // namespace
}  // namespace geardyn
