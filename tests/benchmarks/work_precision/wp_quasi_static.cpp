// Work-precision of the quasi-static run (SimulateQuasiStatic, kMeshCycle: the `geardyn simulate
// --quasi-static` path) on `builtin:kahraman-blankenship-rig` with model = "contact" (Kim's law,
// 100 N·m), rigid teeth and type-A (revolute, Kim's k_b = 11.5e3 N·m/rad) teeth. The knob is the
// number S of samples per mesh cycle. Reference: S = 1024 of the same model. Errors, relative:
// mean K (the mesh-cycle mean of the sampled K(θ), what the LTV table and the --overlay-hb match
// use) and the RMS of the loaded STE about its mean (what drives the dynamic response); the worse
// of the two is the CSV error, both are printed in the comments. The static solves themselves
// converge to round-off: the error is the sampling of a K(θ) that jumps where a pair enters or
// leaves contact.
// Output: CSV `method, knob, wall_time_s, error, evaluations` (evaluations = static solves).
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

constexpr int kReferenceSamples = 1024;

SystemModel Rig(bool revolute) {
  std::vector<std::string> set = {"mesh.pinion-wheel.model=\"contact\""};
  if (revolute) {
    set.push_back("mesh.pinion-wheel.contact.teeth=\"revolute\"");
    set.push_back("mesh.pinion-wheel.contact.bending_stiffness=11.5e3");
  }
  SceneSystemOptions so;
  so.analysis = "wp_quasi_static";
  so.allow_contact_meshes = true;
  return MakeSystemModel(LoadScene("builtin:kahraman-blankenship-rig", set), so);
}

struct Stats {
  double mean_k = 0.0, rms_ste = 0.0, wall = 0.0;
  long solves = 0;
  bool ok = false;
};

Stats Run(const SystemModel& model, int samples) {
  QuasiStaticOptions o;
  o.samples_per_mesh = samples;
  o.sampling = QuasiStaticSampling::kMeshCycle;
  o.check_next_cycle = false;
  const QuasiStaticResult r = SimulateQuasiStatic(model, o);
  Stats s;
  s.ok = r.summary.ok();
  const QuasiStaticMesh& m = r.meshes.at(0);
  s.mean_k = m.stiffness.row(0).mean();
  const double mean = m.loaded_te.mean();
  s.rms_ste = std::sqrt((m.loaded_te.array() - mean).square().mean());
  s.wall = r.summary.wall_time_s;
  s.solves = r.summary.counters.at("static_solves");
  return s;
}

}  // namespace

int main() {
  std::printf("method,knob,wall_time_s,error,evaluations\n");
  std::vector<std::string> notes;
  for (const bool revolute : {false, true}) {
    const char* method = revolute ? "type_a" : "rigid";
    const SystemModel model = Rig(revolute);
    const Stats ref = Run(model, kReferenceSamples);
    char buf[256];
    std::snprintf(buf, sizeof buf,
                  "# %s reference S = %d: mean K %.9e N/m, RMS STE %.9e m, %.2f s (%s)", method,
                  kReferenceSamples, ref.mean_k, ref.rms_ste, ref.wall, ref.ok ? "ok" : "FAILED");
    notes.emplace_back(buf);
    for (const int s : {8, 16, 32, 64, 128, 256}) {
      const Stats r = Run(model, s);
      const double ek = std::abs(r.mean_k - ref.mean_k) / ref.mean_k;
      const double es = std::abs(r.rms_ste - ref.rms_ste) / ref.rms_ste;
      wp::Row(method, s, r.wall, std::max(ek, es), static_cast<double>(r.solves));
      std::snprintf(buf, sizeof buf, "# %s S = %d: mean K error %.2e, RMS STE error %.2e%s", method,
                    s, ek, es, r.ok ? "" : " (FAILED)");
      notes.emplace_back(buf);
    }
  }
  for (const std::string& n : notes) std::printf("%s\n", n.c_str());
  return 0;
}
