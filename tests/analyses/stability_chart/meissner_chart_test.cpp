// ComputeStabilityChart on the Meissner equation (rectangular-wave SDOF), whose multipliers and
// transition curves have closed forms (meissner_closed_form.hpp): the bisected curves against
// GSL's Brent root of |tr Φ_y| = 2 cosh(σT), the verdicts against the same closed form, the
// tongue labels against the classical principal resonances f_m = 2 f_n / k, and the parallel
// result against the serial one bit for bit.
#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>

#include "analyses/stability_chart/meissner_closed_form.hpp"
#include "geardyn/analyses/stability_chart.hpp"
#include "geardyn/common/errors.hpp"
#include "support/expect_throws.hpp"

namespace geardyn {
namespace {

using test::Meissner;

// x = f_m [Hz] (f_n = 1 Hz: principal tongues at 2, 1, 2/3 Hz), y = ε.
ChartAxis FrequencyAxis(int n) { return {"f_m", 0.55, 2.6, n}; }
ChartAxis EpsilonAxis(int n) { return {"epsilon", 0.05, 0.7, n}; }

ChartEvaluatorFactory MeissnerFactory(const Meissner& m) {
  return [m]() -> ChartEvaluator {
    return [m](const ChartPoint& p) {
      ChartPointResult r;
      r.max_abs_multiplier = m.MaxAbsMultiplier(p.x, p.y);
      r.mesh_frequency_hz = p.x;
      return r;
    };
  };
}

// Root of f on [a, b] by GSL's Brent solver to 1e-14 (absolute).
double BrentRoot(const std::function<double(double)>& f, double a, double b) {
  gsl_function F;
  F.function = [](double x, void* params) {
    return (*static_cast<const std::function<double(double)>*>(params))(x);
  };
  F.params = const_cast<std::function<double(double)>*>(&f);
  gsl_root_fsolver* s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
  gsl_root_fsolver_set(s, &F, a, b);
  double root = 0.5 * (a + b);
  for (int it = 0; it < 200; ++it) {
    gsl_root_fsolver_iterate(s);
    root = gsl_root_fsolver_root(s);
    if (gsl_root_test_interval(gsl_root_fsolver_x_lower(s), gsl_root_fsolver_x_upper(s), 1e-14,
                               0.0) == GSL_SUCCESS) {
      break;
    }
  }
  gsl_root_fsolver_free(s);
  return root;
}

// Index i with axis.Value(i) == v exactly, or −1.
int GridIndex(const ChartAxis& axis, double v) {
  for (int i = 0; i < axis.num_points; ++i) {
    if (axis.Value(i) == v) return i;
  }
  return -1;
}

// Every curve point against the closed-form transition curve on the same grid edge.
void ExpectCurvesOnClosedForm(const StabilityChartResult& chart, const Meissner& m,
                              double tolerance) {
  const ChartAxis& xa = chart.x_axis;
  const ChartAxis& ya = chart.y_axis;
  int checked = 0;
  for (const TransitionCurve& curve : chart.curves) {
    for (std::size_t k = 0; k < curve.x.size(); ++k) {
      const double x = curve.x[k], y = curve.y[k];
      const int iy = GridIndex(ya, y);
      if (iy >= 0) {  // on a horizontal edge: x was bisected
        const double step = (xa.hi - xa.lo) / (xa.num_points - 1);
        const int ix = std::min(xa.num_points - 2, static_cast<int>((x - xa.lo) / step));
        const auto f = [&](double s) { return m.BoundaryFunction(s, y); };
        ASSERT_LT(f(xa.Value(ix)) * f(xa.Value(ix + 1)), 0.0) << "no closed-form crossing";
        const double truth = BrentRoot(f, xa.Value(ix), xa.Value(ix + 1));
        EXPECT_NEAR(x, truth, tolerance * (xa.hi - xa.lo)) << "at epsilon " << y;
      } else {  // on a vertical edge: y was bisected
        const int ix = GridIndex(xa, x);
        ASSERT_GE(ix, 0) << "a curve point is on no grid line";
        const double step = (ya.hi - ya.lo) / (ya.num_points - 1);
        const int j = std::min(ya.num_points - 2, static_cast<int>((y - ya.lo) / step));
        const auto f = [&](double s) { return m.BoundaryFunction(x, s); };
        ASSERT_LT(f(ya.Value(j)) * f(ya.Value(j + 1)), 0.0) << "no closed-form crossing";
        const double truth = BrentRoot(f, ya.Value(j), ya.Value(j + 1));
        EXPECT_NEAR(y, truth, tolerance * (ya.hi - ya.lo)) << "at f_m " << x;
      }
      ++checked;
    }
  }
  EXPECT_GT(checked, 20);
}

// The region of the unstable grid point nearest (x, y).
const ChartRegion* RegionNear(const StabilityChartResult& c, double x, double y) {
  int best = -1;
  double best_d = 0.0;
  for (int iy = 0; iy < c.y_axis.num_points; ++iy) {
    for (int ix = 0; ix < c.x_axis.num_points; ++ix) {
      const int i = c.index(ix, iy);
      if (c.region[i] < 0) continue;
      const double d = std::hypot((c.x_axis.Value(ix) - x) / (c.x_axis.hi - c.x_axis.lo),
                                  (c.y_axis.Value(iy) - y) / (c.y_axis.hi - c.y_axis.lo));
      if (best < 0 || d < best_d) {
        best = c.region[i];
        best_d = d;
      }
    }
  }
  return best < 0 ? nullptr : &c.regions[best];
}

TEST(MeissnerChart, DampedTransitionCurvesMatchTheClosedForm) {
  const Meissner m{1.0, 0.01};
  StabilityChartOptions options;
  options.instability_threshold = 0.0;  // a damped boundary crosses max|λ| = 1 transversally
  options.boundary_tolerance = 1e-7;
  options.natural_frequencies_hz = {{1.0}};
  const StabilityChartResult chart =
      ComputeStabilityChart(FrequencyAxis(41), EpsilonAxis(14), MeissnerFactory(m), options);
  ASSERT_TRUE(chart.summary.ok()) << chart.summary.message;
  // Grid verdicts against the trace condition.
  for (int iy = 0; iy < 14; ++iy) {
    for (int ix = 0; ix < 41; ++ix) {
      const double f = m.BoundaryFunction(chart.x_axis.Value(ix), chart.y_axis.Value(iy));
      if (std::abs(f) < 1e-9) continue;
      EXPECT_EQ(chart.stable[chart.index(ix, iy)], f < 0.0 ? 1 : 0) << ix << ", " << iy;
    }
  }
  ExpectCurvesOnClosedForm(chart, m, options.boundary_tolerance);
  EXPECT_LE(chart.summary.error_estimate, 0.5 * options.boundary_tolerance);
}

TEST(MeissnerChart, UndampedTransitionCurvesMatchTheClosedForm) {
  const Meissner m{1.0, 0.0};
  StabilityChartOptions options;  // default threshold 1e-9: |λ| = 1 in the stable regions
  options.boundary_tolerance = 1e-6;
  const StabilityChartResult chart =
      ComputeStabilityChart(FrequencyAxis(31), EpsilonAxis(10), MeissnerFactory(m), options);
  ExpectCurvesOnClosedForm(chart, m, options.boundary_tolerance);
}

TEST(MeissnerChart, TonguesAreLabelledByTheirPrincipalResonance) {
  const Meissner m{1.0, 0.01};
  StabilityChartOptions options;
  options.natural_frequencies_hz = {{1.0}};
  options.trace_curves = false;
  const StabilityChartResult chart =
      ComputeStabilityChart(FrequencyAxis(60), EpsilonAxis(20), MeissnerFactory(m), options);
  // Classical tongues of x'' + ω₀²(1 + ε p(t)) x = 0 at f_m = 2 f_n / k.
  const ChartRegion* first = RegionNear(chart, 2.0, 0.5);
  const ChartRegion* second = RegionNear(chart, 1.0, 0.5);
  const ChartRegion* third = RegionNear(chart, 2.0 / 3.0, 0.6);
  ASSERT_TRUE(first && second && third);
  EXPECT_EQ(first->resonance.label, "2f_1/1");
  EXPECT_EQ(second->resonance.label, "2f_1/2");
  EXPECT_EQ(third->resonance.label, "2f_1/3");
  EXPECT_EQ(first->resonance.kind, ResonanceKind::kPrincipal);
  EXPECT_NEAR(first->resonance.mesh_frequency_hz, 2.0, 1e-15);
  EXPECT_NEAR(second->resonance.mesh_frequency_hz, 1.0, 1e-15);
  // The tongues are distinct regions, each centred near its resonance.
  EXPECT_NE(first, second);
  EXPECT_NE(second, third);
  EXPECT_NEAR(first->mean_mesh_frequency_hz, 2.0, 0.25);
  EXPECT_NEAR(second->mean_mesh_frequency_hz, 1.0, 0.1);
  for (const ChartRegion& r : chart.regions) EXPECT_TRUE(r.labelled);
}

TEST(MeissnerChart, ParallelEqualsSerialBitForBit) {
  const Meissner m{1.0, 0.02};
  StabilityChartOptions options;
  options.natural_frequencies_hz = {{1.0}};
  options.num_threads = 1;
  const StabilityChartResult serial =
      ComputeStabilityChart(FrequencyAxis(37), EpsilonAxis(23), MeissnerFactory(m), options);
  options.num_threads = 4;
  const StabilityChartResult parallel =
      ComputeStabilityChart(FrequencyAxis(37), EpsilonAxis(23), MeissnerFactory(m), options);
  EXPECT_EQ(serial.summary.counters.at("threads"), 1);
  // 4 threads, or fewer on a machine with fewer hardware threads (clamped, with a warning).
  const long used = parallel.summary.counters.at("threads");
  EXPECT_GE(used, 1);
  EXPECT_LE(used, 4);
  if (used < 4) {
    ASSERT_FALSE(parallel.summary.warnings.empty());
    EXPECT_EQ(parallel.summary.warnings[0].rfind(
                  "num_threads: 4 requested, " + std::to_string(used) + " used", 0),
              0u)
        << parallel.summary.warnings[0];
  }
  EXPECT_EQ(serial.max_abs_multiplier, parallel.max_abs_multiplier);
  EXPECT_EQ(serial.stable, parallel.stable);
  EXPECT_EQ(serial.region, parallel.region);
  EXPECT_EQ(serial.summary.counters.at("evaluations"), parallel.summary.counters.at("evaluations"));
  ASSERT_EQ(serial.curves.size(), parallel.curves.size());
  for (std::size_t c = 0; c < serial.curves.size(); ++c) {
    EXPECT_EQ(serial.curves[c].x, parallel.curves[c].x);
    EXPECT_EQ(serial.curves[c].y, parallel.curves[c].y);
    EXPECT_EQ(serial.curves[c].closed, parallel.curves[c].closed);
  }
  ASSERT_EQ(serial.regions.size(), parallel.regions.size());
  for (std::size_t r = 0; r < serial.regions.size(); ++r) {
    EXPECT_EQ(serial.regions[r].resonance.label, parallel.regions[r].resonance.label);
    EXPECT_EQ(serial.regions[r].num_points, parallel.regions[r].num_points);
  }
}

TEST(MeissnerChart, ProgressIsReportedFromTheCallingThreadOnly) {
  const std::thread::id caller = std::this_thread::get_id();
  long last_grid = 0, calls = 0;
  bool other_thread = false;
  StabilityChartOptions options;
  options.num_threads = 3;
  options.progress = [&](const ChartProgress& p) {
    other_thread |= std::this_thread::get_id() != caller;
    ++calls;
    if (std::string(p.phase) == "grid") {
      EXPECT_GE(p.done, last_grid);
      EXPECT_EQ(p.total, 20 * 10);
      last_grid = p.done;
    }
  };
  ComputeStabilityChart(FrequencyAxis(20), EpsilonAxis(10), MeissnerFactory({1.0, 0.0}), options);
  EXPECT_FALSE(other_thread);
  EXPECT_EQ(last_grid, 200);
  EXPECT_GE(calls, 2);
}

TEST(StabilityChart, FailedPointsAreReportedAndLeftOut) {
  // An evaluator that fails on the left third of the chart.
  const auto factory = []() -> ChartEvaluator {
    return [](const ChartPoint& p) {
      ChartPointResult r;
      r.ok = p.x > 1.2;
      r.max_abs_multiplier = Meissner{1.0, 0.0}.MaxAbsMultiplier(p.x, p.y);
      return r;
    };
  };
  const StabilityChartResult chart =
      ComputeStabilityChart(FrequencyAxis(21), EpsilonAxis(5), factory, StabilityChartOptions{});
  EXPECT_EQ(chart.summary.status, Status::kNumericalIssue);
  long failed = 0;
  for (int iy = 0; iy < 5; ++iy) {
    for (int ix = 0; ix < 21; ++ix) {
      const int i = chart.index(ix, iy);
      const bool expect_ok = chart.x_axis.Value(ix) > 1.2;
      EXPECT_EQ(chart.ok[i], expect_ok ? 1 : 0);
      if (!expect_ok) {
        EXPECT_EQ(chart.region[i], -1);
      }
      failed += expect_ok ? 0 : 1;
    }
  }
  EXPECT_EQ(chart.summary.counters.at("undetermined_points"), failed);
  for (const TransitionCurve& c : chart.curves) {
    for (double x : c.x) EXPECT_GT(x, 1.2);
  }
}

TEST(StabilityChart, NanEstimateOrMultiplierIsUndeterminedNotStable) {
  // An evaluator that says ok but returns a NaN estimate (left third) or a NaN max|λ| (right
  // third): before issue 12 a NaN estimate dropped out of "max|λ| > 1 + max(threshold, e)" and
  // the point read as stable. Truth: the closed-form Meissner multipliers in the middle third.
  const auto factory = []() -> ChartEvaluator {
    return [](const ChartPoint& p) {
      ChartPointResult r;
      r.max_abs_multiplier = Meissner{1.0, 0.0}.MaxAbsMultiplier(p.x, p.y);
      if (p.x < 1.0) r.error_estimate = std::numeric_limits<double>::quiet_NaN();
      if (p.x > 2.0) r.max_abs_multiplier = std::numeric_limits<double>::quiet_NaN();
      return r;
    };
  };
  const StabilityChartResult chart =
      ComputeStabilityChart(FrequencyAxis(21), EpsilonAxis(5), factory, StabilityChartOptions{});
  EXPECT_EQ(chart.summary.status, Status::kNumericalIssue);
  long undetermined = 0;
  for (int iy = 0; iy < 5; ++iy) {
    for (int ix = 0; ix < 21; ++ix) {
      const int i = chart.index(ix, iy);
      const double x = chart.x_axis.Value(ix);
      const bool expect_ok = x >= 1.0 && x <= 2.0;
      EXPECT_EQ(chart.ok[i], expect_ok ? 1 : 0) << x;
      if (!expect_ok) {
        EXPECT_EQ(chart.stable[i], 0) << x;
        EXPECT_EQ(chart.region[i], -1) << x;
        ++undetermined;
      } else {
        const bool unstable = Meissner{1.0, 0.0}.MaxAbsMultiplier(x, chart.y_axis.Value(iy)) >
                              1.0 + StabilityChartOptions{}.instability_threshold;
        EXPECT_EQ(chart.stable[i], unstable ? 0 : 1) << x;
      }
    }
  }
  EXPECT_EQ(chart.summary.counters.at("undetermined_points"), undetermined);
}

TEST(StabilityChart, EvaluatorExceptionsAreRethrown) {
  const auto factory = []() -> ChartEvaluator {
    return [](const ChartPoint& p) -> ChartPointResult {
      if (p.ix == 3 && p.iy == 2) throw InvalidInput("bad point (3, 2)");
      return {};
    };
  };
  EXPECT_THROWS_MESSAGE(ComputeStabilityChart(FrequencyAxis(8), EpsilonAxis(4), factory),
                        InvalidInput, "bad point \\(3, 2\\)");
}

TEST(StabilityChart, InvalidAxesAndOptionsNameTheField) {
  const ChartEvaluatorFactory f = MeissnerFactory({});
  EXPECT_THROWS_MESSAGE(ComputeStabilityChart({"a", 0.0, 1.0, 1}, EpsilonAxis(3), f), InvalidInput,
                        "x axis: the number of points must be at least 2, got 1");
  EXPECT_THROWS_MESSAGE(ComputeStabilityChart(FrequencyAxis(3), {"b", 2.0, 2.0, 4}, f),
                        InvalidInput, "y axis: the lower bound must be below the upper bound");
  StabilityChartOptions options;
  options.boundary_tolerance = 0.0;
  EXPECT_THROWS_MESSAGE(ComputeStabilityChart(FrequencyAxis(3), EpsilonAxis(3), f, options),
                        InvalidInput, "boundary_tolerance must be in \\(0, 1\\), got 0");
  options = {};
  options.natural_frequencies_hz = {{1.0}, {1.0}};
  EXPECT_THROWS_MESSAGE(ComputeStabilityChart(FrequencyAxis(3), EpsilonAxis(3), f, options),
                        InvalidInput, "natural_frequencies_hz must have 0, 1 or 3");
}

TEST(Resonances, ListedWithLabelsAndSortedByMeshFrequency) {
  // f = {0 (rigid), 1, 3} Hz: principal 2f/k, sums (f_2 + f_3)/k, differences (f_3 − f_2)/k.
  const std::vector<Resonance> r = ListResonances({0.0, 1.0, 3.0}, 2, true);
  std::vector<std::string> labels;
  std::vector<double> freqs;
  for (const Resonance& x : r) {
    labels.push_back(x.label);
    freqs.push_back(x.mesh_frequency_hz);
  }
  // By hand: 2/2=1 (2f_2/2), 2/2=1 ((f_3-f_2)/2), 2 (2f_2/1), 2 ((f_3-f_2)/1), 2 ((f_2+f_3)/2),
  // 3 (2f_3/2), 4 ((f_2+f_3)/1), 6 (2f_3/1).
  EXPECT_EQ(freqs, (std::vector<double>{1, 1, 2, 2, 2, 3, 4, 6}));
  EXPECT_EQ(labels, (std::vector<std::string>{"2f_2/2", "(f_3-f_2)/2", "2f_2/1", "(f_3-f_2)/1",
                                              "(f_2+f_3)/2", "2f_3/2", "(f_2+f_3)/1", "2f_3/1"}));
  EXPECT_EQ(ListResonances({1.0, 3.0}, 1, false).size(), 3u);  // no differences by default
  // Numbered from 0 (as `geardyn modes`): the same list shifted by one.
  const std::vector<Resonance> zero = ListResonances({0.0, 1.0, 3.0}, 1, false, 0);
  ASSERT_EQ(zero.size(), 3u);
  EXPECT_EQ(zero[0].label, "2f_1/1");
  EXPECT_EQ(zero[1].label, "(f_1+f_2)/1");
  EXPECT_EQ(zero[2].label, "2f_2/1");
}

}  // namespace
}  // namespace geardyn
