/// @file
/// @brief TraceSystemNonlinearHb and SolveSystemNonlinearHb (system_nonlinear_hb.hpp): the
/// engine of nonlinear_hb.hpp on MakeSystemNhbProblem, outputs by SystemPointDescriber.
#include <chrono>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <limits>
#include <numbers>
#include <sstream>
#include <vector>

#include "geardyn/analyses/floquet.hpp"
#include "geardyn/analyses/modal.hpp"
#include "geardyn/analyses/system_nonlinear_hb.hpp"
#include "geardyn/common/check.hpp"
#include "system_nhb/system_outputs.hpp"

namespace geardyn {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

/// "mesh frequency 562.3456 Hz" for Ω = 2π f_m [rad/s] (messages speak the CLI's units).
std::string MeshFrequencyText(double omega) {
  std::ostringstream s;
  s << std::setprecision(10) << "mesh frequency " << omega / kTwoPi << " Hz";
  return s.str();
}

/// The mode of the model (mean mesh stiffness) that harmonic j = 1..H of the base frequency
/// f_m/p is nearest to at f_m, as a sentence for the undamped-resonance message.
std::string NameResonantMode(const SystemModel& model, double mesh_hz, int period_multiple,
                             int harmonics) {
  ModalOptions mo;
  mo.compute_shapes = false;
  const ModalResult modes = ComputeModes(model, mo);
  int best_mode = -1, best_j = 0;
  double best = std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < modes.frequencies_hz.size(); ++i) {
    const double f = modes.frequencies_hz[i];
    if (!(f > 0.0)) continue;
    for (int j = 1; j <= harmonics; ++j) {
      const double d = std::abs(j * mesh_hz / period_multiple - f) / f;
      if (d < best) {
        best = d;
        best_mode = static_cast<int>(i);
        best_j = j;
      }
    }
  }
  std::ostringstream s;
  s << std::setprecision(6);
  if (best_mode < 0) return "no elastic mode found to name";
  s << "nearest: mode " << best_mode + 1 << " at " << modes.frequencies_hz[best_mode] << " Hz";
  if (!modes.labels.empty()) s << " (" << ToString(modes.labels[best_mode]) << ")";
  s << ", met by harmonic " << best_j << " of the " << (period_multiple > 1 ? "base" : "mesh")
    << " frequency (" << best_j * mesh_hz / period_multiple << " Hz; the nonlinear branch's "
    << "frequency differs from the mean-stiffness mode's by the clearance nonlinearity)";
  return s.str();
}

/// Why a damped branch grows without bound (NhbCurve::unbounded_branches), checked on the
/// model: at amplitudes far above the backlash the clearance law acts on both flanks as the
/// linear time-varying mesh (every slice loaded), whose periodic response is unbounded at the
/// edges of its parametric instability regions. The Floquet verdict of the linear model on
/// 2·kScan + 1 frequencies within ±kSpan of the asymptote gives the stability edge nearest to it,
/// or says none was found.
std::string ExplainUnboundedBranch(const SystemModel& model, double asymptote_hz) {
  constexpr int kScan = 12;
  constexpr double kSpan = 0.03;
  FloquetOptions fo;
  fo.tolerance = 1e-8;
  std::vector<double> f(2 * kScan + 1);
  std::vector<FloquetResult> r;
  for (int i = 0; i <= 2 * kScan; ++i) {
    f[i] = asymptote_hz * (1.0 + kSpan * (i - kScan) / kScan);
    fo.mesh_frequency_hz = f[i];
    r.push_back(ComputeFloquet(model, fo));
  }
  std::ostringstream s;
  s << std::setprecision(6);
  int best = -1;
  for (int i = 0; i < 2 * kScan; ++i) {
    const bool a = r[i].verdict == FloquetVerdict::kUnstable;
    const bool b = r[i + 1].verdict == FloquetVerdict::kUnstable;
    if (a == b || r[i].verdict == FloquetVerdict::kUndetermined ||
        r[i + 1].verdict == FloquetVerdict::kUndetermined) {
      continue;
    }
    const double mid = 0.5 * (f[i] + f[i + 1]);
    if (best < 0 ||
        std::abs(mid - asymptote_hz) < std::abs(0.5 * (f[best] + f[best + 1]) - asymptote_hz)) {
      best = i;
    }
  }
  if (best < 0) {
    s << "the linear time-varying model (every slice loaded) shows no parametric-instability "
      << "edge within " << 100 * kSpan << " % of it (Floquet on " << 2 * kScan + 1
      << " frequencies): cause not identified";
    return s.str();
  }
  const int u = r[best].verdict == FloquetVerdict::kUnstable ? best : best + 1;
  s << "the linear time-varying model (every slice loaded), which the two-flank mesh approaches "
    << "at amplitudes far above the backlash, has a parametric-instability edge between " << f[best]
    << " and " << f[best + 1] << " Hz (Floquet: max |lambda| = " << r[u].max_abs_multiplier
    << " at " << f[u] << " Hz): physics, not a numerical failure";
  return s.str();
}

