// Work-precision of the linear LTV harmonic balance on the 12-DOF built-in helical pair (B–S
// 6-DOF mesh core, smooth Fourier stiffness, mesh damping ratio 0.05):
// * RMS DTE error vs wall time over H (condensed and full direct paths) and over the tolerance,
//   against a converged reference (H = 128);
// * the wall time of a 1 000-point sweep (100 Hz … 10 kHz) with H = 20.
// Output: CSV `method, knob, wall_time_s, error, evaluations` (wp_common.hpp).
#include <cmath>
#include <cstdio>
#include <vector>

#include "geardyn/analyses/harmonic_balance.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"
#include "wp_common.hpp"

int main() {
  using namespace geardyn;
  const SystemModel model =
      MakeSystemModel(LoadScene("builtin:helical-pair", {"mesh.pinion-wheel.damping_ratio=0.05"}));
  std::printf("# %d DOF, P = %lld\n", model.num_dofs(),
              static_cast<long long>(model.period_meshes()));
  const double f_m = 2500.0;
  HbOptions options;
  options.time_samples = 1024;  // same samples for every H: only the truncation differs
  options.compute_forces = false;
  options.harmonics = 128;
  const double ref = SolveHarmonicBalance(model, options, f_m).meshes[0].rms_dte;
  std::printf("# reference RMS DTE at %g Hz (H = 128): %.12e m\n", f_m, ref);
  std::printf("method,knob,wall_time_s,error,evaluations\n");
  for (const HbMethod method : {HbMethod::kCondensed, HbMethod::kDirect}) {
    for (const int H : {1, 2, 3, 4, 6, 8, 12, 16, 24, 32}) {
      if (method == HbMethod::kDirect && H > 16) continue;
      options.method = method;
      options.harmonics = H;
      HarmonicBalanceSolver solver(model, options);
      double rms = 0.0;
      const double t = wp::TimeIt([&] { rms = solver.Solve(f_m).meshes[0].rms_dte; });
      wp::Row(method == HbMethod::kCondensed ? "condensed_H" : "direct_H", H, t,
              std::abs(rms - ref) / ref, 1);
    }
  }
  options.method = HbMethod::kAuto;
  options.harmonics = 0;
  options.min_harmonics = 2;
  options.max_harmonics = 256;
  for (const double tol : {1e-2, 1e-3, 1e-4, 1e-6, 1e-8, 1e-10}) {
    options.tolerance = tol;
    HarmonicBalanceSolver solver(model, options);
    HbResult r;
    const double t = wp::TimeIt([&] { r = solver.Solve(f_m); });
    wp::Row("tolerance", tol, t, std::abs(r.meshes[0].rms_dte - ref) / ref, r.harmonics);
  }
  // The 1 000-speed sweep with H = 20 (setup included: one SweepHarmonicBalance call).
  std::vector<double> speeds(1000);
  for (int i = 0; i < 1000; ++i) speeds[i] = 100.0 + 9900.0 * i / 999.0;
  for (const bool forces : {false, true}) {
    HbOptions sweep_options;
    sweep_options.harmonics = 20;
    sweep_options.compute_forces = forces;
    const HbSweepResult sweep = SweepHarmonicBalance(model, speeds, sweep_options);
    wp::Row(forces ? "sweep1000_H20_with_forces" : "sweep1000_H20_dte", 20,
            sweep.summary.wall_time_s, sweep.summary.ok() ? 0.0 : 1.0, 1000);
  }
  return 0;
}
