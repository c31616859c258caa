#include "geardyn/compare_runner.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "geardyn/analyses/harmonic_balance.hpp"
#include "geardyn/analyses/system_nonlinear_hb.hpp"
#include "geardyn/analyses/time_response.hpp"
#include "geardyn/common/check.hpp"
#include "geardyn/common/errors.hpp"
#include "geardyn/hb_report.hpp"
#include "geardyn/models/scene/mesh_model.hpp"
#include "geardyn/models/system/scene_system.hpp"
#include "geardyn/stability_chart_runner.hpp"
#include "geardyn/system/mesh_core.hpp"

namespace geardyn::app {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Floquet error target of the verdicts [-]: |λ| − 1 must be resolved, not 1e-10 (the linear hb's
// choice, hb_command.cpp kLinearStabilityTolerance).
constexpr double kFloquetTolerance = 1e-8;
// Default DTE grid: 0.2 … 2.5 × the operating mesh frequency, this many points (fewer than hb's
// 200: a comparison runs every level, and the time domain costs seconds per point).
constexpr int kDefaultGridPoints = 60;
// Up and down branches closer than this fraction of the peak are one branch.
constexpr double kBranchSplit = 1e-6;
// Stability charts: `geardyn stability-chart`'s defaults (a verdict per point, curves to 1e-3 of
// the axis span).
constexpr double kChartTolerance = 1e-6;
constexpr double kChartBoundaryTolerance = 1e-3;

double Seconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

class Progress {
 public:
  Progress(std::ostream* out, bool on) : out_(on ? out : nullptr) {}
  void Line(const std::string& text) const {
    if (out_ == nullptr) return;
    char t[32];
    std::snprintf(t, sizeof(t), "[%7.1f s] ", Seconds(start_));
    *out_ << "geardyn compare: " << t << text << "\n" << std::flush;
  }

 private:
  std::ostream* out_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

int MeshIndexOf(const SystemModel& model, const std::string& name) {
  for (int k = 0; k < model.num_meshes(); ++k) {
    if (model.meshes()[k].name == name) return k;
  }
  return -1;
}

// The first `count` modes of a result (frequencies, shapes, groups inside the range).
ModalResult FirstModes(const ModalResult& r, int count) {
  count = std::min<int>(count, static_cast<int>(r.frequencies_hz.size()));
  ModalResult out;
  out.frequencies_hz = r.frequencies_hz.head(count);
  out.eigenvalues = r.eigenvalues.head(count);
  out.shapes = r.shapes.leftCols(count);
  out.num_rigid_body_modes = std::min(r.num_rigid_body_modes, count);
  if (static_cast<int>(r.labels.size()) >= count) {
    out.labels.assign(r.labels.begin(), r.labels.begin() + count);
  }
  for (const std::vector<int>& g : r.multiplicity_groups) {
    std::vector<int> kept;
    for (const int k : g) {
      if (k < count) kept.push_back(k);
    }
    if (!kept.empty()) out.multiplicity_groups.push_back(kept);
  }
  return out;
}

// RMS (of the alternating part) and peak-to-peak of samples.
std::pair<double, double> RmsAndPeakToPeak(const Eigen::Ref<const VectorX>& x) {
  const double mean = x.mean();
  const double rms = std::sqrt((x.array() - mean).square().mean());
  return {rms, x.maxCoeff() - x.minCoeff()};
}

// ---------------------------------------------------------------------------- DTE per level

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
                       const CompareSettings& settings, const Progress& progress,
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
    on_progress = [&progress, &level, last](double fraction, const std::string&) mutable {
      if (Seconds(last) < 5.0) return;
      last = std::chrono::steady_clock::now();
      char line[64];
      std::snprintf(line, sizeof(line), "%.0f %%", 100.0 * fraction);
      progress.Line(level + ": simulate " + line);
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
        SimulateSteadyState(model, grid.front(), options.response, on_progress, nullptr);
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
    const TimeSweep sweep = SimulateSweep(model, grid, options, on_progress, nullptr);
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
      *why = "mesh '" + m.name + "' runs at another mesh frequency or phase than the first (its "
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
    parameters.transmission_error = ToFourier(
        TableCoefficient(epsilon, period), static_cast<int>(kSamplesPerMesh / 4 * period));
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

// ---------------------------------------------------------------------------- verdicts

std::string Percent(double x) {
  char s[32];
  std::snprintf(s, sizeof(s), "%+.3g %%", 100.0 * x);
  return s;
}

std::string Hz(double f) {
  char s[32];
  std::snprintf(s, sizeof(s), "%.4g Hz", f);
  return s;
}

bool FloquetDetermined(const FloquetResult& r) {
  return r.verdict != FloquetVerdict::kUndetermined && std::isfinite(r.max_abs_multiplier);
}

std::string ModeName(const ModalResult& r, int k) {
  std::string name = "mode " + std::to_string(k + 1);
  if (k < static_cast<int>(r.labels.size()))
    name += std::string(" (") + ToString(r.labels[k]) + ")";
  return name + " " + Hz(r.frequencies_hz(k));
}

const LevelRun* FindRun(const CompareResult& result, const std::string& level) {
  for (const LevelRun& r : result.runs) {
    if (r.level == level) return &r;
  }
  return nullptr;
}

std::string SkipReason(const LevelRun& run, CompareAnalysis a) {
  const auto it = run.skipped.find(a);
  return it != run.skipped.end() ? it->second : std::string("not run");
}

void CompareModes(const LevelRun& run, const LevelRun* ref, const CompareSettings& settings,
                  LevelComparison* c) {
  std::string& v = c->verdict[CompareAnalysis::kModes];
  if (!run.modes) {
    v = "skipped";
    c->notes.push_back("modes: skipped (" + SkipReason(run, CompareAnalysis::kModes) + ")");
    return;
  }
  if (ref == nullptr || !ref->modes) {
    v = "undetermined";
    c->notes.push_back("modes: undetermined (no reference level ran the modes)");
    return;
  }
  if (!run.modes->summary.ok() || !ref->modes->summary.ok()) {
    v = "undetermined";
    c->notes.push_back(
        std::string("modes: undetermined (") +
        (run.modes->summary.ok() ? "the reference's" : "its") +
        " modal analysis did not succeed: " +
        (run.modes->summary.ok() ? ref->modes->summary.message : run.modes->summary.message) + ")");
    return;
  }
  const ModalResult reference = FirstModes(*ref->modes, settings.num_modes);
  ModeMatchingOptions options;
  options.mac_threshold = settings.mac_threshold;
  c->modes = MatchModesByMac(reference, *run.modes, ref->mass, options);
  c->modes_max_in_plane = c->modes_max_out_of_plane = 0.0;
  for (const ModeMatch& m : c->modes->matches) {
    if (m.other < 0 || !std::isfinite(m.relative_difference) ||
        m.reference >= static_cast<int>(reference.labels.size())) {
      continue;
    }
    const ModeType type = reference.labels[m.reference];
    double& worst = type == ModeType::kAxial || type == ModeType::kRocking
                        ? c->modes_max_out_of_plane
                        : c->modes_max_in_plane;
    worst = std::max(worst, std::abs(m.relative_difference));
  }
  if (run.level == ref->level) {
    v = "reference";
    return;
  }
  int outside = 0, absent = 0;
  std::vector<std::string> lines;
  for (const ModeMatch& m : c->modes->matches) {
    if (m.other < 0) {
      ++absent;
      lines.push_back("  " + ModeName(reference, m.reference) + ": absent (best MAC " +
                      std::to_string(m.mac).substr(0, 4) + ")");
    } else if (!(std::abs(m.relative_difference) <= settings.frequency_tolerance)) {
      ++outside;
      lines.push_back("  " + ModeName(reference, m.reference) + ": " +
                      (std::isfinite(m.relative_difference) ? Percent(m.relative_difference)
                                                            : std::string("rigid vs not")) +
                      " (" + Hz(m.other_hz) + ", MAC " + std::to_string(m.mac).substr(0, 4) + ")");
    }
  }
  const int matched = c->modes->num_matched;
  const int total = static_cast<int>(c->modes->matches.size());
  if (outside == 0 && absent == 0) {
    v = "agrees";
    c->notes.push_back("modes: agrees — all " + std::to_string(total) + " modes matched (MAC ≥ " +
                       std::to_string(settings.mac_threshold).substr(0, 4) + "), max |Δf/f| " +
                       Percent(c->modes->max_abs_relative_difference).substr(1) + " ≤ " +
                       Percent(settings.frequency_tolerance).substr(1));
  } else {
    v = "differs";
    c->notes.push_back("modes: differs — " + std::to_string(matched) + "/" + std::to_string(total) +
                       " matched, " + std::to_string(outside) + " beyond ±" +
                       Percent(settings.frequency_tolerance).substr(1) + ", " +
                       std::to_string(absent) + " absent:");
    for (std::string& l : lines) c->notes.push_back(std::move(l));
  }
}

void CompareFloquet(const LevelRun& run, const LevelRun* ref, LevelComparison* c) {
  std::string& v = c->verdict[CompareAnalysis::kFloquet];
  if (!run.floquet) {
    v = "skipped";
    c->notes.push_back("floquet: skipped (" + SkipReason(run, CompareAnalysis::kFloquet) + ")");
    return;
  }
  const FloquetResult& f = *run.floquet;
  if (ref == nullptr || !ref->floquet || !FloquetDetermined(f) ||
      !FloquetDetermined(*ref->floquet)) {
    v = "undetermined";
    c->notes.push_back(std::string("floquet: undetermined (") +
                       (FloquetDetermined(f) ? "the reference's" : "its") + " verdict is " +
                       "undetermined: " +
                       (FloquetDetermined(f) && ref && ref->floquet ? ref->floquet->summary.message
                                                                    : f.summary.message) +
                       ")");
    return;
  }
  c->floquet_difference = f.max_abs_multiplier - ref->floquet->max_abs_multiplier;
  if (run.level == ref->level) {
    v = "reference";
    return;
  }
  const bool same = f.verdict == ref->floquet->verdict;
  v = same ? "agrees" : "differs";
  c->notes.push_back(std::string("floquet: ") + (same ? "agrees — " : "differs — ") +
                     ToString(f.verdict) + ", max|λ| " +
                     FormatMaxAbsMultiplier(f.max_abs_multiplier) + " vs the reference's " +
                     ToString(ref->floquet->verdict) + ", " +
                     FormatMaxAbsMultiplier(ref->floquet->max_abs_multiplier));
}

void CompareDte(const LevelRun& run, const LevelRun* ref, const CompareResult& result,
                const CompareSettings& settings, LevelComparison* c) {
  std::string& v = c->verdict[CompareAnalysis::kHb];
  if (!run.dte) {
    v = "skipped";
    c->notes.push_back("DTE: skipped (" +
                       SkipReason(run, run.skipped.count(CompareAnalysis::kHb)
                                           ? CompareAnalysis::kHb
                                           : CompareAnalysis::kSimulate) +
                       ")");
    return;
  }
  if (ref == nullptr || !ref->dte || !run.dte->summary.ok() || !ref->dte->summary.ok()) {
    v = "undetermined";
    const bool mine = !run.dte->summary.ok();
    c->notes.push_back(mine ? "DTE: undetermined (its " + run.dte->source +
                                  " did not succeed: " + run.dte->summary.message + ")"
                            : "DTE: undetermined (the reference " +
                                  (ref ? ref->level : std::string("level")) +
                                  " did not succeed: see its verdict)");
    return;
  }
  c->dte = CalcDteDifference(*run.dte, *ref->dte, result.frequencies_hz, settings.dte_tolerance);
  if (run.level == ref->level) {
    v = "reference";
    return;
  }
  const DteDifference& d = *c->dte;
  if (!std::isfinite(d.max_abs)) {
    v = "undetermined";
    c->notes.push_back("DTE: undetermined (no mesh frequency where both have a stable solution)");
    return;
  }
  std::string peak;
  if (d.reference_peak_hz > 0.0) {
    peak = "; peak " + Hz(d.peak_hz) + " vs " + Hz(d.reference_peak_hz) + " (" +
           Percent((d.peak_hz - d.reference_peak_hz) / d.reference_peak_hz) + "), height ×" +
           std::to_string(d.peak_ratio).substr(0, 5);
  }
  if (d.max_abs <= settings.dte_tolerance && d.missing == 0) {
    v = "agrees";
    c->notes.push_back("DTE: agrees — max |Δ RMS| " + Percent(d.max_abs).substr(1) +
                       " of the reference's peak ≤ " + Percent(settings.dte_tolerance).substr(1) +
                       peak);
    return;
  }
  v = "differs";
  std::string ranges;
  for (const auto& [lo, hi] : d.disagree_ranges) {
    ranges += (ranges.empty() ? "" : ", ") + (lo == hi ? Hz(lo) : Hz(lo) + "–" + Hz(hi));
  }
  c->notes.push_back("DTE: differs — max |Δ RMS| " + Percent(d.max_abs).substr(1) +
                     " of the reference's peak at " + Hz(d.max_at_hz) + " (" + d.max_where +
                     "), RMS " + Percent(d.rms).substr(1) + peak);
  if (!ranges.empty())
    c->notes.push_back("  beyond ±" + Percent(settings.dte_tolerance).substr(1) + " at " + ranges);
  if (d.missing > 0) {
    c->notes.push_back("  " + std::to_string(d.missing) +
                       " branch point(s) with a stable solution on one side only (a jump or a "
                       "range without a steady state)");
  }
}

LevelComparison CompareToReferences(const LevelRun& run, const CompareResult& result,
                                    const CompareSettings& settings) {
  LevelComparison c;
  c.level = run.level;
  const auto ref = [&](CompareAnalysis a) -> const LevelRun* {
    const auto it = result.reference.find(a);
    return it == result.reference.end() || it->second.empty() ? nullptr
                                                              : FindRun(result, it->second);
  };
  if (result.reference.count(CompareAnalysis::kModes)) {
    CompareModes(run, ref(CompareAnalysis::kModes), settings, &c);
  }
  if (result.reference.count(CompareAnalysis::kFloquet)) {
    CompareFloquet(run, ref(CompareAnalysis::kFloquet), &c);
  }
  if (result.reference.count(CompareAnalysis::kHb)) {
    CompareDte(run, ref(CompareAnalysis::kHb), result, settings, &c);
  }
  // Charts: the share of grid points with the reference's verdict.
  const LevelRun* chart_ref = nullptr;
  for (const LevelRun& r : result.runs) {
    if (r.chart && r.chart->summary.ok()) {
      chart_ref = &r;
      break;
    }
  }
  if (const auto it = result.reference.find(CompareAnalysis::kFloquet);
      it != result.reference.end() && !it->second.empty()) {
    const LevelRun* floquet_ref = FindRun(result, it->second);
    if (floquet_ref && floquet_ref->chart) chart_ref = floquet_ref;
  }
  if (chart_ref && run.chart && chart_ref->chart &&
      run.chart->stable.size() == chart_ref->chart->stable.size()) {
    int same = 0, compared = 0;
    for (std::size_t k = 0; k < run.chart->stable.size(); ++k) {
      if (!run.chart->ok[k] || !chart_ref->chart->ok[k]) continue;
      ++compared;
      same += run.chart->stable[k] == chart_ref->chart->stable[k];
    }
    c.chart_points = compared;
    if (compared > 0) {
      c.chart_agreement = static_cast<double>(same) / compared;
      if (run.level != chart_ref->level) {
        c.notes.push_back("chart: the reference's verdict at " +
                          Percent(c.chart_agreement).substr(1) + " of " + std::to_string(compared) +
                          " grid points");
      }
    }
  } else if (!run.chart_skipped.empty()) {
    c.notes.push_back("chart: skipped (" + run.chart_skipped + ")");
  }
  return c;
}

}  // namespace

void ValidateCompareSettings(const CompareSettings& s) {
  GEARDYN_THROW_UNLESS(s.num_modes >= 1 && s.num_modes <= 1000,
                       "--modes: must be in [1, 1000], got " << s.num_modes);
  GEARDYN_THROW_UNLESS(s.mac_threshold > 0.0 && s.mac_threshold <= 1.0,
                       "--mac-threshold: must be in (0, 1], got " << s.mac_threshold);
  GEARDYN_THROW_UNLESS(std::isfinite(s.frequency_tolerance) && s.frequency_tolerance > 0.0 &&
                           s.frequency_tolerance < 1.0,
                       "--frequency-tolerance: a relative frequency difference in (0, 1), got "
                           << s.frequency_tolerance);
  GEARDYN_THROW_UNLESS(
      std::isfinite(s.dte_tolerance) && s.dte_tolerance > 0.0 && s.dte_tolerance < 10.0,
      "--dte-tolerance: a DTE difference as a fraction of the reference's peak, in (0, 10), got "
          << s.dte_tolerance);
  GEARDYN_THROW_UNLESS(
      s.nonlinear_harmonics >= 1 && s.nonlinear_harmonics <= 512,
      "--harmonics: the nonlinear HB's H must be in [1, 512], got " << s.nonlinear_harmonics);
  GEARDYN_THROW_UNLESS(std::isfinite(s.simulate_tolerance) && s.simulate_tolerance >= 1e-14 &&
                           s.simulate_tolerance <= 1e-2,
                       "--simulate-tolerance: the local relative error per step must be in "
                       "[1e-14, 1e-2], got "
                           << s.simulate_tolerance);
  GEARDYN_THROW_UNLESS(std::isfinite(s.steady_tolerance) && s.steady_tolerance >= 1e-14 &&
                           s.steady_tolerance <= 1,
                       "--steady-tolerance: the period-to-period change must be in [1e-14, 1], got "
                           << s.steady_tolerance);
  GEARDYN_THROW_UNLESS(s.max_periods >= 1 && s.max_periods <= 10000000,
                       "--max-periods: must be in [1, 10000000], got " << s.max_periods);
  GEARDYN_THROW_UNLESS(!s.analyses.empty(), "--analyses: nothing to run");
  GEARDYN_THROW_UNLESS(s.chart_x.empty() == s.chart_y.empty(),
                       "--chart-x and --chart-y: give both axes of the stability chart");
  if (!s.chart_x.empty()) {
    GEARDYN_THROW_UNLESS(
        std::find(s.analyses.begin(), s.analyses.end(), CompareAnalysis::kFloquet) !=
            s.analyses.end(),
        "--chart-x: the stability charts are Floquet charts; add floquet to --analyses");
    ParseChartAxis("--chart-x", s.chart_x);
    ParseChartAxis("--chart-y", s.chart_y);
  }
  if (!s.reference.empty()) {
    GEARDYN_THROW_UNLESS(FindCompareLevel(s.reference) != nullptr,
                         "--reference: unknown level '" << s.reference << "'");
    GEARDYN_THROW_UNLESS(
        s.levels.empty() ||
            std::find(s.levels.begin(), s.levels.end(), s.reference) != s.levels.end(),
        "--reference: '" << s.reference << "' is not one of the compared --levels");
  }
}

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

CompareResult RunCompare(const Scene& scene, const CompareSettings& input,
                         std::ostream* progress_stream) {
  const auto start = std::chrono::steady_clock::now();
  CompareSettings settings = input;
  ValidateCompareSettings(settings);
  const Progress progress(progress_stream, settings.progress);
  GEARDYN_THROW_UNLESS(!scene.meshes.empty(),
                       scene.source << ": the scene has no mesh, so it has no model levels");
  CompareResult result;
  result.scene = scene.source;
  result.mesh = settings.mesh.empty() ? scene.meshes.front().name : settings.mesh;
  GEARDYN_THROW_UNLESS(std::any_of(scene.meshes.begin(), scene.meshes.end(),
                                   [&](const MeshDef& m) { return m.name == result.mesh; }),
                       "--mesh: the scene has no mesh '" << result.mesh << "'");
  const auto has = [&](CompareAnalysis a) {
    return std::find(settings.analyses.begin(), settings.analyses.end(), a) !=
           settings.analyses.end();
  };
  const bool wants_dte = has(CompareAnalysis::kHb) || has(CompareAnalysis::kSimulate);
  const bool levels_given = settings.levels_given && !settings.levels.empty();
  if (settings.levels.empty()) {
    // Defaults: every level but the contact model (seconds per speed: ask for it by name).
    for (const CompareLevelInfo& l : CompareLevels()) {
      if (l.name != "contact" && ParseMeshModelLevel(l.name)) settings.levels.push_back(l.name);
    }
  }
  GEARDYN_THROW_UNLESS(
      !(std::find(settings.levels.begin(), settings.levels.end(), "contact") !=
            settings.levels.end() &&
        !has(CompareAnalysis::kSimulate) && settings.levels.size() == 1),
      "--levels: the contact level has modes, Floquet and harmonic balance of none; it needs "
      "--analyses simulate");
  result.operating_mesh_frequency_hz = scene.MeshFrequencyHz(scene.meshes.front());
  if (wants_dte) {
    if (settings.mesh_frequency.empty()) {
      GEARDYN_THROW_UNLESS(result.operating_mesh_frequency_hz > 0.0,
                           "--mesh-frequency: required (the scene's operating speed is 0)");
      const double f0 = result.operating_mesh_frequency_hz;
      std::ostringstream spec;
      spec.precision(17);
      spec << 0.2 * f0 << ":" << 2.5 * f0 << ":" << kDefaultGridPoints;
      result.frequencies_hz = ParseMeshFrequencies(spec.str(), f0);
    } else {
      result.frequencies_hz =
          ParseMeshFrequencies(settings.mesh_frequency, result.operating_mesh_frequency_hz);
    }
    GEARDYN_THROW_UNLESS(std::is_sorted(result.frequencies_hz.begin(), result.frequencies_hz.end()),
                         "--mesh-frequency: must be ascending (lo:hi:n with lo <= hi)");
  }
  if (has(CompareAnalysis::kFloquet)) {
    GEARDYN_THROW_UNLESS(result.operating_mesh_frequency_hz > 0.0,
                         "--analyses floquet: the scene's mesh frequency is 0 (set "
                         "operating_point.speed_rpm > 0)");
  }

  for (const std::string& level : settings.levels) {
    const CompareLevelInfo& info = *FindCompareLevel(level);
    LevelRun run;
    run.level = level;
    progress.Line(level + ": building");
    const auto skip_all = [&](const std::string& why) {
      for (const CompareAnalysis a : settings.analyses) run.skipped[a] = why;
    };
    if (!ParseMeshModelLevel(level)) {
      GEARDYN_THROW_UNLESS(!levels_given,
                           "--levels: '" << level << "' is not available in this build");
      skip_all("not available in this build");
      result.runs.push_back(std::move(run));
      continue;
    }
    const Scene at_level = SceneAtLevel(scene, level);
    // One build per need: without ε for modes and Floquet (as `geardyn modes`/`floquet`), with
    // it for the DTE; the contact level only for the time domain.
    const auto build = [&](bool with_epsilon, bool time_domain) {
      SceneSystemOptions o;
      o.analysis = "compare (" + level + ")";
      o.transmission_error = with_epsilon;
      o.allow_contact_meshes = time_domain;
      o.runout_form = time_domain ? RunoutForm::kTable : RunoutForm::kAuto;
      return BuildSceneSystem(at_level, o);
    };
    std::optional<SceneSystem> operator_system;
    if (info.frequency_domain && (has(CompareAnalysis::kModes) || has(CompareAnalysis::kFloquet))) {
      try {
        operator_system = build(false, false);
      } catch (const InvalidInput& e) {
        GEARDYN_THROW_UNLESS(!levels_given, "--levels: the scene cannot be built at level '"
                                                << level << "': " << e.what());
        skip_all(std::string("the scene cannot be built at this level: ") + e.what());
        result.runs.push_back(std::move(run));
        continue;
      }
      run.num_dofs = operator_system->model.num_dofs();
      run.mass = operator_system->model.mass();
      for (const std::string& w : operator_system->warnings) run.warnings.push_back(w);
    }
    // ---- modes
    if (has(CompareAnalysis::kModes)) {
      if (!info.frequency_domain) {
        run.skipped[CompareAnalysis::kModes] = "a time-domain model only (no linear operator)";
      } else {
        progress.Line(level + ": modes");
        const auto t0 = std::chrono::steady_clock::now();
        ModalOptions options;
        const int n = operator_system->model.num_dofs();
        // Twice the reference's count, so that a mode that moved is still found.
        options.num_modes = std::min(n, 2 * settings.num_modes);
        options.compute_shapes = true;
        run.modes = ComputeModes(operator_system->model, options);
        run.modes_time_s = Seconds(t0);
        if (!run.modes->summary.ok()) result.ok = false;
      }
    }
    // ---- floquet
    if (has(CompareAnalysis::kFloquet)) {
      if (!info.frequency_domain) {
        run.skipped[CompareAnalysis::kFloquet] = "a time-domain model only (no linear operator)";
      } else {
        progress.Line(level + ": floquet");
        const auto t0 = std::chrono::steady_clock::now();
        FloquetOptions options;
        options.mesh_frequency_hz = result.operating_mesh_frequency_hz;
        options.tolerance = kFloquetTolerance;
        try {
          run.floquet = ComputeFloquet(operator_system->model, options);
          if (!run.floquet->summary.ok() || !FloquetDetermined(*run.floquet)) result.ok = false;
        } catch (const InvalidInput& e) {
          run.skipped[CompareAnalysis::kFloquet] = e.what();
        }
        run.floquet_time_s = Seconds(t0);
      }
    }
    // ---- stability chart
    if (has(CompareAnalysis::kFloquet) && !settings.chart_x.empty()) {
      if (!info.frequency_domain) {
        run.chart_skipped = "a time-domain model only (no linear operator)";
      } else {
        progress.Line(level + ": stability chart");
        const auto t0 = std::chrono::steady_clock::now();
        SceneChartSettings chart;
        chart.scene = settings.scene_path;
        chart.overrides = settings.overrides;
        for (const MeshDef& m : scene.meshes) {
          chart.overrides.push_back("mesh." + m.name + ".model=" + level);
        }
        chart.x = ParseChartAxis("--chart-x", settings.chart_x);
        chart.y = ParseChartAxis("--chart-y", settings.chart_y);
        chart.floquet.tolerance = kChartTolerance;
        chart.chart.num_threads = settings.threads;
        chart.chart.boundary_tolerance = kChartBoundaryTolerance;
        try {
          SceneChart c = ComputeSceneStabilityChart(chart);
          if (!c.chart.summary.ok()) result.ok = false;
          for (const std::string& w : c.warnings) run.warnings.push_back("chart: " + w);
          run.chart = std::move(c.chart);
        } catch (const InvalidInput& e) {
          GEARDYN_THROW_UNLESS(!levels_given,
                               "--chart-x/--chart-y at level '" << level << "': " << e.what());
          run.chart_skipped = e.what();
        }
        run.chart_time_s = Seconds(t0);
      }
    }
    // ---- DTE
    if (wants_dte) {
      const bool by_hb = has(CompareAnalysis::kHb) && info.frequency_domain;
      const bool by_time = !by_hb && has(CompareAnalysis::kSimulate);
      if (!by_hb && !by_time) {
        run.skipped[CompareAnalysis::kHb] =
            "no harmonic balance at this level; add --analyses simulate for its time-domain DTE";
      } else {
        std::optional<SceneSystem> forced;
        try {
          if (level == "lti") {
            std::string why;
            if (std::optional<Scene> loaded = LtiWithLoadedSte(scene, &why)) {
              SceneSystemOptions o;
              o.analysis = "compare (lti)";
              o.allow_contact_meshes = false;
              forced = BuildSceneSystem(*loaded, o);
              run.warnings.push_back(
                  "excited by the loaded static TE of blankenship_singh at the operating "
                  "torque (mean stiffness, scalar TE; Kahraman 1993)");
            } else {
              run.warnings.push_back("excited by the scene's unloaded TE only (" + why +
                                     "): the stiffness variation under load is not in it");
            }
          }
          if (!forced) forced = build(true, by_time);
        } catch (const InvalidInput& e) {
          GEARDYN_THROW_UNLESS(!levels_given, "--levels: the scene cannot be built at level '"
                                                  << level << "': " << e.what());
          run.skipped[by_hb ? CompareAnalysis::kHb : CompareAnalysis::kSimulate] =
              std::string("the scene cannot be built at this level: ") + e.what();
        }
        if (forced) {
          for (const std::string& w : forced->warnings) {
            if (std::find(run.warnings.begin(), run.warnings.end(), w) == run.warnings.end()) {
              run.warnings.push_back(w);
            }
          }
          run.num_dofs = forced->model.num_dofs();
          const int mesh = MeshIndexOf(forced->model, result.mesh);
          GEARDYN_DEMAND(mesh >= 0);
          progress.Line(level + ": DTE over " + std::to_string(result.frequencies_hz.size()) +
                        " mesh frequencies (" +
                        (by_time       ? "time domain"
                         : info.linear ? "linear hb"
                                       : "nonlinear hb") +
                        ")");
          LevelDte dte = by_time ? TimeDomainDte(forced->model, mesh, result.frequencies_hz,
                                                 settings, progress, level)
                         : info.linear
                             ? LinearDte(forced->model, mesh, result.frequencies_hz, &run.warnings)
                             : NonlinearDte(forced->model, mesh, result.frequencies_hz, settings);
          dte.multivalued = IsMultivalued(dte);
          if (!dte.summary.ok()) result.ok = false;
          for (const std::string& w : dte.summary.warnings) run.warnings.push_back(w);
          run.dte = std::move(dte);
        }
      }
      // The DTE is one comparison; its source names the analysis that ran.
      if (run.dte) {
        run.skipped.erase(CompareAnalysis::kHb);
        run.skipped.erase(CompareAnalysis::kSimulate);
      } else if (!has(CompareAnalysis::kHb)) {
        run.skipped.erase(CompareAnalysis::kHb);
      }
    }
    result.runs.push_back(std::move(run));
  }

  // ---- references: the user's, else the most detailed level that ran the analysis.
  const auto ran = [&](const LevelRun& r, CompareAnalysis a) {
    switch (a) {
      case CompareAnalysis::kModes:
        return r.modes.has_value();
      case CompareAnalysis::kFloquet:
        return r.floquet.has_value();
      case CompareAnalysis::kHb:
      case CompareAnalysis::kSimulate:
        return r.dte.has_value();
    }
    return false;
  };
  const auto succeeded = [&](const LevelRun& r, CompareAnalysis a) {
    switch (a) {
      case CompareAnalysis::kModes:
        return r.modes && r.modes->summary.ok();
      case CompareAnalysis::kFloquet:
        return r.floquet && r.floquet->summary.ok() && FloquetDetermined(*r.floquet);
      case CompareAnalysis::kHb:
      case CompareAnalysis::kSimulate:
        return r.dte && r.dte->summary.ok();
    }
    return false;
  };
  const std::vector<CompareAnalysis> kinds = {CompareAnalysis::kModes, CompareAnalysis::kFloquet,
                                              CompareAnalysis::kHb};
  for (const CompareAnalysis a : kinds) {
    if (a == CompareAnalysis::kHb ? !wants_dte : !has(a)) continue;
    std::string ref;
    if (!settings.reference.empty()) {
      const auto it = std::find_if(result.runs.begin(), result.runs.end(), [&](const LevelRun& r) {
        return r.level == settings.reference;
      });
      GEARDYN_THROW_UNLESS(it != result.runs.end() && ran(*it, a),
                           "--reference: level '"
                               << settings.reference << "' did not run "
                               << (a == CompareAnalysis::kHb ? "the DTE" : ToString(a)) << " ("
                               << (it == result.runs.end() ? "not run"
                                   : it->skipped.count(a)  ? it->skipped.at(a)
                                                           : "skipped")
                               << ")");
      ref = settings.reference;
    } else {
      // The most detailed level whose run succeeded; a failed one is compared (undetermined)
      // but cannot be the yardstick of the others.
      std::string first_ran;
      for (const LevelRun& r : result.runs) {
        if (!ran(r, a)) continue;
        if (first_ran.empty()) first_ran = r.level;
        if (succeeded(r, a)) {
          ref = r.level;
          break;
        }
      }
      if (ref.empty()) {
        ref = first_ran;
      } else if (ref != first_ran) {
        result.warnings.push_back(std::string("reference of the ") +
                                  (a == CompareAnalysis::kHb ? "DTE" : ToString(a)) + ": " + ref +
                                  ", because the more detailed " + first_ran +
                                  " did not succeed (its verdict is undetermined)");
      }
    }
    result.reference[a] = ref;
  }

  // ---- comparisons
  for (const LevelRun& run : result.runs) {
    result.comparisons.push_back(CompareToReferences(run, result, settings));
  }
  result.wall_time_s = Seconds(start);
  return result;
}

}  // namespace geardyn::app