void CheckOptions(const SystemNhbOptions& options) {
  std::string why;
  GEARDYN_THROW_UNLESS(options.IsValid(&why), "nonlinear harmonic balance options: " << why);
}

/// With tooth errors the period is P = period_meshes mesh cycles and H counts harmonics of
/// ω_m/(p·P), so the mesh frequency is harmonic p·P: an H below it leaves the mesh excitation out
/// of the basis and returns the errors' low harmonics alone with status success (issue 12: the
/// rig with a 5 µm runout, P = 50, default H = 24). The H = 0 tolerance loop starts at H = 4 or 8
/// and may stop there for the same reason, so it is refused too.
void CheckHarmonicsContainTheMesh(const NhbOptions& hb, int period_meshes) {
  if (period_meshes <= 1) return;
  const std::int64_t mesh_harmonic =
      static_cast<std::int64_t>(hb.period_multiple) * static_cast<std::int64_t>(period_meshes);
  GEARDYN_THROW_UNLESS(
      hb.harmonics >= mesh_harmonic,
      "hb.harmonics: H = " << hb.harmonics << (hb.harmonics == 0 ? " (chosen by tolerance)" : "")
                           << " is below the mesh harmonic " << mesh_harmonic
                           << ": the tooth errors repeat every P = " << period_meshes
                           << " mesh cycles, H counts harmonics of f_mesh/" << mesh_harmonic
                           << ", and the mesh frequency would not be in the basis; give H = k·"
                           << mesh_harmonic << " for k mesh orders");
}

}  // namespace

bool SystemNhbOptions::IsValid(std::string* why) const {
  std::ostringstream s;
  std::string inner;
  if (!hb.IsValid(&inner)) {
    s << "hb." << inner;
  } else if (!(std::isfinite(start_hz) && start_hz > 0.0)) {
    s << "start_hz: must be a finite mesh frequency > 0 Hz, got " << start_hz;
  } else if (!(std::isfinite(end_hz) && end_hz > 0.0) || end_hz == start_hz) {
    s << "end_hz: must be a finite mesh frequency > 0 Hz different from start_hz, got " << end_hz;
  } else {
    NhbContinuationOptions c = continuation;
    c.omega_start = kTwoPi * start_hz;
    c.omega_end = kTwoPi * end_hz;
    if (c.IsValid(&inner)) return true;
    s << "continuation." << inner;
  }
  if (why) *why = s.str();
  return false;
}

