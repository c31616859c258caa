// Numerical stress suite, part A — stability charts (ComputeStabilityChart), issue 16: a grid
// that straddles the edges of the first Meissner tongue, with points that fail in every way an
// evaluator can fail (ok = false, NaN or inf max|λ|, NaN estimate) — the chart marks exactly
// those points undetermined, keeps every other verdict right, reports the count in its status,
// and draws no curve through them; an evaluator that throws is rethrown; a chart where every
// point fails is empty but well-formed.
//
// Truth: the undamped Meissner equation x'' + δ(1 ± ε)x = 0 (T = 2π, halves), whose monodromy is
// the product of two closed-form transfer matrices (stress_cases.hpp): a point is unstable iff
// |tr Φ| > 2, and a transition curve lies where |tr Φ| = 2.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "geardyn/analyses/floquet.hpp"
#include "geardyn/analyses/floquet_system.hpp"
#include "geardyn/analyses/stability_chart.hpp"
#include "stress/stress_cases.hpp"

namespace geardyn::stress {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// |tr Φ| − 2 of the Meissner point (δ, ε): > 0 unstable.
double Boundary(double delta, double eps) {
  return std::abs((DampedTransfer(delta * (1 - eps), 0.0, kPi) *
                   DampedTransfer(delta * (1 + eps), 0.0, kPi))
                      .trace()) -
         2.0;
}

// The failure injected at one grid point.
enum class Failure { kNotOk, kNaNMultiplier, kInfMultiplier, kNaNEstimate };

struct ChartCase {
  std::string name;
  Failure failure;
};
void PrintTo(const ChartCase& c, std::ostream* os) { *os << c.name; }

const ChartAxis kDelta{"delta", 0.1, 0.45, 15};  // both edges of the tongue around ¼
const ChartAxis kEps{"epsilon", 0.1, 0.4, 4};
constexpr int kBadIx = 6, kBadIy = 2;  // inside the tongue, next to its lower edge

// Evaluator: ComputeFloquet (exact steps) on the Meissner system, except at the bad grid point
// and on a small disc around it (so that bisections through it fail too).
ChartEvaluatorFactory MakeFactory(Failure failure) {
  return [failure] {
    return [failure](const ChartPoint& p) {
      const double bad_x = kDelta.Value(kBadIx), bad_y = kEps.Value(kBadIy);
      const bool bad = (p.ix == kBadIx && p.iy == kBadIy) ||
                       (std::abs(p.x - bad_x) < 1e-3 && std::abs(p.y - bad_y) < 1e-9);
      FloquetOptions o;
      o.list_undamped_modes = false;
      const FloquetResult r =
          ComputeFloquet(MakeMeissnerSystem(p.x * (1 + p.y), p.x * (1 - p.y), 0.5, kTwoPi), o);
      ChartPointResult out{r.max_abs_multiplier, r.summary.error_estimate, 0.0,
                           r.verdict != FloquetVerdict::kUndetermined};
      if (bad) {
        switch (failure) {
          case Failure::kNotOk:
            out.ok = false;
            break;
          case Failure::kNaNMultiplier:
            out.max_abs_multiplier = kNaN;
            break;
          case Failure::kInfMultiplier:
            out.max_abs_multiplier = kInf;
            break;
          case Failure::kNaNEstimate:
            out.error_estimate = kNaN;
            break;
        }
      }
      return out;
    };
  };
}

class ChartStress : public ::testing::TestWithParam<ChartCase> {};

TEST_P(ChartStress, FailedPointIsUndeterminedAndTheOthersAreRight) {
  StabilityChartOptions options;
  options.num_threads = 2;
  options.boundary_tolerance = 1e-7;
  const StabilityChartResult c =
      ComputeStabilityChart(kDelta, kEps, MakeFactory(GetParam().failure), options);

  // The status says what went wrong, with the count.
  EXPECT_EQ(c.summary.status, Status::kNumericalIssue);
  EXPECT_FALSE(c.summary.message.empty());
  EXPECT_EQ(c.summary.counters.at("undetermined_points"), 1);

  const int bad = c.index(kBadIx, kBadIy);
  EXPECT_EQ(c.ok[bad], 0);
  EXPECT_EQ(c.stable[bad], 0);
  EXPECT_EQ(c.region[bad], -1);
  int checked = 0;
  for (int iy = 0; iy < kEps.num_points; ++iy) {
    for (int ix = 0; ix < kDelta.num_points; ++ix) {
      const int i = c.index(ix, iy);
      if (i == bad) continue;
      const double g = Boundary(kDelta.Value(ix), kEps.Value(iy));
      SCOPED_TRACE(::testing::Message() << "point (" << ix << ", " << iy << "), |tr|−2 = " << g);
      EXPECT_EQ(c.ok[i], 1);
      EXPECT_TRUE(std::isfinite(c.max_abs_multiplier[i]) && std::isfinite(c.error_estimate[i]));
      if (std::abs(g) > 1e-9) {  // decided by the closed form
        EXPECT_EQ(c.stable[i], g < 0 ? 1 : 0);
        EXPECT_EQ(c.region[i] >= 0, g > 0);
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, kDelta.num_points * kEps.num_points - 5);

  // The curves: finite coordinates, each on a closed-form edge (|tr| = 2 within the bisection
  // bracket along one axis), none through the failed point.
  ASSERT_FALSE(c.curves.empty());
  const double hx = 2e-7 * (kDelta.hi - kDelta.lo), hy = 2e-7 * (kEps.hi - kEps.lo);
  for (const TransitionCurve& curve : c.curves) {
    ASSERT_EQ(curve.x.size(), curve.y.size());
    for (std::size_t k = 0; k < curve.x.size(); ++k) {
      const double x = curve.x[k], y = curve.y[k];
      ASSERT_TRUE(std::isfinite(x) && std::isfinite(y)) << "curve point " << k;
      const bool across_x = (Boundary(x - hx, y) > 0) != (Boundary(x + hx, y) > 0);
      const bool across_y = (Boundary(x, y - hy) > 0) != (Boundary(x, y + hy) > 0);
      EXPECT_TRUE(across_x || across_y) << "curve point (" << x << ", " << y << ") is off the edge";
      EXPECT_FALSE(x == kDelta.Value(kBadIx) && y == kEps.Value(kBadIy));
    }
  }
  EXPECT_TRUE(std::isfinite(c.summary.error_estimate));
}

INSTANTIATE_TEST_SUITE_P(Cases, ChartStress,
                         ::testing::Values(ChartCase{"evaluator_not_ok", Failure::kNotOk},
                                           ChartCase{"nan_multiplier", Failure::kNaNMultiplier},
                                           ChartCase{"inf_multiplier", Failure::kInfMultiplier},
                                           ChartCase{"nan_estimate", Failure::kNaNEstimate}),
                         [](const ::testing::TestParamInfo<ChartCase>& param_info) {
                           return param_info.param.name;
                         });

// Every point fails: no regions, no curves, every point undetermined, a status — no crash.
TEST(ChartStressAll, EveryPointFailing) {
  const ChartEvaluatorFactory factory = [] {
    return [](const ChartPoint&) { return ChartPointResult{kNaN, kNaN, 0.0, false}; };
  };
  const StabilityChartResult c = ComputeStabilityChart(kDelta, kEps, factory);
  EXPECT_EQ(c.summary.status, Status::kNumericalIssue);
  EXPECT_EQ(c.summary.counters.at("undetermined_points"), kDelta.num_points * kEps.num_points);
  EXPECT_TRUE(c.regions.empty());
  EXPECT_TRUE(c.curves.empty());
  for (std::size_t i = 0; i < c.ok.size(); ++i) {
    EXPECT_EQ(c.ok[i], 0);
    EXPECT_EQ(c.stable[i], 0);
    EXPECT_EQ(c.region[i], -1);
  }
  EXPECT_TRUE(std::isfinite(c.summary.error_estimate));
}

// An evaluator that throws at one point: the exception is rethrown (documented), not swallowed
// into a half-filled chart, from the parallel loop.
TEST(ChartStressAll, ThrowingEvaluatorIsRethrown) {
  const ChartEvaluatorFactory factory = [] {
    return [](const ChartPoint& p) {
      if (p.ix == 3 && p.iy == 1) throw std::runtime_error("evaluator failed at (3, 1)");
      return ChartPointResult{1.0, 0.0, 0.0, true};
    };
  };
  StabilityChartOptions options;
  options.num_threads = 2;
  EXPECT_THROW(ComputeStabilityChart(kDelta, kEps, factory, options), std::runtime_error);
}

}  // namespace
}  // namespace geardyn::stress
