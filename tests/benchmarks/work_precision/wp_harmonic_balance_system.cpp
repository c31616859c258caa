// Work-precision of the nonlinear harmonic balance of a gear SYSTEM (system_nonlinear_hb.hpp) on
// the Kahraman–Blankenship rig with a 10-slice mesh (12 DOF; 9 flexible coupled coordinates;
// contact loss), 100 N·m:
// * RMS DTE error vs wall time over H at 1700 Hz (≈ 30 % contact loss), single solve from the
//   contact guess, against H = 128 (same equations, AFT samples = 16 H);
// * the wall time of the continuation over 700–3500 Hz (points, folds) for H = 16, 24, 32.
// Output: CSV `method, knob, wall_time_s, error, evaluations` (wp_common.hpp).
#include <Eigen/Core>
#include <cmath>
#include <cstdio>

#include "geardyn/analyses/system_nonlinear_hb.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"
#include "wp_common.hpp"

int main() {
  using namespace geardyn;
  const SystemModel model = MakeSystemModel(LoadScene(
      "builtin:kahraman-blankenship-rig",
      {"mesh.pinion-wheel.model=\"slices\"", "mesh.pinion-wheel.slices=10",
       "mesh.pinion-wheel.center_distance=0.1502", "mesh.pinion-wheel.damping_ratio=0.05"}));
  const double f_m = 1700.0;
  SystemNhbOptions o;
  o.compute_element_forces = false;
  o.hb.stability = NhbStabilityMethod::kNone;
  o.hb.harmonics = 128;
  const double ref = SolveSystemNonlinearHb(model, f_m, o).meshes[0].rms_dte;
  std::printf("# %d DOF; reference RMS DTE at %g Hz (H = 128): %.12e m\n", model.num_dofs(), f_m,
              ref);
  std::printf("method,knob,wall_time_s,error,evaluations\n");
  for (const int H : {4, 8, 12, 16, 24, 32, 48, 64}) {
    o.hb.harmonics = H;
    SystemNhbPoint p;
    Summary s;
    const double t = wp::TimeIt([&] { p = SolveSystemNonlinearHb(model, f_m, o, &s); });
    wp::Row("solve_H", H, t, std::abs(p.meshes[0].rms_dte - ref) / ref, p.point.newton_iterations);
  }
  o.start_hz = 700.0;
  o.end_hz = 3500.0;
  o.hb.stability = NhbStabilityMethod::kMonodromy;
  for (const int H : {16, 24, 32}) {
    o.hb.harmonics = H;
    const SystemNhbCurve c = TraceSystemNonlinearHb(model, o);
    wp::Row("trace_700_3500_H", H, c.summary.wall_time_s, c.summary.ok() ? 0.0 : 1.0,
            static_cast<double>(c.points.size()));
  }
  return 0;
}
