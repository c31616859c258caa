#include "geardyn/models/contact/contact_presearch.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <numbers>
#include <random>

#include "geardyn/models/contact/mesh_kinematics.hpp"
#include "support/contact_pairs.hpp"

namespace geardyn {
namespace {

// On random poses (random phase, centre and tilt offsets, both sides), every tooth pair that an
// all-pairs search finds in or near contact (valid, δ > −20 µm) is among the pre-search's
// candidates, and the candidates are few (O(1), not O(z1·z2)).
TEST(ContactPresearchTest, FindsEveryPairTheAllPairsSearchFinds) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const GearPairSpec& spec :
       {test::KimRigPair(150.2), test::UnequalSpurPair(), test::HelicalPair()}) {
    const auto s = test::MakeContactPair(spec);
    const ContactMeshKinematics kin(s.pair, s.frame, s.pinion, s.gear, 2);
    const int z1 = s.pair.pinion.teeth, z2 = s.pair.gear.teeth;
    int found = 0;
    for (int trial = 0; trial < 40; ++trial) {
      Vector12 q;
      for (int i = 0; i < 12; ++i) q(i) = (i % 6 < 3 ? 2e-5 : 2e-4) * u(rng);
      const double theta = 2 * std::numbers::pi * 60 * (u(rng) + 1.0);
      for (int slice = 0; slice < 2; ++slice) {
        const auto [p1, p2] = kin.SlicePoses(q, theta, slice);
        std::array<ToothPairCandidate, 64> buf;
        const double gap = 2e-5;
        const int n = FindCandidatePairs(s.pinion, p1.layout, s.gear, p2.layout,
                                         2 * gap / s.pinion.base_radius, buf);
        ASSERT_LE(n, 36);  // ≤ 6 teeth per window on these pairs (z ≤ 50)
        for (int i1 = 0; i1 < z1; ++i1) {
          for (int i2 = 0; i2 < z2; ++i2) {
            for (FlankSide side : {FlankSide::kDrive, FlankSide::kCoast}) {
              const SliceToothContact c = kin.EvalToothPair(q, theta, slice, i1, i2, side);
              if (!c.transverse.found || !c.transverse.valid || c.penetration < -gap) continue;
              ++found;
              EXPECT_TRUE(
                  std::any_of(buf.begin(), buf.begin() + n,
                              [&](const auto& p) { return p.tooth1 == i1 && p.tooth2 == i2; }))
                  << "pair " << i1 << "/" << i2;
            }
          }
        }
      }
    }
    EXPECT_GT(found, 40);
  }
}

TEST(ContactPresearchTest, NoCandidatesWhenTheTipCirclesDoNotOverlap) {
  const auto s = test::MakeContactPair(test::UnequalSpurPair());
  ToothLayout a, b;
  b.center = Vector2(s.pinion.tip_radius + s.gear.tip_radius + 1e-6, 0.0);
  std::array<ToothPairCandidate, 4> buf;
  EXPECT_EQ(FindCandidatePairs(s.pinion, a, s.gear, b, 0.0, buf), 0);
}

}  // namespace
}  // namespace geardyn
