// Work-precision of the time integrators on the tooth-body rig (issue 14: "RMS DTE error vs wall
// time for each integrator, against a converged reference"): `builtin:kahraman-blankenship-rig`
// with model = "contact", Kim's type-A teeth (revolute, k_b = 11.5e3 N·m/rad, c_b = 2e-4
// N·m·s/rad, Kim Table 3), Kim's law, 100 N·m, 2000 Hz. From the static equilibrium, one period
// of the core (P = 50 mesh cycles: every tooth is distinct) integrated, then one period recorded
// (64 samples per mesh cycle): a fixed 100 mesh cycles per run, the same transient for all.
// Reference: rk8pd at tolerance 1e-9. Error = RMS over the recorded samples of DTE − DTE_ref,
// relative to the reference's RMS DTE.
// Usage: wp_tooth_bodies [teeth] — teeth "revolute" (default) or "bushing" (type B).
// Output: CSV `method, knob, wall_time_s, error, evaluations` (knob: tolerance), then comments
// with steps, rejected steps, events, the wall time per mesh cycle and the energy-balance error.
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

SystemModel Rig(const std::string& teeth) {
  const std::vector<std::string> set = {"mesh.pinion-wheel.model=\"contact\"",
                                        "mesh.pinion-wheel.contact.teeth=\"" + teeth + "\"",
                                        "mesh.pinion-wheel.contact.bending_stiffness=11.5e3",
                                        "mesh.pinion-wheel.contact.bending_damping=2e-4"};
  SceneSystemOptions so;
  so.analysis = "wp_tooth_bodies";
  so.allow_contact_meshes = true;
  return MakeSystemModel(LoadScene("builtin:kahraman-blankenship-rig", set), so);
}

TimeResponse Run(const SystemModel& model, TimeIntegrator method, double tol,
                 int sparse_threshold = kSparseStateThreshold) {
  TimeResponseOptions o;
  o.integration.sparse_threshold = sparse_threshold;
  o.integration.integrator = method;
  o.integration.relative_tolerance = o.integration.absolute_tolerance = tol;
  // Generalized-α takes minutes per mesh cycle here: capped, it reports "max_steps" instead.
  o.integration.max_steps = method == TimeIntegrator::kGeneralizedAlpha ? 200000 : 100000000;
  o.steady.tolerance = 1e-14;  // never steady: exactly one period, then the record
  o.steady.min_periods = 1;
  o.steady.max_periods = 1;
  return SimulateSteadyState(model, kMeshFrequency, o);
}

}  // namespace

int main(int argc, char** argv) {
  const std::string teeth = argc > 1 ? argv[1] : "revolute";
  const SystemModel model = Rig(teeth);
  const TimeResponse ref = Run(model, TimeIntegrator::kRungeKutta, 1e-9);
  const VectorX& dte_ref = ref.meshes[0].dte;
  const double rms_ref = ref.meshes[0].rms_dte;
  const double cycles = 2.0 * static_cast<double>(model.period_meshes());
  std::printf("# %s teeth, reference: %ld samples, RMS DTE %.9e m, %ld steps, %ld events, %.2f s\n",
              teeth.c_str(), static_cast<long>(dte_ref.size()), rms_ref, ref.steps, ref.events,
              ref.summary.wall_time_s);
  std::printf("method,knob,wall_time_s,error,evaluations\n");
  std::vector<std::string> notes;
  auto report = [&](const char* method, double knob, const TimeResponse& r) {
    // A failed run (e.g. max_steps) records nothing: no meshes.
    const VectorX d = r.meshes.empty() ? VectorX() : r.meshes[0].dte;
    const double rms = r.meshes.empty() ? std::nan("") : r.meshes[0].rms_dte;
    const double err =
        d.size() == dte_ref.size()
            ? std::sqrt((d - dte_ref).squaredNorm() / static_cast<double>(d.size())) / rms_ref
            : std::nan("");
    const auto count = [&](const char* key) {
      const auto it = r.summary.counters.find(key);
      return it == r.summary.counters.end() ? -1L : static_cast<long>(it->second);
    };
    wp::Row(method, knob, r.summary.wall_time_s, err,
            static_cast<double>(count("force_evaluations")));
    char buf[320];
    std::snprintf(buf, sizeof buf,
                  "# %s %g: %ld steps, %ld rejected, %ld events, %.2f ms per mesh cycle, energy "
                  "error %.2e, RMS DTE %.9e m, %s",
                  method, knob, r.steps, count("rejected_steps"), r.events,
                  1e3 * r.summary.wall_time_s / cycles, r.max_energy_error, rms,
                  r.summary.message.c_str());
    notes.emplace_back(buf);
    std::fflush(stdout);
  };
  report("reference rk8pd", 1e-9, ref);
  for (const double tol : {1e-4, 1e-5, 1e-6, 1e-7})
    report("rk8pd", tol, Run(model, TimeIntegrator::kRungeKutta, tol));
  for (const double tol : {1e-3, 1e-4})
    report("generalized-alpha", tol, Run(model, TimeIntegrator::kGeneralizedAlpha, tol));
  // Generalized-α with the sparse tangents and SparseLU at 112 coordinates too.
  for (const double tol : {1e-3, 1e-4})
    report("generalized-alpha sparse", tol,
           Run(model, TimeIntegrator::kGeneralizedAlpha, tol, /*sparse_threshold=*/1));
  for (const std::string& s : notes) std::printf("%s\n", s.c_str());
  return 0;
}
