#include "geardyn/quasi_static.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "geardyn/analyses/time_response.hpp"
#include "geardyn/common/check.hpp"

namespace geardyn::app {
namespace {

// Relative difference of K and STE one mesh cycle apart accepted as "identical teeth" [-]: the
// static solves converge to round-off, so anything above 1e-6 is a real tooth-to-tooth change.
constexpr double kCyclePeriodicityTol = 1e-6;

}  // namespace

QuasiStaticResult ComputeQuasiStatic(const SystemModel& model,
                                     const std::vector<double>& half_face_widths, int samples) {
  GEARDYN_THROW_UNLESS(samples >= 1 && samples <= kMaxQuasiStaticSamples,
                       "--samples-per-period: the quasi-static samples per mesh cycle must be in "
                       "[1, "
                           << kMaxQuasiStaticSamples << "], got " << samples);
  GEARDYN_THROW_UNLESS(model.num_meshes() > 0, "--quasi-static: the scene has no mesh");
  GEARDYN_CHECK_SIZE(static_cast<int>(half_face_widths.size()), model.num_meshes(),
                     "half_face_widths");
  for (const SystemMesh& mesh : model.meshes()) {
    // Linear and slice cores repeat over more than one mesh cycle only through tooth errors. A
    // contact core counts its teeth apart (P = tooth-count period) even when they are identical:
    // checked after the roll (the engine's next_cycle_change).
    const bool contact_core =
        std::holds_alternative<std::shared_ptr<const NonlinearMeshCore>>(mesh.core);
    GEARDYN_THROW_UNLESS(contact_core || PeriodMeshes(mesh.core) == 1,
                         "--quasi-static: mesh "
                             << mesh.name << " repeats over " << PeriodMeshes(mesh.core)
                             << " mesh cycles (tooth errors), but a [mesh.parameters] table holds "
                                "one mesh cycle; drop the tooth errors ([mesh.errors])");
  }
  QuasiStaticOptions options;
  options.samples_per_mesh = samples;
  options.sampling = QuasiStaticSampling::kMeshCycle;
  options.check_next_cycle = true;
  const geardyn::QuasiStaticResult engine = SimulateQuasiStatic(model, options);
  QuasiStaticResult result;
  result.summary = engine.summary;
  if (!engine.summary.ok()) result.summary.message = "static solve: " + engine.summary.message;
  for (std::size_t k = 0; k < engine.meshes.size(); ++k) {
    const geardyn::QuasiStaticMesh& e = engine.meshes[k];
    const SystemMesh& mesh = model.meshes()[k];
    if (engine.summary.ok() && PeriodMeshes(mesh.core) > 1) {
      // The cycle after: the same K and STE at θ_k + 2π, or the teeth differ.
      GEARDYN_THROW_UNLESS(e.next_cycle_change <= kCyclePeriodicityTol,
                           "--quasi-static: mesh "
                               << mesh.name << ": the next mesh cycle differs (relative change "
                               << e.next_cycle_change
                               << " of K or STE; NaN: its static solve failed): the teeth are not "
                                  "identical, and a [mesh.parameters] table holds one mesh cycle");
    }
    QuasiStaticMesh out;
    MeshParameterSamples& p = out.parameters;
    p.mesh = e.name;
    p.half_face_width = half_face_widths[k];
    for (Eigen::Index s = 0; s < e.loaded_te.size(); ++s) {
      p.stiffness.push_back(std::max(0.0, e.stiffness(0, s)));
      p.stiffness_h.push_back(e.stiffness(1, s));
      p.stiffness_mu_b2.push_back(e.stiffness(2, s));
      p.transmission_error.push_back(e.transmission_error(s));
      out.loaded_ste.push_back(e.loaded_te(s));
      out.force.push_back(e.force_pair(0, s));
    }
    result.meshes.push_back(std::move(out));
  }
  return result;
}

}  // namespace geardyn::app
