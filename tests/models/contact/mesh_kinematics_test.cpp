#include "geardyn/models/contact/mesh_kinematics.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "geardyn/common/errors.hpp"
#include "geardyn/models/contact/contact_presearch.hpp"
#include "geardyn/models/mesh/contact_lines.hpp"
#include "geardyn/models/mesh/mesh_jacobian.hpp"
#include "geardyn/models/mesh/tooth_modifications.hpp"
#include "support/contact_pairs.hpp"
#include "support/expect_throws.hpp"

namespace geardyn {
namespace {

using test::ContactPairSetup;
using test::MakeContactPair;

constexpr double kPi = std::numbers::pi;
// Penetrations are differences of lengths of ~0.1 m computed through atan2 and √: a few ulps.
constexpr double kLengthTol = 1e-12;  // [m]

struct PairContact {
  int tooth1, tooth2;
  SliceToothContact c;
};

// All valid contacts of one side in one slice, from the pre-search candidates: flank–flank ones
// only, or also tip-corner ones (pairs beyond the ends of the path, usually open).
std::vector<PairContact> ValidContacts(const ContactMeshKinematics& kin, const Vector12& q,
                                       double theta, int slice, FlankSide side,
                                       bool corners = false) {
  const auto [p1, p2] = kin.SlicePoses(q, theta, slice);
  std::array<ToothPairCandidate, 64> buf;
  const int n = FindCandidatePairs(kin.pinion(), p1.layout, kin.gear(), p2.layout, 0.05, buf);
  EXPECT_LE(n, 64);
  std::vector<PairContact> out;
  for (int k = 0; k < std::min(n, 64); ++k) {
    SliceToothContact c = kin.EvalToothPair(q, theta, slice, buf[k].tooth1, buf[k].tooth2, side);
    if (c.transverse.found && c.transverse.valid && (corners || c.transverse.corner == 0)) {
      out.push_back({buf[k].tooth1, buf[k].tooth2, c});
    }
  }
  return out;
}

double MaxPenetration(const std::vector<PairContact>& contacts) {
  double m = -std::numeric_limits<double>::infinity();
  for (const auto& c : contacts) m = std::max(m, c.c.penetration);
  return m;
}

class LawOfGearingTest : public ::testing::TestWithParam<int> {};

// Rigid perfect involutes, no load: over a whole mesh cycle (and the hand-over between pairs)
// every drive pair in contact has zero penetration (the law of gearing: the no-load TE is 0), and
// the pairs in contact are exactly the mesh cycles n whose roll x_n = (θ/2π − n) p_bt lies on the
// path of contact, pinion tooth n mod z1 with gear tooth n mod z2 (tooth_modifications.hpp).
TEST_P(LawOfGearingTest, ZeroTransmissionErrorAndTheRightPairsOverACycle) {
  const int which = GetParam();
  const GearPairSpec spec = which == 0   ? test::KimRigPair()
                            : which == 1 ? test::UnequalSpurPair()
                                         : test::HelicalPair();
  for (int drive_sign : {1, -1}) {
    const ContactPairSetup s = MakeContactPair(spec, drive_sign);
    const ContactMeshKinematics kin(s.pair, s.frame, s.pinion, s.gear, 3);
    const double pbt = s.pair.transverse_base_pitch;
    const double x_s =
        s.pair.path_start_from_pinion_tangent - s.pair.pitch_point_from_pinion_tangent;
    const double x_e = s.pair.path_end_from_pinion_tangent - s.pair.pitch_point_from_pinion_tangent;
    const int z1 = s.pair.pinion.teeth, z2 = s.pair.gear.teeth;
    const Vector12 q = Vector12::Zero();
    for (int k = 0; k < 97; ++k) {
      const double theta = 2 * kPi * (7.0 + (k + 0.5) / 97.0);  // cycles 7–8 (teeth wrap)
      for (int slice = 0; slice < 3; ++slice) {
        const auto contacts = ValidContacts(kin, q, theta, slice, FlankSide::kDrive);
        ASSERT_FALSE(contacts.empty());
        for (const auto& c : contacts) {
          EXPECT_NEAR(c.c.penetration, 0.0, kLengthTol) << "theta " << theta;
        }
        // Expected pairs: in slice y the transverse section is the mid-face one turned by the
        // helix, f1 y, which moves the pinion's flanks along the path by s f1 y r_b1.
        const double y = kin.slice_position(slice);
        const double helix_shift = s.pinion.helix_factor * y * s.pair.pinion.base_radius;
        int expected = 0;
        for (int n = 0; n < 20; ++n) {
          const double x = (theta / (2 * kPi) - n) * pbt + drive_sign * helix_shift;
          if (x <= x_s || x >= x_e) continue;
          ++expected;
          const auto it = std::find_if(contacts.begin(), contacts.end(), [&](const PairContact& c) {
            return c.tooth1 == n % z1 && c.tooth2 == n % z2;
          });
          ASSERT_NE(it, contacts.end()) << "cycle " << n << " theta " << theta;
          EXPECT_NEAR(it->c.transverse.roll1, x + s.pair.pitch_point_from_pinion_tangent,
                      kLengthTol);
        }
        EXPECT_EQ(static_cast<int>(contacts.size()), expected) << "theta " << theta;
        // Tip corners of the pairs outside the path never interfere (they are open).
        for (const auto& c : ValidContacts(kin, q, theta, slice, FlankSide::kDrive, true)) {
          EXPECT_LE(c.c.penetration, kLengthTol);
        }
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Pairs, LawOfGearingTest, ::testing::Values(0, 1, 2));

// The fraction of a mesh cycle with two pairs in zero-gap contact is ε_α − 1 (spur pairs).
TEST(ContactMeshKinematicsTest, TwoPairFractionEqualsContactRatioMinusOne) {
  for (const GearPairSpec& spec : {test::KimRigPair(), test::UnequalSpurPair()}) {
    const ContactPairSetup s = MakeContactPair(spec);
    const ContactMeshKinematics kin(s.pair, s.frame, s.pinion, s.gear, 1);
    constexpr int kSamples = 2000;
    int two = 0;
    for (int k = 0; k < kSamples; ++k) {
      const double theta = 2 * kPi * (3.0 + (k + 0.5) / kSamples);
      const auto contacts = ValidContacts(kin, Vector12::Zero(), theta, 0, FlankSide::kDrive);
      ASSERT_GE(contacts.size(), 1u);
      ASSERT_LE(contacts.size(), 2u);
      if (contacts.size() == 2) ++two;
    }
    // Sampling resolves the fraction to 1/kSamples at each of the two hand-overs.
    EXPECT_NEAR(static_cast<double>(two) / kSamples, s.pair.transverse_contact_ratio - 1.0,
                2.0 / kSamples);
  }
}

// With tip and root relief the unloaded TE (the smallest gap over the pairs in contact) equals
// the relief in closed form: min over the lines on the path of UnloadedSeparation's profile
// separation at their roll positions x_n = (θ/2π − n) p_bt.
TEST(ContactMeshKinematicsTest, UnloadedTransmissionErrorEqualsTipRelief) {
  const ContactPairSetup s = MakeContactPair(test::UnequalSpurPair());
  ToothModifications m;
  // Bands longer than the two-pair zones (≈ 4.4 mm), so the relief shows in the TE.
  m.pinion_tip_relief = {12e-6, 5.5e-3, ReliefShape::kLinear};
  m.gear_tip_relief = {8e-6, 5.0e-3, ReliefShape::kParabolic};
  m.pinion_root_relief = {3e-6, 6.0e-3, ReliefShape::kParabolic};
  const ContactMeshKinematics kin(s.pair, s.frame, s.pinion, s.gear, 1,
                                  FlankModifications(s.pair, m));
  const UnloadedSeparation truth(MakeZoneOfAction(s.pair, 1), m);
  const double pbt = s.pair.transverse_base_pitch;
  double largest = 0.0;
  for (int k = 0; k < 211; ++k) {
    const double theta = 2 * kPi * (5.0 + (k + 0.37) / 211.0);
    const auto contacts =
        ValidContacts(kin, Vector12::Zero(), theta, 0, FlankSide::kDrive, /*corners=*/true);
    ASSERT_FALSE(contacts.empty());
    const double te = -MaxPenetration(contacts);
    double expected = std::numeric_limits<double>::infinity();
    for (int n = 0; n < 12; ++n) {
      const double x = (theta / (2 * kPi) - n) * pbt;
      if (x > truth.path_start() && x < truth.path_end()) {
        expected = std::min(expected, truth.ProfileSeparation(x));
      }
    }
    EXPECT_NEAR(te, expected, 1e-12) << "theta " << theta;
    largest = std::max(largest, te);
  }
  EXPECT_GT(largest, 1e-6);  // the relief was actually seen
}

// Backlash: turning the pinion back from drive contact, the coast flanks touch after exactly the
// normal backlash j_bn of GearPairGeometry, i.e. a pinion rotation j_bn / (r_b1 cos β_b).
TEST(ContactMeshKinematicsTest, CoastFlanksCloseAfterTheBacklash) {
  for (const GearPairSpec& spec :
       {test::KimRigPair(150.2), test::UnequalSpurPair(), test::HelicalPair()}) {
    for (int drive_sign : {1, -1}) {
      const ContactPairSetup s = MakeContactPair(spec, drive_sign);
      ASSERT_GT(s.pair.backlash_normal, 1e-5);
      const ContactMeshKinematics kin(s.pair, s.frame, s.pinion, s.gear, 1);
      for (double theta : {0.3, 2.1, 4.4}) {
        // Coast penetration as a function of the pinion's turning back by β (against s).
        auto coast = [&](double back) {
          Vector12 q = Vector12::Zero();
          q(5) = -drive_sign * back;
          return MaxPenetration(ValidContacts(kin, q, theta, 0, FlankSide::kCoast, true));
        };
        double lo = 0.0, hi = 0.05;
        ASSERT_LT(coast(lo), 0.0);
        ASSERT_GT(coast(hi), 0.0);
        for (int it = 0; it < 80; ++it) {
          const double mid = 0.5 * (lo + hi);
          (coast(mid) > 0.0 ? hi : lo) = mid;
        }
        const double expected = s.pair.backlash_normal /
                                (s.pair.pinion.base_radius * std::cos(s.pair.base_helix_angle));
        EXPECT_NEAR(lo, expected, 1e-10 * expected + 1e-15) << "theta " << theta;
        // And the drive flanks open by the same amount: still zero at the start.
        EXPECT_NEAR(
            MaxPenetration(ValidContacts(kin, Vector12::Zero(), theta, 0, FlankSide::kDrive)), 0.0,
            kLengthTol);
      }
    }
  }
}

// Central finite differences of δ_n (with relief, helical, at a displaced state) against the
// closed-form gradient, for the 12 body coordinates and the phase.
TEST(ContactMeshKinematicsTest, PenetrationGradientMatchesFiniteDifferences) {
  for (const GearPairSpec& spec : {test::UnequalSpurPair(), test::HelicalPair()}) {
    const ContactPairSetup s = MakeContactPair(spec, -1);
    ToothModifications m;
    m.pinion_tip_relief = {10e-6, 2.0e-3, ReliefShape::kParabolic};
    m.gear_tip_relief = {10e-6, 2.0e-3, ReliefShape::kParabolic};
    m.lead_crowning = 5e-6;
    const ContactMeshKinematics kin(s.pair, s.frame, s.pinion, s.gear, 4,
                                    FlankModifications(s.pair, m));
    Vector12 q;
    q << 3e-6, -2e-6, 4e-6, 1e-5, -2e-5, 3e-5, -1e-6, 2e-6, -3e-6, -1e-5, 1.5e-5, -2e-5;
    const double theta = 2 * kPi * 4.3;
    int checked = 0;
    for (int slice = 0; slice < 4; ++slice) {
      for (const auto& c : ValidContacts(kin, q, theta, slice, FlankSide::kDrive)) {
        const double h = 1e-7;
        Vector12 fd;
        for (int i = 0; i < 12; ++i) {
          Vector12 qp = q, qm = q;
          qp(i) += h;
          qm(i) -= h;
          fd(i) = (kin.EvalToothPair(qp, theta, slice, c.tooth1, c.tooth2, FlankSide::kDrive)
                       .penetration -
                   kin.EvalToothPair(qm, theta, slice, c.tooth1, c.tooth2, FlankSide::kDrive)
                       .penetration) /
                  (2 * h);
        }
        // Central differences with h = 1e-7 on lengths of 0.1 m: ~1e-8 relative.
        EXPECT_LT((fd - c.c.d_penetration).norm(), 1e-7 * c.c.d_penetration.norm())
            << fd.transpose() << "\n"
            << c.c.d_penetration.transpose();
        const double ht = 1e-6;
        const double fdt =
            (kin.EvalToothPair(q, theta + ht, slice, c.tooth1, c.tooth2, FlankSide::kDrive)
                 .penetration -
             kin.EvalToothPair(q, theta - ht, slice, c.tooth1, c.tooth2, FlankSide::kDrive)
                 .penetration) /
            (2 * ht);
        EXPECT_NEAR(fdt, c.c.d_penetration_d_phase,
                    1e-6 * s.pair.pinion.base_radius / s.pair.pinion.teeth);
        ++checked;
      }
    }
    EXPECT_GT(checked, 3);
  }
}

// THE B–S LINK: at q = 0 the derivative of every contact's δ_n with respect to the 12 body
// coordinates (central differences of the full kinematics + kernel) equals [1, −σ] G with
// G = CalcMeshJacobian(frame) and σ = (P − p0)·σ̂, for spur and helical pairs, both hands and
// both drive directions.
TEST(ContactMeshKinematicsTest, GradientIsTheBlankenshipSinghInterface) {
  for (const GearPairSpec& spec : {test::UnequalSpurPair(), test::HelicalPair(HelixHand::kRight),
                                   test::HelicalPair(HelixHand::kLeft)}) {
    for (int drive_sign : {1, -1}) {
      const ContactPairSetup s = MakeContactPair(spec, drive_sign);
      const ContactMeshKinematics kin(s.pair, s.frame, s.pinion, s.gear, 5);
      const Matrix2x12 G = CalcMeshJacobian(s.frame);
      int checked = 0;
      for (double theta : {0.2, 1.7, 3.9, 5.5}) {
        for (int slice = 0; slice < 5; ++slice) {
          for (const auto& c :
               ValidContacts(kin, Vector12::Zero(), theta, slice, FlankSide::kDrive)) {
            Vector12 fd;
            const double h = 1e-7;
            for (int i = 0; i < 12; ++i) {
              Vector12 qp = Vector12::Zero(), qm = Vector12::Zero();
              qp(i) = h;
              qm(i) = -h;
              fd(i) = (kin.EvalToothPair(qp, theta, slice, c.tooth1, c.tooth2, FlankSide::kDrive)
                           .penetration -
                       kin.EvalToothPair(qm, theta, slice, c.tooth1, c.tooth2, FlankSide::kDrive)
                           .penetration) /
                      (2 * h);
            }
            const Vector12 bs = (G.row(0) - c.c.sigma * G.row(1)).transpose();
            EXPECT_LT((fd - bs).norm(), 1e-7 * bs.norm())
                << "fd " << fd.transpose() << "\nbs " << bs.transpose();
            EXPECT_LT((c.c.d_penetration - bs).norm(), 1e-12 * bs.norm());
            ++checked;
          }
        }
      }
      EXPECT_GT(checked, 20);
    }
  }
}

TEST(ContactMeshKinematicsTest, RejectsBadInput) {
  const ContactPairSetup s = MakeContactPair(test::UnequalSpurPair());
  EXPECT_THROWS_MESSAGE(ContactMeshKinematics(s.pair, s.frame, s.pinion, s.gear, 0), InvalidInput,
                        "num_slices: 0 must lie in");
  EXPECT_THROWS_MESSAGE(ContactMeshKinematics(s.pair, s.frame, s.pinion, s.gear, 1001),
                        InvalidInput, "num_slices: 1001");
  EXPECT_THROWS_MESSAGE(ContactMeshKinematics(s.pair, s.frame, s.gear, s.pinion, 1), InvalidInput,
                        "pinion.base_radius");
}

}  // namespace
}  // namespace geardyn
