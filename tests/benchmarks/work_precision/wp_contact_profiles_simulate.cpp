// Work-precision of the contact profile at the simulate level (issue 14: "RMS DTE error vs wall
// time ... for exact involute vs biarc contact, against a converged reference"):
// `builtin:kahraman-blankenship-rig` with model = "contact" (rigid teeth, Kim's law, 100 N·m) at
// 2000 Hz, integrated from the static equilibrium for a fixed 20 mesh periods (the contact model's
// own damping is light: it is not steady within hundreds of periods, so every run covers the same
// transient), then one period recorded. Reference: exact involute, rk8pd at tolerance 1e-11.
// Error = RMS over the recorded samples of DTE − DTE_ref, relative to the reference's RMS DTE.
// Runs: exact at tolerances 1e-6 … 1e-9; biarc N = 2 … 32 at 1e-8 (the integrator then
// contributes ≈ the exact row's error at 1e-8).
// Output: CSV `method, knob, wall_time_s, error, evaluations` (knob: tolerance for exact, N for
// biarc), then comments with steps, events and the energy-balance error.
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

constexpr double kMeshFrequency = 2000.0;  // Hz
constexpr int kPeriods = 20;

SystemModel Rig(int arcs) {
  std::vector<std::string> set = {"mesh.pinion-wheel.model=\"contact\""};
  if (arcs > 0) {
    set.push_back("mesh.pinion-wheel.contact.profile=\"biarc\"");
    set.push_back("mesh.pinion-wheel.contact.arcs=" + std::to_string(arcs));
  }
  SceneSystemOptions so;
  so.analysis = "wp_contact_profiles_simulate";
  so.allow_contact_meshes = true;
  return MakeSystemModel(LoadScene("builtin:kahraman-blankenship-rig", set), so);
}

TimeResponse Run(const SystemModel& model, double tol) {
  TimeResponseOptions o;
  o.integration.integrator = TimeIntegrator::kRungeKutta;
  o.integration.relative_tolerance = o.integration.absolute_tolerance = tol;
  o.steady.tolerance = 1e-14;  // never steady: exactly kPeriods periods, then the record
  o.steady.min_periods = kPeriods;
  o.steady.max_periods = kPeriods;
  return SimulateSteadyState(model, kMeshFrequency, o);
}

}  // namespace

int main() {
  const SystemModel exact = Rig(0);
  const TimeResponse ref = Run(exact, 1e-11);
  const VectorX& dte_ref = ref.meshes[0].dte;
  const double rms_ref = ref.meshes[0].rms_dte;
  std::printf("# reference: %ld samples, RMS DTE %.9e m, %ld steps, %ld events, %.2f s, %s\n",
              static_cast<long>(dte_ref.size()), rms_ref, ref.steps, ref.events,
              ref.summary.wall_time_s, ref.summary.message.c_str());
  std::printf("method,knob,wall_time_s,error,evaluations\n");
  std::vector<std::string> notes;
  auto report = [&](const char* method, double knob, const TimeResponse& r) {
    const VectorX& d = r.meshes[0].dte;
    const double err =
        d.size() == dte_ref.size()
            ? std::sqrt((d - dte_ref).squaredNorm() / static_cast<double>(d.size())) / rms_ref
            : std::nan("");
    wp::Row(method, knob, r.summary.wall_time_s, err,
            static_cast<double>(r.summary.counters.at("force_evaluations")));
    char buf[256];
    std::snprintf(buf, sizeof buf,
                  "# %s %g: %ld steps, %ld events, energy error %.2e, RMS DTE %.9e m", method, knob,
                  r.steps, r.events, r.max_energy_error, r.meshes[0].rms_dte);
    notes.emplace_back(buf);
  };
  for (const double tol : {1e-6, 1e-7, 1e-8, 1e-9}) report("exact", tol, Run(exact, tol));
  for (const int n : {2, 4, 8, 16, 32}) report("biarc", n, Run(Rig(n), 1e-8));
  for (const std::string& s : notes) std::printf("%s\n", s.c_str());
  return 0;
}
