#include "geardyn/models/contact/flank_relief.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "geardyn/models/mesh/contact_lines.hpp"
#include "support/contact_pairs.hpp"

namespace geardyn {
namespace {

// On the rigid pair (ρ2 = T1T2 − ρ1) the per-flank values add up to UnloadedSeparation's profile
// separation at x = ρ1 − T1C, and the slopes match central differences.
TEST(FlankModificationsTest, AgreesWithUnloadedSeparationOnTheRigidPair) {
  const auto s = test::MakeContactPair(test::UnequalSpurPair());
  ToothModifications m;
  m.pinion_tip_relief = {12e-6, 3e-3, ReliefShape::kLinear};
  m.gear_tip_relief = {8e-6, 2.5e-3, ReliefShape::kParabolic};
  m.pinion_root_relief = {3e-6, 2e-3, ReliefShape::kParabolic};
  m.gear_root_relief = {4e-6, 1.5e-3, ReliefShape::kLinear};
  m.lead_crowning = 6e-6;
  m.lead_slope = 2e-6;
  const FlankModifications mods(s.pair, m);
  const UnloadedSeparation truth(MakeZoneOfAction(s.pair, 1), m);
  const double t1c = s.pair.pitch_point_from_pinion_tangent;
  const double t1t2 = (s.pair.pinion.base_radius + s.pair.gear.base_radius) *
                      std::tan(s.pair.operating_pressure_angle);
  for (int k = 0; k <= 200; ++k) {
    const double x = truth.path_start() + (truth.path_end() - truth.path_start()) * (k + 0.3) / 201;
    const double rho1 = x + t1c, rho2 = t1t2 - rho1;
    EXPECT_NEAR(mods.Pinion(false, rho1).value + mods.Gear(false, rho2).value,
                truth.ProfileSeparation(x), 1e-18);
    const double h = 1e-9;
    EXPECT_NEAR(mods.Pinion(false, rho1).slope,
                (mods.Pinion(false, rho1 + h).value - mods.Pinion(false, rho1 - h).value) / (2 * h),
                1e-6);
    EXPECT_NEAR(mods.Gear(false, rho2).slope,
                (mods.Gear(false, rho2 + h).value - mods.Gear(false, rho2 - h).value) / (2 * h),
                1e-6);
    EXPECT_EQ(mods.Pinion(true, rho1).value, 0.0);  // coast flanks unmodified by default
  }
  for (double y : {-0.0125, -0.004, 0.0, 0.009}) {
    EXPECT_NEAR(mods.Lead(false, y), truth.LeadSeparation(y), 1e-18);
  }
}

}  // namespace
}  // namespace geardyn
