// The DTE of one level over the mesh-frequency grid for `geardyn compare` (compare_runner.hpp):
// linear HB, traced nonlinear HB read along both sweep branches, time-domain sweeps; the LTI
// level's loaded-STE excitation; the difference of two levels' curves.
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "geardyn/analyses/harmonic_balance.hpp"
#include "geardyn/analyses/system_nonlinear_hb.hpp"
#include "geardyn/analyses/time_response.hpp"
#include "geardyn/common/check.hpp"
#include "geardyn/compare_internal.hpp"
#include "geardyn/interrupt.hpp"
#include "geardyn/models/scene/mesh_model.hpp"
#include "geardyn/models/system/scene_system.hpp"
#include "geardyn/system/mesh_core.hpp"

namespace geardyn::app {
namespace compare_internal {
namespace {

std::pair<double, double> RmsAndPeakToPeak(const Eigen::Ref<const VectorX>& x) {
  const double mean = x.mean();
  const double rms = std::sqrt((x.array() - mean).square().mean());
  return {rms, x.maxCoeff() - x.minCoeff()};
}

}  // namespace

LevelDte LinearDte(const SystemModel& model, int mesh, const std::vector<double>& grid,
                   std::vector<std::string>* warnings) {
  LevelDte out;
  out.source = "linear hb";
  const auto start = std::chrono::steady_clock::now();
  HbOptions options;  // H from the default tolerance, as `geardyn hb`
  const auto* linear = std::get_if<LinearMeshCore>(&model.meshes()[mesh].core);
  const bool add_epsilon = linear != nullptr && linear->has_transmission_error();
  options.keep_harmonics = add_epsilon;
  options.compute_forces = false;
  options.cancel = CancelFlag();
  const HbSweepResult sweep = SweepHarmonicBalance(model, grid, options);
  out.summary = sweep.summary;
  bool warned = false;
  for (const HbResult& p : sweep.points) {
    double rms = p.meshes[mesh].rms_dte, p2p = p.meshes[mesh].peak_to_peak_dte;
    if (add_epsilon) {
      if (p.dte_samples.cols() > 0) {
        // δ_η = DTE + ε_η(θ_k) at θ_s = 2πP s/S (harmonic_balance.hpp).
        const int S = static_cast<int>(p.dte_samples.cols());
        VectorX loaded(S);
        const SystemMesh& m = model.meshes()[mesh];
        for (int s = 0; s < S; ++s) {
          const double theta =
              2.0 * std::numbers::pi * static_cast<double>(p.period_meshes) * s / S;
          loaded(s) =
              p.dte_samples(mesh, s) + EvalTransmissionError(*linear, m.MeshPhase(theta))(0);
        }
        std::tie(rms, p2p) = RmsAndPeakToPeak(loaded);
      } else if (!warned) {
        warned = true;
        warnings->push_back(
            "linear hb: sparse harmonics (a long hunting period) keep no DTE samples, so the "
            "compared quantity is the DTE δ_η − ε_η, not the loaded TE δ_η");
      }
    }
    out.rms_up.push_back(rms);
    out.peak_to_peak_up.push_back(p2p);
  }
  out.rms_down = out.rms_up;
  out.peak_to_peak_down = out.peak_to_peak_up;
  out.wall_time_s = Seconds(start);
  return out;
}

LevelDte NonlinearDte(const SystemModel& model, int mesh, const std::vector<double>& grid,
                      const CompareSettings& settings) {
  LevelDte out;
  out.source = "nonlinear hb";
  const auto start = std::chrono::steady_clock::now();
  SystemNhbOptions options;
  options.hb.harmonics = settings.nonlinear_harmonics;
  options.continuation.branch_search = settings.branch_search;
  options.compute_element_forces = false;
  std::vector<SystemNhbPoint> points;
  const int n = static_cast<int>(grid.size());
  if (n == 1) {
    Summary summary;
    points.push_back(SolveSystemNonlinearHb(model, grid.front(), options, &summary));
    out.summary = summary;
  } else {
    options.start_hz = grid.front();
    options.end_hz = grid.back();
    // As `geardyn hb`: n sets the resolution (a step changes f_m by at most 1/n of the range).
    options.continuation.max_omega_step = 2.0 * std::numbers::pi * (grid.back() - grid.front()) / n;
    options.continuation.initial_step = std::min(options.continuation.initial_step, 1.0 / n);
    options.continuation.max_points = std::max(options.continuation.max_points, 20 * n);
    options.continuation.cancel = CancelFlag();
    SystemNhbCurve curve = TraceSystemNonlinearHb(model, options);
    out.summary = curve.summary;
    points = std::move(curve.points);
    for (const SystemNhbJump& j : curve.jumps) out.jumps_hz.push_back(j.mesh_frequency_hz);
  }
  std::vector<double> p2p;
  for (const SystemNhbPoint& p : points) {
    out.curve_hz.push_back(p.mesh_frequency_hz);
    out.curve_rms.push_back(p.meshes[mesh].rms_dte);
    p2p.push_back(p.meshes[mesh].peak_to_peak_dte);
    out.curve_stable.push_back(p.point.stable == FloquetVerdict::kStable     ? 1
                               : p.point.stable == FloquetVerdict::kUnstable ? 0
                                                                             : -1);
    out.curve_segment.push_back(p.point.segment);
  }
  if (n == 1) {
    const bool stable = !points.empty() && out.curve_stable.front() == 1;
    out.rms_up = {stable ? out.curve_rms.front() : kNaN};
    out.peak_to_peak_up = {stable ? p2p.front() : kNaN};
    out.rms_down = out.rms_up;
    out.peak_to_peak_down = out.peak_to_peak_up;
  } else {
    ResampleNhbBranches(out.curve_hz, out.curve_rms, p2p, out.curve_stable, out.curve_segment, grid,
                        &out.rms_up, &out.rms_down, &out.peak_to_peak_up, &out.peak_to_peak_down);
  }
  out.wall_time_s = Seconds(start);
  return out;
}

LevelDte TimeDomainDte(const SystemModel& model, int mesh, const std::vector<double>& grid,
                       const CompareSettings& settings, const ProgressLine& progress_line,
                       const std::string& level) {
  LevelDte out;
  out.source = "simulate";
  const auto start = std::chrono::steady_clock::now();
  TimeSweepOptions options;
  options.response.integration.relative_tolerance = settings.simulate_tolerance;
  options.response.steady.max_periods = settings.max_periods;
  options.response.steady.tolerance = settings.steady_tolerance;
  options.response.steady.min_periods =
      std::min(options.response.steady.min_periods, settings.max_periods);
  options.response.integration.record_element_forces = false;
  const int n = static_cast<int>(grid.size());
  out.rms_up.assign(n, kNaN);
  out.rms_down.assign(n, kNaN);
  out.peak_to_peak_up.assign(n, kNaN);
  out.peak_to_peak_down.assign(n, kNaN);
  TimeProgress on_progress;
  if (settings.progress) {
    auto last = std::chrono::steady_clock::now() - std::chrono::hours(1);
    on_progress = [&progress_line, &level, last](double fraction, const std::string&) mutable {
      if (Seconds(last) < 5.0) return;
      last = std::chrono::steady_clock::now();
      char line[64];
      std::snprintf(line, sizeof(line), "%.0f %%", 100.0 * fraction);
      progress_line(level + ": simulate " + line);
    };
  }
  const auto keep = [&](const TimeSweepPoint& p, int k, bool up) {
    const bool steady = p.status == Status::kSuccess && p.steady == SteadyVerdict::kSteady;
    (up ? out.rms_up : out.rms_down)[k] = steady ? p.rms_dte[mesh] : kNaN;
    (up ? out.peak_to_peak_up : out.peak_to_peak_down)[k] =
        steady ? p.peak_to_peak_dte[mesh] : kNaN;
  };
  if (n == 1) {
    const TimeResponse r =
        SimulateSteadyState(model, grid.front(), options.response, on_progress, CancelFlag());
    out.summary = r.summary;
    TimeSweepPoint p;
    p.status = r.summary.status;
    p.steady = r.steady;
    for (const MeshTimeHistory& h : r.meshes) {
      p.rms_dte.push_back(h.rms_dte);
      p.peak_to_peak_dte.push_back(h.peak_to_peak_dte);
    }
    keep(p, 0, true);
    keep(p, 0, false);
  } else {
    const TimeSweep sweep = SimulateSweep(model, grid, options, on_progress, CancelFlag());
    out.summary = sweep.summary;
    for (const TimeSweepPoint& p : sweep.points) {
      const auto it = std::lower_bound(grid.begin(), grid.end(),
                                       p.mesh_frequency_hz - 1e-9 * std::abs(p.mesh_frequency_hz));
      if (it == grid.end()) continue;
      keep(p, static_cast<int>(it - grid.begin()), p.branch == SweepBranch::kUp);
    }
  }
  out.wall_time_s = Seconds(start);
  return out;
}

// The LTI level as the LTI models of the literature use it (Kahraman 1993; B–S §5.3: "the
// excitation term independent of K_o(θ*)"): the mean operator K̄2, excited by the LOADED static
// transmission error of the B–S model at the operating torque. With the mean stiffness alone and
// the scene's ε (the unloaded, kinematic TE), an unmodified pair would have no excitation at all:
// its whine comes from the stiffness variation under load, which the loaded STE carries. Per
// mesh: a slow roll of the B–S model (SimulateQuasiStatic, kSamplesPerMesh samples per mesh
// cycle over its period P) gives δ_η(θ) and the static force pair F(θ); the scalar TE
// ε_η = δ_η − (K̄2⁺F)_η, ε_ζ = 0 (the scalar TE of B–S Eq. 42) makes the LTI model's static
// deflection reproduce the loaded STE. The mesh then carries these as user [mesh.parameters]
// (constant K̄2 channels, ε table), its modifications and errors being inside the loaded STE.
// Returns nullopt (with the reason) where this cannot be done; the caller keeps the scene's lti.
constexpr int kSamplesPerMesh = 256;
constexpr std::int64_t kMaxLoadedSteMeshes = 64;

std::optional<Scene> LtiWithLoadedSte(const Scene& scene, std::string* why) {
  SceneSystemOptions o;
  o.analysis = "compare (lti: loaded static TE of blankenship_singh)";
  const SceneSystem bs = BuildSceneSystem(SceneAtLevel(scene, "blankenship_singh"), o);
  const SystemModel& model = bs.model;
  const std::int64_t period = model.period_meshes();
  if (period > kMaxLoadedSteMeshes) {
    *why = "the loaded static TE repeats over " + std::to_string(period) +
           " mesh cycles (more than " + std::to_string(kMaxLoadedSteMeshes) + " are not rolled)";
    return std::nullopt;
  }
  for (const SystemMesh& m : model.meshes()) {
    if (m.phase_ratio != 1.0 || m.phase_offset != 0.0) {
      *why = "mesh '" + m.name +
             "' runs at another mesh frequency or phase than the first (its "
             "loaded STE is sampled on the system phase)";
      return std::nullopt;
    }
  }
  QuasiStaticOptions qs;
  qs.samples_per_mesh = kSamplesPerMesh;
  qs.check_next_cycle = false;
  const QuasiStaticResult roll = SimulateQuasiStatic(model, qs);
  if (!roll.summary.ok()) {
    *why = "the slow roll of blankenship_singh did not succeed: " + roll.summary.message;
    return std::nullopt;
  }
  Scene out = SceneAtLevel(scene, "lti");
  for (int k = 0; k < model.num_meshes(); ++k) {
    const SystemMesh& mesh = model.meshes()[k];
    const QuasiStaticMesh& q = roll.meshes[k];
    const Matrix2& K = mesh.mean_core_stiffness;  // K̄2 [[K, −Kh], [−Kh, Kμb²]]
    const Eigen::CompleteOrthogonalDecomposition<Matrix2> pinv(K);
    const int S = static_cast<int>(q.loaded_te.size());
    MatrixX epsilon = MatrixX::Zero(2, S);
    for (int s = 0; s < S; ++s) {
      epsilon(0, s) = q.loaded_te(s) - pinv.solve(Vector2(q.force_pair.col(s)))(0);
    }
    auto it = std::find_if(out.meshes.begin(), out.meshes.end(),
                           [&](const MeshDef& d) { return d.name == mesh.name; });
    GEARDYN_DEMAND(it != out.meshes.end());
    UserMeshParameters parameters;
    parameters.stiffness = ConstantCoefficient(Vector3(K(0, 0), -K(0, 1), K(1, 1)));
    // Its trigonometric interpolant with a quarter of the samples' harmonics: the table's linear
    // interpolation has kinks whose 1/k² tail keeps the HB's H search from converging.
    parameters.transmission_error = ToFourier(TableCoefficient(epsilon, period),
                                              static_cast<int>(kSamplesPerMesh / 4 * period));
    it->model.parameters = std::move(parameters);
    it->model.stiffness_per_length.reset();
    it->model.modifications = ToothModifications{};
    ToothErrors no_errors;
    no_errors.pinion_teeth = it->model.errors.pinion_teeth;
    no_errors.gear_teeth = it->model.errors.gear_teeth;
    it->model.errors = no_errors;
  }
  return out;
}

bool IsMultivalued(const LevelDte& d) {
  double peak = 0.0;
  for (std::size_t k = 0; k < d.rms_up.size(); ++k) {
    if (std::isfinite(d.rms_up[k])) peak = std::max(peak, d.rms_up[k]);
    if (std::isfinite(d.rms_down[k])) peak = std::max(peak, d.rms_down[k]);
  }
  for (std::size_t k = 0; k < d.rms_up.size(); ++k) {
    if (std::isfinite(d.rms_up[k]) && std::isfinite(d.rms_down[k]) &&
        std::abs(d.rms_up[k] - d.rms_down[k]) > kBranchSplit * peak) {
      return true;
    }
  }
  return false;
}

}  // namespace compare_internal

using compare_internal::kBranchSplit;
using compare_internal::kNaN;

void ResampleNhbBranches(const std::vector<double>& hz, const std::vector<double>& rms,
                         const std::vector<double>& p2p, const std::vector<int>& stable,
                         const std::vector<int>& segment, const std::vector<double>& grid,
                         std::vector<double>* up, std::vector<double>* down,
                         std::vector<double>* up_p2p, std::vector<double>* down_p2p) {
  const std::size_t n = grid.size();
  // Stable intersections (rms, p2p) at every grid frequency.
  std::vector<std::vector<std::pair<double, double>>> cuts(n);
  for (std::size_t k = 0; k + 1 < hz.size(); ++k) {
    if (segment[k] != segment[k + 1] || stable[k] != 1 || stable[k + 1] != 1) continue;
    const double a = std::min(hz[k], hz[k + 1]), b = std::max(hz[k], hz[k + 1]);
    for (std::size_t g = 0; g < n; ++g) {
      const double f = grid[g];
      if (f < a || f > b) continue;
      const double t = b > a ? (f - hz[k]) / (hz[k + 1] - hz[k]) : 0.0;
      cuts[g].emplace_back(rms[k] + t * (rms[k + 1] - rms[k]), p2p[k] + t * (p2p[k + 1] - p2p[k]));
    }
  }
  const auto sweep = [&](bool ascending, std::vector<double>* r, std::vector<double>* p) {
    r->assign(n, kNaN);
    p->assign(n, kNaN);
    double previous = kNaN;
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t g = ascending ? i : n - 1 - i;
      if (cuts[g].empty()) {
        previous = kNaN;
        continue;
      }
      std::size_t best = 0;
      for (std::size_t c = 1; c < cuts[g].size(); ++c) {
        const bool better = std::isfinite(previous) ? std::abs(cuts[g][c].first - previous) <
                                                          std::abs(cuts[g][best].first - previous)
                                                    : cuts[g][c].first < cuts[g][best].first;
        if (better) best = c;
      }
      (*r)[g] = cuts[g][best].first;
      (*p)[g] = cuts[g][best].second;
      previous = (*r)[g];
    }
  };
  sweep(true, up, up_p2p);
  sweep(false, down, down_p2p);
}

