// Interference within the rounding of printed profile shifts: CalcGearPairGeometry accepts a
// given centre distance whose flanks interfere by at most what a profile-shift sum too large by
// 1e-4 causes (two shifts printed to 4 decimals), as zero backlash with a warning, and rejects
// more.
//
// Independent truth: at a fixed centre distance a change Δx of a profile shift changes the
// normal backlash by exactly −2 m_n sin α_n Δx (ISO 21771: the tooth thickness grows by
// 2 x m_n tan α_n in the normal section, projected onto the line of action). The tests step x
// across the tolerance from a pair run at its own zero-backlash centre distance.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "geardyn/common/errors.hpp"
#include "geardyn/common/units.hpp"
#include "geardyn/models/gear/gear_geometry.hpp"
#include "support/expect_throws.hpp"
#include "support/published_stages.hpp"

namespace geardyn {
namespace {

using test::NrelParallelStage;

constexpr double kMm = 1e-3;
constexpr double kShiftTolerance = 1e-4;  // the documented bound on x1 + x2 rounding
// j_bn is a difference of O(m_n) thicknesses: round-off ~1e-15 m_n relative to 1e-4 m_n.
constexpr double kRelTol = 1e-8;

TEST(BacklashToleranceTest, PublishedStageWithRoundedShiftsIsAcceptedWithAWarning) {
  const GearPairGeometry g = CalcGearPairGeometry(NrelParallelStage());
  EXPECT_EQ(g.backlash_circumferential, 0.0);
  EXPECT_EQ(g.backlash_normal, 0.0);
  // The interference is what the shifts' rounding explains: below 2 m_n sin α_n · 1e-4.
  EXPECT_GT(g.interference_normal, 0.0);
  EXPECT_LT(g.interference_normal, 2.0 * 14.0 * kMm * std::sin(DegToRad(20.0)) * kShiftTolerance);
  ASSERT_EQ(g.warnings.size(), 1u);
  EXPECT_NE(g.warnings[0].find("center_distance: 861 mm gives negative backlash"),
            std::string::npos)
      << g.warnings[0];
  EXPECT_NE(g.warnings[0].find("taken as zero backlash"), std::string::npos) << g.warnings[0];
  // KISSsoft's printed working transverse pressure angle 22.856° (the flanks close at 861 mm).
  EXPECT_NEAR(RadToDeg(g.operating_pressure_angle), 22.856, 0.0005);
}

// A pair at its own zero-backlash centre distance with x2 then raised by Δx.
GearPairGeometry ShiftedAtFixedCentreDistance(GearPairSpec s, double dx) {
  s.center_distance.reset();
  s.center_distance = CalcGearPairGeometry(s).zero_backlash_center_distance;
  s.gear.profile_shift += dx;
  return CalcGearPairGeometry(s);
}

TEST(BacklashToleranceTest, EdgeOfTheToleranceExternalPair) {
  GearPairSpec s = NrelParallelStage();
  const double jbn_per_dx = 2.0 * s.normal_module * std::sin(s.normal_pressure_angle);
  // Just below the tolerance: zero backlash, the interference −Δj_bn = 2 m_n sin α_n Δx.
  const double below = 0.99 * kShiftTolerance;
  const GearPairGeometry g = ShiftedAtFixedCentreDistance(s, below);
  EXPECT_EQ(g.backlash_normal, 0.0);
  EXPECT_NEAR(g.interference_normal, jbn_per_dx * below, kRelTol * jbn_per_dx * below);
  ASSERT_EQ(g.warnings.size(), 1u);
  // Just above: the error, saying by how much.
  EXPECT_THROWS_MESSAGE(ShiftedAtFixedCentreDistance(s, 1.01 * kShiftTolerance), InvalidInput,
                        "^center_distance: .* gives negative backlash .*as if x1 \\+ x2 were "
                        "0\\.000101.* too large.*more than the 0\\.0001");
  // A pair without interference has no warning and no interference.
  const GearPairGeometry clear = ShiftedAtFixedCentreDistance(s, -below);
  EXPECT_TRUE(clear.warnings.empty());
  EXPECT_EQ(clear.interference_normal, 0.0);
  EXPECT_NEAR(clear.backlash_normal, jbn_per_dx * below, kRelTol * jbn_per_dx * below);
}

TEST(BacklashToleranceTest, EdgeOfTheToleranceInternalPair) {
  // Spur ring pair (x2 in the ISO sign, positive thickens the ring's teeth).
  GearPairSpec s;
  s.normal_module = 14.0 * kMm;
  s.normal_pressure_angle = DegToRad(20.0);
  s.pinion.teeth = 17;
  s.gear.teeth = 96;
  s.gear.kind = GearKind::kInternal;
  s.pinion.profile_shift = 0.2;
  s.gear.profile_shift = 0.5;
  s.pinion.face_width = 100.0 * kMm;
  s.gear.face_width = 100.0 * kMm;
  const double jbn_per_dx = 2.0 * s.normal_module * std::sin(s.normal_pressure_angle);
  const double below = 0.99 * kShiftTolerance;
  const GearPairGeometry g = ShiftedAtFixedCentreDistance(s, below);
  EXPECT_EQ(g.backlash_normal, 0.0);
  EXPECT_NEAR(g.interference_normal, jbn_per_dx * below, kRelTol * jbn_per_dx * below);
  EXPECT_THROWS_MESSAGE(ShiftedAtFixedCentreDistance(s, 1.01 * kShiftTolerance), InvalidInput,
                        "^center_distance: .* gives negative backlash .* above the zero-backlash");
}

}  // namespace
}  // namespace geardyn
