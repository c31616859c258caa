// Stability charts (issue 5 target: a 200 × 200 SDOF chart in under a second, all cores):
// ComputeStabilityChart on the Meissner equation x'' + 2ζω₀x' + ω₀²(1 ± ε)x = 0 over
// f_m ∈ [0.55, 2.6] Hz × ε ∈ [0.05, 0.7] (f_n = 1 Hz, ζ = 0.01), with
// * "floquet": every point a ComputeFloquet(MakeMeissnerSystem(...)) (exact steps, the library
//   path a real SDOF chart takes);
// * "closed_form": the 2×2 exact transfer matrices inline (the chart engine's own overhead).
// Arguments: grid points per axis, threads (0 = all cores), transition curves on/off.
#include <benchmark/benchmark.h>

#include <Eigen/Dense>
#include <cmath>
#include <numbers>

#include "geardyn/analyses/floquet_system.hpp"
#include "geardyn/analyses/stability_chart.hpp"

namespace geardyn {
namespace {

constexpr double kZeta = 0.01;
const double kOmega0 = 2.0 * std::numbers::pi;  // f_n = 1 Hz

ChartEvaluatorFactory FloquetFactory() {
  return []() -> ChartEvaluator {
    return [](const ChartPoint& p) {
      const double k = kOmega0 * kOmega0;
      const PeriodicSecondOrderSystem sys = MakeMeissnerSystem(
          k * (1.0 + p.y), k * (1.0 - p.y), 0.5, 1.0 / p.x, 2.0 * kZeta * kOmega0);
      FloquetOptions options;
      options.method = FloquetMethod::kExactSteps;
      const FloquetResult r = ComputeFloquet(sys, options);
      return ChartPointResult{r.max_abs_multiplier, r.summary.error_estimate, p.x, r.summary.ok()};
    };
  };
}

Eigen::Matrix2d Transfer(double w2, double tau) {
  const double sigma = kZeta * kOmega0, wd = std::sqrt(w2 - sigma * sigma);
  const double c = std::cos(wd * tau), s = std::sin(wd * tau);
  Eigen::Matrix2d t;
  t << c + sigma * s / wd, s / wd, -w2 * s / wd, c - sigma * s / wd;
  return std::exp(-sigma * tau) * t;
}

ChartEvaluatorFactory ClosedFormFactory() {
  return []() -> ChartEvaluator {
    return [](const ChartPoint& p) {
      const double w2 = kOmega0 * kOmega0, tau = 0.5 / p.x;
      const Eigen::Matrix2d phi = Transfer(w2 * (1 - p.y), tau) * Transfer(w2 * (1 + p.y), tau);
      return ChartPointResult{phi.eigenvalues().cwiseAbs().maxCoeff(), 0.0, p.x, true};
    };
  };
}

void RunChart(benchmark::State& state, const ChartEvaluatorFactory& factory) {
  const int n = static_cast<int>(state.range(0));
  StabilityChartOptions options;
  options.num_threads = static_cast<int>(state.range(1));
  options.trace_curves = state.range(2) != 0;
  options.boundary_tolerance = 1e-6;
  options.natural_frequencies_hz = {{1.0}};
  long evaluations = 0, regions = 0;
  for (auto _ : state) {
    const StabilityChartResult c =
        ComputeStabilityChart({"f_m", 0.55, 2.6, n}, {"epsilon", 0.05, 0.7, n}, factory, options);
    evaluations = c.summary.counters.at("evaluations");
    regions = static_cast<long>(c.regions.size());
    benchmark::DoNotOptimize(c.max_abs_multiplier.data());
  }
  state.counters["evaluations"] = static_cast<double>(evaluations);
  state.counters["regions"] = static_cast<double>(regions);
}

void BM_ChartFloquet(benchmark::State& state) { RunChart(state, FloquetFactory()); }
void BM_ChartClosedForm(benchmark::State& state) { RunChart(state, ClosedFormFactory()); }

BENCHMARK(BM_ChartFloquet)
    ->ArgsProduct({{200}, {1, 0}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_ChartClosedForm)
    ->ArgsProduct({{200}, {1, 0}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace geardyn

BENCHMARK_MAIN();