DteDifference CalcDteDifference(const LevelDte& level, const LevelDte& reference,
                                const std::vector<double>& grid, double tolerance) {
  DteDifference out;
  const std::size_t n = grid.size();
  double ref_peak = 0.0, level_peak = 0.0;
  std::size_t ref_peak_at = 0, level_peak_at = 0;
  for (std::size_t k = 0; k < n; ++k) {
    for (const double v : {reference.rms_up[k], reference.rms_down[k]}) {
      if (std::isfinite(v) && v > ref_peak) ref_peak = v, ref_peak_at = k;
    }
    for (const double v : {level.rms_up[k], level.rms_down[k]}) {
      if (std::isfinite(v) && v > level_peak) level_peak = v, level_peak_at = k;
    }
  }
  out.reference_peak_hz = grid[ref_peak_at];
  out.peak_hz = grid[level_peak_at];
  out.peak_ratio = ref_peak > 0.0 ? level_peak / ref_peak : kNaN;
  out.up.assign(n, kNaN);
  out.down.assign(n, kNaN);
  double sum2 = 0.0;
  int count = 0;
  out.max_abs = kNaN;
  std::vector<bool> outside(n, false);
  for (std::size_t k = 0; k < n; ++k) {
    for (int branch = 0; branch < 2; ++branch) {
      const double l = branch == 0 ? level.rms_up[k] : level.rms_down[k];
      const double r = branch == 0 ? reference.rms_up[k] : reference.rms_down[k];
      if (std::isfinite(l) != std::isfinite(r)) ++out.missing;
      if (!std::isfinite(l) || !std::isfinite(r) || !(ref_peak > 0.0)) continue;
      const double d = (l - r) / ref_peak;
      (branch == 0 ? out.up : out.down)[k] = d;
      sum2 += d * d;
      ++count;
      if (!std::isfinite(out.max_abs) || std::abs(d) > out.max_abs) {
        out.max_abs = std::abs(d);
        out.max_at_hz = grid[k];
        const bool jump =
            std::abs(level.rms_up[k] - level.rms_down[k]) > kBranchSplit * ref_peak ||
            std::abs(reference.rms_up[k] - reference.rms_down[k]) > kBranchSplit * ref_peak;
        // A resonance: within two grid points of a local maximum of either curve.
        const auto near_peak = [&](const std::vector<double>& y) {
          for (std::size_t j = (k >= 2 ? k - 2 : 0); j <= std::min(n - 1, k + 2); ++j) {
            const double left = j > 0 ? y[j - 1] : -1.0;
            const double right = j + 1 < n ? y[j + 1] : -1.0;
            if (std::isfinite(y[j]) && y[j] >= left && y[j] >= right && j > 0 && j + 1 < n) {
              return true;
            }
          }
          return false;
        };
        out.max_where = jump                                                     ? "jump"
                        : near_peak(reference.rms_up) || near_peak(level.rms_up) ? "resonance"
                                                                                 : "off resonance";
      }
      if (std::abs(d) > tolerance) outside[k] = true;
    }
  }
  out.rms = count > 0 ? std::sqrt(sum2 / count) : kNaN;
  for (std::size_t k = 0; k < n; ++k) {
    if (!outside[k]) continue;
    if (k > 0 && outside[k - 1]) {
      out.disagree_ranges.back().second = grid[k];
    } else {
      out.disagree_ranges.emplace_back(grid[k], grid[k]);
    }
  }
  return out;
}

}  // namespace geardyn::app
