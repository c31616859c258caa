// Tests of geardyn/models/mesh/tooth_modifications.hpp against hand-computed values of the
// documented formulas: where each relief band sits on the path of contact and its shape, crowning
// and slope across the face, the mesh-cycle tooth indexing, flank lags from single pitch
// deviations (cumulative sums, mean removed), the runout projection, the period and every error
// path.
#include "geardyn/models/mesh/tooth_modifications.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "geardyn/common/errors.hpp"
#include "geardyn/common/units.hpp"
#include "support/expect_throws.hpp"

namespace geardyn {
namespace {

constexpr double kPitch = 0.0059;  // p_bt [m]
constexpr double kFace = 0.024;    // B [m]
constexpr double kUm = 1e-6;       // 1 µm [m]
// Hand values vs a few flops: round-off of O(1) operations on µm-sized numbers.
constexpr double kTol = 1e-12 * kUm;

ZoneOfAction Zone(double eps_alpha, double eps_beta, double offset = 0.0) {
  ZoneOfAction z;
  z.length = eps_alpha * kPitch;
  z.face_width = kFace;
  z.transverse_base_pitch = kPitch;
  z.base_helix_angle = std::atan(eps_beta * kPitch / kFace);
  z.pitch_point_offset = offset;
  return z;
}

TEST(ToothModificationsTest, PathEndsFollowTheZone) {
  const ZoneOfAction zone = Zone(1.6, 0.0, 0.2 * kPitch);
  const UnloadedSeparation e(zone, {});
  EXPECT_DOUBLE_EQ(e.path_start(), -0.8 * kPitch - 0.2 * kPitch);
  EXPECT_DOUBLE_EQ(e.path_end(), e.path_start() + 1.6 * kPitch);
  EXPECT_FALSE(e.has_flank_modifications());
  EXPECT_FALSE(e.has_tooth_errors());
  EXPECT_EQ(e.period_meshes(), 1);
  EXPECT_TRUE(e.profile_kinks().empty());
  EXPECT_EQ(e.Separation(0.0, 0.0, 7, 1.0), 0.0);
}

TEST(ToothModificationsTest, TipReliefActsAtThePathEndOfItsTip) {
  // Pinion tip: end of the path (x_e), gear tip: start (x_s). Linear: C·u, parabolic: C·u².
  const ZoneOfAction zone = Zone(1.6, 0.0, 0.2 * kPitch);
  ToothModifications m;
  m.pinion_tip_relief = {10 * kUm, 0.4 * kPitch, ReliefShape::kLinear};
  m.gear_tip_relief = {8 * kUm, 0.5 * kPitch, ReliefShape::kParabolic};
  const UnloadedSeparation e(zone, m);
  const double xs = e.path_start(), xe = e.path_end();
  EXPECT_NEAR(e.ProfileSeparation(xe), 10 * kUm, kTol);
  EXPECT_NEAR(e.ProfileSeparation(xe - 0.1 * kPitch), 7.5 * kUm, kTol);  // u = 0.75
  EXPECT_NEAR(e.ProfileSeparation(xe - 0.4 * kPitch), 0.0, kTol);
  EXPECT_EQ(e.ProfileSeparation(0.5 * (xs + xe)), 0.0);  // mid path: no relief
  EXPECT_NEAR(e.ProfileSeparation(xs), 8 * kUm, kTol);
  EXPECT_NEAR(e.ProfileSeparation(xs + 0.25 * kPitch), 2 * kUm, kTol);  // u = 1/2 → C/4
  EXPECT_NEAR(e.ProfileSeparation(xs + 0.5 * kPitch), 0.0, kTol);
  EXPECT_TRUE(e.has_flank_modifications());
  ASSERT_EQ(e.profile_kinks().size(), 2u);
  EXPECT_DOUBLE_EQ(e.profile_kinks()[0], xs + 0.5 * kPitch);
  EXPECT_DOUBLE_EQ(e.profile_kinks()[1], xe - 0.4 * kPitch);
}

TEST(ToothModificationsTest, RootReliefActsAtThePathEndOfTheMatingTip) {
  // The pinion root meets the gear tip at x_s; the gear root meets the pinion tip at x_e.
  const ZoneOfAction zone = Zone(1.45, 0.8);
  ToothModifications m;
  m.pinion_root_relief = {4 * kUm, 0.2 * kPitch, ReliefShape::kLinear};
  m.gear_root_relief = {6 * kUm, 0.3 * kPitch, ReliefShape::kParabolic};
  m.pinion_tip_relief = {5 * kUm, 0.3 * kPitch, ReliefShape::kLinear};  // same band as gear root
  const UnloadedSeparation e(zone, m);
  const double xs = e.path_start(), xe = e.path_end();
  EXPECT_NEAR(e.ProfileSeparation(xs), 4 * kUm, kTol);
  EXPECT_NEAR(e.ProfileSeparation(xs + 0.1 * kPitch), 2 * kUm, kTol);
  EXPECT_NEAR(e.ProfileSeparation(xe), 11 * kUm, kTol);  // bands add
  EXPECT_NEAR(e.ProfileSeparation(xe - 0.15 * kPitch), 1.5 * kUm + 2.5 * kUm, kTol);
  // Coincident kinks are listed once.
  EXPECT_EQ(e.profile_kinks().size(), 2u);
}

TEST(ToothModificationsTest, ReliefOverTheWholePathHasNoInteriorKink) {
  const ZoneOfAction zone = Zone(1.3, 0.0);
  ToothModifications m;
  m.pinion_tip_relief = {3 * kUm, 1.3 * kPitch, ReliefShape::kLinear};
  const UnloadedSeparation e(zone, m);
  EXPECT_TRUE(e.profile_kinks().empty());
  EXPECT_NEAR(e.ProfileSeparation(e.path_start()), 0.0, kTol);
  EXPECT_NEAR(e.ProfileSeparation(0.5 * (e.path_start() + e.path_end())), 1.5 * kUm, kTol);
}

TEST(ToothModificationsTest, CrowningIsParabolicAndSlopeLinearAcrossTheFace) {
  const ZoneOfAction zone = Zone(1.5, 1.1);
  ToothModifications m;
  m.lead_crowning = 6 * kUm;
  m.lead_slope = 4 * kUm;
  const UnloadedSeparation e(zone, m);
  const double b = 0.5 * kFace;
  EXPECT_NEAR(e.LeadSeparation(0.0), 0.0, kTol);
  EXPECT_NEAR(e.LeadSeparation(b), 6 * kUm + 2 * kUm, kTol);   // C_b + f/2
  EXPECT_NEAR(e.LeadSeparation(-b), 6 * kUm - 2 * kUm, kTol);  // C_b − f/2
  EXPECT_NEAR(e.LeadSeparation(0.5 * b), 1.5 * kUm + 1 * kUm, kTol);
  // Lead modifications do not depend on the roll, profile ones not on the face coordinate.
  EXPECT_NEAR(e.Separation(0.001, 0.5 * b, 3, 2.0), 2.5 * kUm, kTol);
  EXPECT_EQ(e.period_meshes(), 1);
}

TEST(ToothModificationsTest, MeshCyclesIndexBothMembersModuloTheirTeeth) {
  ToothErrors err;
  err.pinion_teeth = 3;
  err.gear_teeth = 4;
  err.gear_runout = 1 * kUm;  // any error makes the indexing matter
  const UnloadedSeparation e(Zone(1.5, 0.0), {}, err);
  EXPECT_EQ(e.period_meshes(), 12);
  EXPECT_EQ(e.PinionTooth(0), 0);
  EXPECT_EQ(e.PinionTooth(4), 1);
  EXPECT_EQ(e.PinionTooth(-1), 2);
  EXPECT_EQ(e.GearTooth(-1), 3);
  EXPECT_EQ(e.GearTooth(13), 1);
  // gcd = 1: every pinion tooth meets every gear tooth exactly once per hunting period.
  std::set<std::pair<int, int>> pairs;
  for (int n = 0; n < 12; ++n) pairs.insert({e.PinionTooth(n), e.GearTooth(n)});
  EXPECT_EQ(pairs.size(), 12u);
  // gcd = 2 (4/6): lcm = 12, only half of the 24 combinations ever mesh.
  err.pinion_teeth = 4;
  err.gear_teeth = 6;
  const UnloadedSeparation f(Zone(1.5, 0.0), {}, err);
  EXPECT_EQ(f.period_meshes(), 12);
}

TEST(ToothModificationsTest, PitchDeviationsGiveMeanFreeFlankLags) {
  // Pinion tooth 1 trails by d (pitch 0→1 longer by d, 1→2 shorter by d): lags (0, d, 0) − d/3.
  const double d = 3 * kUm;
  const ZoneOfAction zone = Zone(1.5, 1.2);
  const double cb = std::cos(zone.base_helix_angle);
  ToothErrors err;
  err.pinion_teeth = 3;
  err.gear_teeth = 5;
  err.pinion_pitch_deviations = {0.0, d, -d};
  err.gear_pitch_deviations = {1 * kUm, -2 * kUm, 0.0, 0.5 * kUm, 0.5 * kUm};
  const UnloadedSeparation e(zone, {}, err);
  ASSERT_EQ(e.pinion_flank_lags().size(), 3u);
  EXPECT_NEAR(e.pinion_flank_lags()[0], -d / 3, kTol);
  EXPECT_NEAR(e.pinion_flank_lags()[1], 2 * d / 3, kTol);
  EXPECT_NEAR(e.pinion_flank_lags()[2], -d / 3, kTol);
  // Gear: cumulative (0, −2, −2, −1.5, −1) µm, mean −1.3 µm.
  const std::vector<double> gear = {1.3, -0.7, -0.7, -0.2, 0.3};
  for (int i = 0; i < 5; ++i) EXPECT_NEAR(e.gear_flank_lags()[i], gear[i] * kUm, kTol);
  EXPECT_TRUE(e.has_tooth_errors());
  EXPECT_EQ(e.period_meshes(), 15);
  // A lagging pinion flank opens the gap, a lagging gear flank closes it; normal = cos β_b·lag.
  for (long n = -20; n < 40; ++n) {
    const int i1 = static_cast<int>(((n % 3) + 3) % 3), i2 = static_cast<int>(((n % 5) + 5) % 5);
    const double expected = cb * (e.pinion_flank_lags()[i1] - gear[i2] * kUm);
    EXPECT_NEAR(e.ToothPairSeparation(n), expected, kTol) << "cycle " << n;
  }
}

// Measured deviations are typed rounded: a mean-free list printed with 7 significant digits sums
// to ~1e-8 of Σ|f_p| and was rejected (closure tolerance 1e-9) with advice ("subtract the mean
// -4e-14 m") that rounding undoes. Truth: the unrounded mean-free list; the rounded one gives the
// same flank lags to the rounding (≤ 5e-7 relative per entry, summed over the teeth).
TEST(ToothModificationsTest, PitchDeviationsRoundedToSevenDigitsCloseWithinTheirRounding) {
  const ZoneOfAction zone = Zone(1.5, 0.0);
  constexpr int kTeeth = 50;
  std::vector<double> exact(kTeeth), rounded(kTeeth);
  double mean = 0.0;
  for (int i = 0; i < kTeeth; ++i) {
    exact[i] = 3 * kUm * std::sin(2.1 * i + 0.3) * std::cos(0.7 * i);  // irrational-looking
    mean += exact[i] / kTeeth;
  }
  double sum_abs = 0.0, rounded_sum = 0.0;
  for (int i = 0; i < kTeeth; ++i) {
    exact[i] -= mean;
    char text[32];
    std::snprintf(text, sizeof(text), "%.6e", exact[i]);
    rounded[i] = std::stod(text);
    sum_abs += std::abs(exact[i]);
    rounded_sum += rounded[i];
  }
  ASSERT_GT(std::abs(rounded_sum), 1e-9 * sum_abs);  // the case the old tolerance rejected
  ToothErrors a, b;
  a.pinion_teeth = b.pinion_teeth = kTeeth;
  a.gear_teeth = b.gear_teeth = 7;
  a.pinion_pitch_deviations = exact;
  b.pinion_pitch_deviations = rounded;
  const UnloadedSeparation e_exact(zone, {}, a), e_rounded(zone, {}, b);
  for (int i = 0; i < kTeeth; ++i) {
    EXPECT_NEAR(e_rounded.pinion_flank_lags()[i], e_exact.pinion_flank_lags()[i],
                kTeeth * 5e-7 * 3 * kUm);
  }
  // A list that does not close (Σ = 1e-5 Σ|f_p|, ten times the tolerance) is still rejected.
  b.pinion_pitch_deviations[0] += 1e-5 * sum_abs;
  EXPECT_THROWS_MESSAGE(UnloadedSeparation(zone, {}, b), InvalidInput,
                        "pinion_pitch_deviations: the single pitch deviations of a closed gear");
}

TEST(ToothModificationsTest, RunoutIsTheCentreOffsetProjectedOnTheNormal) {
  const ZoneOfAction zone = Zone(1.5, 1.2);
  const double cb = std::cos(zone.base_helix_angle);
  ToothErrors err;
  err.pinion_teeth = 25;
  err.gear_teeth = 61;
  err.pinion_runout = 7 * kUm;
  err.pinion_runout_phase = 0.4;
  err.gear_runout = 11 * kUm;
  err.gear_runout_phase = -1.3;
  const UnloadedSeparation e(zone, {}, err);
  EXPECT_EQ(e.period_meshes(), 1525);
  for (double t : {0.0, 1.0, 100.0, 2 * kPi * 1525 - 0.1}) {
    const double expected =
        cb * (-7 * kUm * std::cos(t / 25 + 0.4) + 11 * kUm * std::cos(t / 61 - 1.3));
    EXPECT_NEAR(e.RunoutSeparation(t), expected, kTol) << "theta " << t;
  }
  // Once per pinion revolution (25 mesh cycles) for the pinion term.
  ToothErrors only_pinion = err;
  only_pinion.gear_runout = 0.0;
  const UnloadedSeparation p(zone, {}, only_pinion);
  EXPECT_NEAR(p.RunoutSeparation(1.0 + 2 * kPi * 25), p.RunoutSeparation(1.0), 1e-9 * kUm);
  EXPECT_NEAR(p.RunoutSeparation(2 * kPi * 25 * 0.5 - 0.4 * 25), cb * 7 * kUm, 1e-9 * kUm);
}

// ------------------------------------------------------------------------------ error paths

TEST(ToothModificationsTest, InvalidModificationsNameTheField) {
  const ZoneOfAction zone = Zone(1.5, 0.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto with = [&](auto edit) {
    ToothModifications m;
    edit(m);
    return UnloadedSeparation(zone, m);
  };
  EXPECT_THROWS_MESSAGE(with([](ToothModifications& m) { m.pinion_tip_relief.amount = -1e-6; }),
                        InvalidInput, "modifications.pinion_tip_relief.amount");
  EXPECT_THROWS_MESSAGE(with([&](ToothModifications& m) { m.gear_tip_relief.amount = nan; }),
                        InvalidInput, "modifications.gear_tip_relief.amount");
  EXPECT_THROWS_MESSAGE(with([](ToothModifications& m) {
                          m.pinion_root_relief = {1e-6, -1e-3, ReliefShape::kLinear};
                        }),
                        InvalidInput, "modifications.pinion_root_relief.length");
  EXPECT_THROWS_MESSAGE(with([](ToothModifications& m) {
                          m.gear_root_relief = {1e-6, 0.0, ReliefShape::kLinear};
                        }),
                        InvalidInput, "modifications.gear_root_relief.length: must be > 0");
  EXPECT_THROWS_MESSAGE(with([](ToothModifications& m) {
                          m.pinion_tip_relief = {1e-6, 1.51 * kPitch, ReliefShape::kParabolic};
                        }),
                        InvalidInput,
                        "modifications.pinion_tip_relief.length: .* longer than the path");
  EXPECT_THROWS_MESSAGE(with([](ToothModifications& m) {
                          m.gear_tip_relief = {1e-6, 0.1 * kPitch, static_cast<ReliefShape>(7)};
                        }),
                        InvalidInput, "modifications.gear_tip_relief.shape");
  EXPECT_THROWS_MESSAGE(with([](ToothModifications& m) { m.lead_crowning = -1e-6; }), InvalidInput,
                        "modifications.lead_crowning");
  EXPECT_THROWS_MESSAGE(with([&](ToothModifications& m) { m.lead_slope = nan; }), InvalidInput,
                        "modifications.lead_slope");
  // A zero amount with a zero length is simply no relief; the full path length is allowed.
  EXPECT_NO_THROW(with([](ToothModifications& m) {
    m.pinion_tip_relief = {1e-6, 1.5 * kPitch, ReliefShape::kLinear};
  }));
  ZoneOfAction bad = zone;
  bad.length = -1.0;
  EXPECT_THROWS_MESSAGE(UnloadedSeparation(bad, {}), InvalidInput, "zone.length");
}

TEST(ToothModificationsTest, InvalidToothErrorsNameTheField) {
  const ZoneOfAction zone = Zone(1.5, 0.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto with = [&](auto edit) {
    ToothErrors err;
    err.pinion_teeth = 3;
    err.gear_teeth = 4;
    edit(err);
    return UnloadedSeparation(zone, {}, err);
  };
  EXPECT_THROWS_MESSAGE(with([](ToothErrors& e) {
                          e.pinion_pitch_deviations = {1e-6, -1e-6};
                        }),
                        InvalidInput,
                        "errors.pinion_pitch_deviations: has 2 entries but the member has 3 teeth");
  EXPECT_THROWS_MESSAGE(with([](ToothErrors& e) {
                          e.gear_pitch_deviations = {1, 2, 3, 4, 5};
                        }),
                        InvalidInput, "errors.gear_pitch_deviations: has 5 entries");
  EXPECT_THROWS_MESSAGE(
      with([](ToothErrors& e) {
        e.pinion_pitch_deviations = {1e-6, 0.0, 0.0};
      }),
      InvalidInput,
      "errors.pinion_pitch_deviations: the single pitch deviations of a closed gear sum to zero");
  EXPECT_THROWS_MESSAGE(with([&](ToothErrors& e) {
                          e.gear_pitch_deviations = {0, nan, 0, 0};
                        }),
                        InvalidInput, "errors.gear_pitch_deviations\\[1\\]");
  EXPECT_THROWS_MESSAGE(with([](ToothErrors& e) { e.pinion_runout = -1e-6; }), InvalidInput,
                        "errors.pinion_runout");
  EXPECT_THROWS_MESSAGE(with([&](ToothErrors& e) { e.gear_runout = nan; }), InvalidInput,
                        "errors.gear_runout");
  EXPECT_THROWS_MESSAGE(with([&](ToothErrors& e) { e.gear_runout_phase = nan; }), InvalidInput,
                        "errors.gear_runout_phase");
  EXPECT_THROWS_MESSAGE(with([](ToothErrors& e) {
                          e.pinion_teeth = 0;
                          e.gear_runout = 1e-6;
                        }),
                        InvalidInput, "errors.pinion_teeth");
  EXPECT_THROWS_MESSAGE(with([](ToothErrors& e) {
                          e.gear_teeth = 0;
                          e.gear_pitch_deviations = {};
                          e.pinion_pitch_deviations = {1e-6, -1e-6, 0.0};
                        }),
                        InvalidInput, "errors.gear_teeth");
  EXPECT_THROWS_MESSAGE(with([](ToothErrors& e) {
                          e.pinion_teeth = 65536;
                          e.gear_teeth = 65537;
                          e.gear_runout = 1e-6;
                        }),
                        InvalidInput, "hunting period");
  // Zero errors: mesh-periodic, and teeth counts are not needed.
  const UnloadedSeparation none(zone, {}, ToothErrors{});
  EXPECT_EQ(none.period_meshes(), 1);
  EXPECT_THROWS_MESSAGE(none.PinionTooth(3), InvalidInput, "errors.pinion_teeth");
  // All-zero deviation vectors of the right size are accepted and leave the period at 1.
  const UnloadedSeparation zeros = with([](ToothErrors& e) {
    e.pinion_pitch_deviations = {0, 0, 0};
  });
  EXPECT_FALSE(zeros.has_tooth_errors());
  EXPECT_EQ(zeros.period_meshes(), 1);
}

}  // namespace
}  // namespace geardyn
