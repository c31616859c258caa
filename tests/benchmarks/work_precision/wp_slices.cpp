// Work-precision benchmark of the slice mesh core (spec 01 §4.4; architecture §3.10): slice count
// N vs the error of its linear limit (Σk_s, Σk_sσ_s, Σk_sσ_s²) against the analytic contact lines
// (K, K·h, K·μ·b²) (spec 01 §4.1, closed-form clipped-line integrals).
//
// Prints CSV `method, knob, wall_time_s, error, evaluations` (lines starting with '#' are
// comments). knob = N. For each scene (spur: constant k, exact steps; helical: tooth-like k(r),
// 256-sample table):
//  * <scene>_K, <scene>_h, <scene>_mu — error = max over the 256 exact table phases of
//    |Δc|/(K̄ b^c) for c = K, K·h, K·μ·b²; wall_time_s = one EvalSliceForce call (new θ each
//    call, every slice loaded); evaluations = N slice terms per call.
//  * <scene>_mu_offgrid — the same for μ at the midpoints between table samples: what an analysis
//    sees between samples (slicing + linear interpolation of k_s(θ)).
//  * <scene>_build — wall_time_s = MakeSliceMeshCore; error = the μ error; evaluations = band
//    integrals computed (N × phases).
//  * <scene>_contact_lines — the reference: ContactLineModel::CalcChannels per θ, error 0.
// A '#' line per scene gives the observed orders log2(e_N/e_2N).
//
// Run: build with -DCMAKE_BUILD_TYPE=Release -DGEARDYN_BUILD_BENCHMARKS=ON, then
//   ./tests/benchmarks/wp_slices > wp_slices.csv
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "geardyn/common/units.hpp"
#include "geardyn/models/gear/gear_geometry.hpp"
#include "geardyn/models/mesh/mesh_cores.hpp"
#include "geardyn/system/mesh_core.hpp"
#include "wp_common.hpp"

namespace {

using geardyn::wp::TimeIt;

using geardyn::MeshCoreSource;
using geardyn::SliceMeshCore;
using geardyn::Vector3;
constexpr double kTwoPi = 2.0 * geardyn::kPi;
constexpr int kPhases = 256;

void Row(const std::string& method, double knob, double time, double error, double evaluations) {
  geardyn::wp::Row(method.c_str(), knob, time, error, evaluations);
}

MeshCoreSource Source(bool helical) {
  geardyn::GearPairSpec s;
  s.normal_module = 2.5e-3;
  s.normal_pressure_angle = geardyn::DegToRad(20.0);
  s.helix_angle = geardyn::DegToRad(helical ? 18.0 : 0.0);
  s.pinion_hand = helical ? geardyn::HelixHand::kRight : geardyn::HelixHand::kNone;
  s.pinion.teeth = 23;
  s.gear.teeth = 61;
  s.pinion.face_width = 0.030;
  s.gear.face_width = 0.030;
  const geardyn::GearPairGeometry g = geardyn::CalcGearPairGeometry(s);
  if (!helical) return geardyn::MakeMeshCoreSource(g, geardyn::StiffnessPerUnitLength{1.4e10});
  const double len = g.line_of_action_length;
  return geardyn::MakeMeshCoreSource(
      g, geardyn::StiffnessProfile::PiecewiseLinear({0.0, 0.3 * len, 0.7 * len, len},
                                                    {0.6e10, 1.4e10, 1.4e10, 0.7e10}));
}

/// Max over phases of |Δc|/(K̄ b^c), c = 0, 1, 2; phases θ_i = 2π(i + offset)/kPhases.
Vector3 Errors(const MeshCoreSource& source, const SliceMeshCore& core, double offset) {
  geardyn::SliceMeshWorkspace ws(core);
  const double b = source.contact_lines.half_face_width();
  std::vector<Vector3> exact(kPhases), slices(kPhases);
  double mean_k = 0.0;
  for (int i = 0; i < kPhases; ++i) {
    const double theta = kTwoPi * (i + offset) / kPhases;
    source.contact_lines.CalcChannels(theta, exact[i]);
    slices[i] = geardyn::EvalSliceChannels(core, ws, theta);
    mean_k += exact[i][0] / kPhases;
  }
  Vector3 err = Vector3::Zero();
  for (int i = 0; i < kPhases; ++i) {
    for (int c = 0; c < 3; ++c) {
      err[c] = std::max(err[c], std::abs(slices[i][c] - exact[i][c]) / (mean_k * std::pow(b, c)));
    }
  }
  return err;
}

void RunScene(const std::string& name, bool helical) {
  const MeshCoreSource source = Source(helical);
  const geardyn::ZoneOfAction& zone = source.contact_lines.zone();
  std::printf("# %s: eps_alpha %.4f, eps_beta %.4f, beta_b %.3f deg, p_bt %.4f mm, B %.1f mm\n",
              name.c_str(), zone.transverse_contact_ratio(), zone.overlap_ratio(),
              geardyn::RadToDeg(std::abs(zone.base_helix_angle)), 1e3 * zone.transverse_base_pitch,
              1e3 * zone.face_width);
  geardyn::SliceCoefficientOptions options;
  options.num_samples = kPhases;  // kAuto: exact steps (spur) or a 256-sample table (helical)
  {
    Vector3 c;
    double theta = 0.0;
    const double t = TimeIt([&] {
      for (int i = 0; i < 1000; ++i) source.contact_lines.CalcChannels(theta += 0.0123, c);
    });
    Row(name + "_contact_lines", 0, t / 1000, 0.0, 1);
  }
  std::vector<int> counts;
  std::vector<Vector3> errors;
  for (int n = 2; n <= 256; n *= 2) {
    SliceMeshCore core = geardyn::MakeSliceMeshCore(source, n, options);
    const double t_build = TimeIt([&] { core = geardyn::MakeSliceMeshCore(source, n, options); });
    geardyn::SliceMeshWorkspace ws(core);
    double theta = 0.0, sink = 0.0;
    const double t_force =
        TimeIt([&] {
          for (int i = 0; i < 1000; ++i) {
            sink += geardyn::EvalSliceForce(core, ws, theta += 0.0123, 1e-3, 0.0).force[0];
          }
        }) /
        1000;
    if (!(sink > 0.0)) std::printf("# unexpected: no load\n");
    const Vector3 e = Errors(source, core, 0.0);
    const Vector3 e_off = Errors(source, core, 0.5);
    counts.push_back(n);
    errors.push_back(e);
    Row(name + "_K", n, t_force, e[0], n);
    Row(name + "_h", n, t_force, e[1], n);
    Row(name + "_mu", n, t_force, e[2], n);
    Row(name + "_mu_offgrid", n, t_force, e_off[2], n);
    const int build_phases =
        helical ? kPhases : static_cast<int>(source.contact_lines.Breakpoints().size());
    Row(name + "_build", n, t_build, e[2], static_cast<double>(n) * build_phases);
  }
  for (int c = 1; c < 3; ++c) {
    std::printf("# %s observed orders of %s:", name.c_str(), c == 1 ? "K*h" : "K*mu*b^2");
    for (size_t i = 0; i + 1 < counts.size(); ++i) {
      const double ratio = errors[i][c] / errors[i + 1][c];
      if (errors[i + 1][c] > 0.0 && errors[i][c] > 1e-14) {
        std::printf(" %d->%d %.2f", counts[i], counts[i + 1], std::log2(ratio));
      }
    }
    std::printf("\n");
  }
}

}  // namespace

int main() {
  std::printf("method,knob,wall_time_s,error,evaluations\n");
  RunScene("spur", false);
  RunScene("helical", true);
  return 0;
}
