// The sweep branches of a traced nonlinear-HB curve on a grid (ResampleNhbBranches) and the
// difference of two DTE curves (CalcDteDifference), against curves built by hand whose branches
// and differences are known.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "geardyn/compare_runner.hpp"

namespace geardyn::app {
namespace {

constexpr double kTol = 1e-12;

// A softening fold in arclength order: the resonant branch A (f 1.0 → 1.8, RMS 1 → 3, stable),
// the unstable middle branch B (f 1.8 → 1.4), the low branch C (f 1.4 → 2.5, RMS 0.5 → 0.2,
// stable). A slow up-sweep stays on A to its fold at 1.8 and drops to C; a down-sweep stays on C
// to its end at 1.4 and jumps up to A.
struct Fold {
  std::vector<double> hz, rms, p2p;
  std::vector<int> stable, segment;
  void Add(double f, double r, int s) {
    hz.push_back(f);
    rms.push_back(r);
    p2p.push_back(2.0 * r);
    stable.push_back(s);
    segment.push_back(0);
  }
};

double A(double f) { return 1.0 + 2.5 * (f - 1.0); }
double C(double f) { return 0.5 - 0.3 * (f - 1.4) / 1.1; }

TEST(CompareBranchesTest, SweepsFollowTheirBranchUntilItEnds) {
  Fold c;
  // Integer steps (exact ends); the branches reach past the grid's ends 1.0 and 2.5.
  for (int k = 0; k <= 17; ++k) c.Add(0.95 + 0.05 * k, A(0.95 + 0.05 * k), 1);  // to 1.8
  for (int k = 1; k <= 7; ++k) c.Add(1.8 - 0.05 * k, 2.0 + (0.4 - 0.05 * k) * 2.5, 0);
  for (int k = 0; k <= 24; ++k) c.Add(1.4 + 0.05 * k, C(1.4 + 0.05 * k), 1);  // to 2.6
  std::vector<double> grid;
  for (int k = 0; k <= 14; ++k) grid.push_back(1.05 + 0.1 * k);  // none on the folds 1.4, 1.8
  std::vector<double> up, down, up_p2p, down_p2p;
  ResampleNhbBranches(c.hz, c.rms, c.p2p, c.stable, c.segment, grid, &up, &down, &up_p2p,
                      &down_p2p);
  for (std::size_t k = 0; k < grid.size(); ++k) {
    const double f = grid[k];
    const double expected_up = f < 1.8 ? A(f) : C(f);
    const double expected_down = f > 1.4 ? C(f) : A(f);
    EXPECT_NEAR(up[k], expected_up, 1e-9) << "up at " << f;
    EXPECT_NEAR(down[k], expected_down, 1e-9) << "down at " << f;
    EXPECT_NEAR(up_p2p[k], 2.0 * expected_up, 1e-9);
    EXPECT_NEAR(down_p2p[k], 2.0 * expected_down, 1e-9);
  }
}

TEST(CompareBranchesTest, NoStableSolutionIsNaNNotZero) {
  Fold c;
  c.Add(1.0, 1.0, 1);
  c.Add(2.0, 2.0, 0);  // unstable: the segment 1 → 2 is not a stable branch
  c.Add(3.0, 3.0, 0);
  std::vector<double> up, down, up_p2p, down_p2p;
  ResampleNhbBranches(c.hz, c.rms, c.p2p, c.stable, c.segment, {1.5, 2.5}, &up, &down, &up_p2p,
                      &down_p2p);
  EXPECT_TRUE(std::isnan(up[0]) && std::isnan(up[1]) && std::isnan(down[0]));
}

TEST(CompareBranchesTest, DifferenceIsAFractionOfTheReferencesPeak) {
  const std::vector<double> grid = {100.0, 200.0, 300.0, 400.0};
  LevelDte ref, level;
  ref.rms_up = ref.rms_down = {1.0, 4.0, 2.0, 1.0};  // peak 4 at 200 Hz
  level.rms_up = {1.0, 3.0, 3.0, 1.0};               // peak moved to 200–300 Hz
  level.rms_down = {1.0, 3.0, 1.0, 1.0};             // a jump: the down branch differs at 300
  const DteDifference d = CalcDteDifference(level, ref, grid, 0.1);
  const std::vector<double> up = {0.0, -0.25, 0.25, 0.0}, down = {0.0, -0.25, -0.25, 0.0};
  for (std::size_t k = 0; k < grid.size(); ++k) {
    EXPECT_NEAR(d.up[k], up[k], kTol);
    EXPECT_NEAR(d.down[k], down[k], kTol);
  }
  EXPECT_NEAR(d.max_abs, 0.25, kTol);
  EXPECT_EQ(d.max_at_hz, 200.0);  // the first of the equal maxima
  EXPECT_NEAR(d.rms, std::sqrt(4 * 0.0625 / 8.0), kTol);
  EXPECT_EQ(d.reference_peak_hz, 200.0);
  EXPECT_NEAR(d.peak_ratio, 0.75, kTol);
  ASSERT_EQ(d.disagree_ranges.size(), 1u);
  EXPECT_EQ(d.disagree_ranges[0].first, 200.0);
  EXPECT_EQ(d.disagree_ranges[0].second, 300.0);
  EXPECT_EQ(d.missing, 0);
}

}  // namespace
}  // namespace geardyn::app