SystemNhbCurve TraceSystemNonlinearHb(const SystemModel& model, const SystemNhbOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  CheckOptions(options);
  const SystemNhbProblem sp = MakeSystemNhbProblem(model);
  CheckHarmonicsContainTheMesh(options.hb, sp.period_meshes);
  NhbOptions hb = options.hb;
  hb.period_multiple *= sp.period_meshes;
  NhbContinuationOptions c = options.continuation;
  c.omega_start = kTwoPi * options.start_hz;
  c.omega_end = kTwoPi * options.end_hz;
  if (!c.omega_text) c.omega_text = MeshFrequencyText;
  const NhbCurve curve = TraceNonlinearHarmonicBalance(sp.problem, hb, c);

  SystemNhbCurve out;
  out.harmonics_used = curve.harmonics_used;
  out.period_multiple = hb.period_multiple;
  out.summary = curve.summary;
  if (sp.problem.damping.isZero(0.0)) {
    // Said first: every resonance crossed is unbounded, and a failed trace is explained by it.
    out.summary.warnings.insert(
        out.summary.warnings.begin(),
        "the model has no damping (no mesh damping or damping_ratio, no element damping): the "
        "periodic response is unbounded at every resonance the range crosses, and the "
        "continuation may climb a vertical branch or loop; give the meshes a damping_ratio");
    // (No mode is named here: away from a vertical branch the nearest (mode, harmonic) pair
    // among all H harmonics is a coincidence, not a diagnosis.)
    if (!out.summary.ok()) out.summary.message += " (the model has no damping)";
  }
  if (curve.undamped_resonance_omega > 0.0) {
    out.summary.message += "; " + NameResonantMode(model, curve.undamped_resonance_omega / kTwoPi,
                                                   hb.period_multiple, curve.harmonics_used);
  }
  {
    size_t k = 0;
    for (std::string& w : out.summary.warnings) {
      if (w.rfind("the branch grows without bound", 0) != 0 ||
          k >= curve.unbounded_branches.size()) {
        continue;
      }
      const double hz = curve.unbounded_branches[k++][0] / kTwoPi;
      out.unbounded_branches_hz.push_back(hz);
      w += "; " + ExplainUnboundedBranch(model, hz);
    }
  }
  for (const std::string& w : sp.warnings) out.summary.warnings.push_back(w);
  internal::SystemPointDescriber describer(model, sp, hb, options.compute_element_forces,
                                           options.keep_response);
  out.points.reserve(curve.points.size());
  for (const NhbPoint& p : curve.points) out.points.push_back(describer.Describe(p));
  // The ends as requested (2π f / 2π may differ from f in the last bit).
  if (!out.points.empty() && curve.points.front().omega == c.omega_start) {
    out.points.front().mesh_frequency_hz = options.start_hz;
  }
  if (!out.points.empty() && curve.points.back().omega == c.omega_end) {
    out.points.back().mesh_frequency_hz = options.end_hz;
  }
  for (const NhbFold& f : curve.folds) {
    out.fold_frequencies_hz.push_back(f.omega / kTwoPi);
    out.fold_errors_hz.push_back(f.omega_error / kTwoPi);
  }
  for (const NhbJump& j : curve.jumps) {
    SystemNhbJump sj;
    sj.up_sweep = j.up_sweep;
    sj.mesh_frequency_hz = j.omega / kTwoPi;
    sj.rms_dte_before = j.rms_before;
    sj.rms_dte_after = j.rms_after;
    sj.rms_dte_landings = j.rms_landings;
    out.jumps.push_back(sj);
  }
  out.summary.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

SystemNhbPoint SolveSystemNonlinearHb(const SystemModel& model, double mesh_frequency_hz,
                                      const SystemNhbOptions& options, Summary* summary) {
  GEARDYN_THROW_UNLESS(std::isfinite(mesh_frequency_hz) && mesh_frequency_hz > 0.0,
                       "mesh_frequency_hz: must be finite and > 0, got " << mesh_frequency_hz);
  std::string why;
  GEARDYN_THROW_UNLESS(options.hb.IsValid(&why), "nonlinear harmonic balance options: hb." << why);
  const SystemNhbProblem sp = MakeSystemNhbProblem(model);
  CheckHarmonicsContainTheMesh(options.hb, sp.period_meshes);
  NhbOptions hb = options.hb;
  hb.period_multiple *= sp.period_meshes;
  const NhbSolveResult r =
      SolveNonlinearHarmonicBalance(sp.problem, kTwoPi * mesh_frequency_hz, hb);
  internal::SystemPointDescriber describer(model, sp, hb, options.compute_element_forces,
                                           options.keep_response);
  SystemNhbPoint out = describer.Describe(r.point);
  if (summary) {
    *summary = r.summary;
    for (const std::string& w : sp.warnings) summary->warnings.push_back(w);
  }
  return out;
}

}  // namespace geardyn
