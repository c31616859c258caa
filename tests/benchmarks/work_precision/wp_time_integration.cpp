// Work-precision of the time integration (time_response.hpp) on the Kahraman–Blankenship rig
// (12 DOF), 100 N·m, ζ_m = 0.05, one steady-state run from the static equilibrium (transient
// included: what `geardyn simulate` at one speed costs):
// * slices: the 10-slice mesh at 1700 Hz (≈ 25 % contact loss, switches located);
// * ltv: the Blankenship–Singh LTV mesh at 3000 Hz;
// for each integrator (rk8pd, generalized-α with ρ∞ = 0.9 and 1, rk8pd without event location)
// over its tolerance, the RMS DTE error against a converged reference (rk8pd at 1e-12) vs wall
// time, and the energy-balance error per period.
// Output: CSV `method, knob, wall_time_s, error, evaluations` (wp_common.hpp), then the energy
// errors as comments.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "geardyn/analyses/time_response.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"
#include "wp_common.hpp"

namespace {

using namespace geardyn;

TimeResponseOptions Options(TimeIntegrator method, double tol) {
  TimeResponseOptions o;
  o.integration.integrator = method;
  o.integration.relative_tolerance = o.integration.absolute_tolerance = tol;
  o.steady.tolerance = std::max(1e-10, 10.0 * tol);
  return o;
}

void Case(const char* name, const SystemModel& model, double f_m) {
  const TimeResponse ref =
      SimulateSteadyState(model, f_m, Options(TimeIntegrator::kRungeKutta, 1e-12));
  const double rms_ref = ref.meshes[0].rms_dte;
  std::printf("# %s: %d DOF, %.0f Hz, reference RMS DTE %.12e m (%s, %d periods)\n", name,
              model.num_dofs(), f_m, rms_ref, StatusName(ref.summary.status), ref.periods);
  struct Variant {
    std::string label;
    TimeIntegrator method;
    double rho;
    bool events;
    std::vector<double> tols;
  };
  const std::vector<Variant> variants = {
      {"rk8pd", TimeIntegrator::kRungeKutta, 0.9, true, {1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10}},
      {"rk8pd_no_events", TimeIntegrator::kRungeKutta, 0.9, false, {1e-6, 1e-8, 1e-10}},
      {"galpha_0.9", TimeIntegrator::kGeneralizedAlpha, 0.9, true, {1e-4, 1e-5, 1e-6, 1e-7}},
      {"galpha_1.0", TimeIntegrator::kGeneralizedAlpha, 1.0, true, {1e-4, 1e-5, 1e-6, 1e-7}},
  };
  std::printf("method,knob,wall_time_s,error,evaluations\n");
  std::vector<std::string> notes;
  for (const Variant& v : variants) {
    for (double tol : v.tols) {
      TimeResponseOptions o = Options(v.method, tol);
      o.integration.spectral_radius = v.rho;
      o.integration.locate_events = v.events;
      const TimeResponse r = SimulateSteadyState(model, f_m, o);
      const double err =
          r.summary.ok() ? std::abs(r.meshes[0].rms_dte - rms_ref) / rms_ref : std::nan("");
      const std::string label = std::string(name) + "_" + v.label;
      wp::Row(label.c_str(), tol, r.summary.wall_time_s, err,
              static_cast<double>(r.summary.counters.at("force_evaluations")));
      char buf[256];
      std::snprintf(buf, sizeof buf, "# %s tol %g: %d periods, %ld steps, %ld events, energy %.2e",
                    label.c_str(), tol, r.periods, r.steps, r.events, r.max_energy_error);
      notes.emplace_back(buf);
    }
  }
  for (const std::string& n : notes) std::printf("%s\n", n.c_str());
}

}  // namespace

int main() {
  const std::vector<std::string> common = {"mesh.pinion-wheel.damping_ratio=0.05"};
  auto scene = [&](std::vector<std::string> extra) {
    extra.insert(extra.end(), common.begin(), common.end());
    return MakeSystemModel(LoadScene("builtin:kahraman-blankenship-rig", extra));
  };
  Case("slices",
       scene({"mesh.pinion-wheel.model=\"slices\"", "mesh.pinion-wheel.slices=10",
              "mesh.pinion-wheel.center_distance=0.1502"}),
       1700.0);
  Case("ltv", scene({"mesh.pinion-wheel.model=\"blankenship_singh\""}), 3000.0);
  return 0;
}
