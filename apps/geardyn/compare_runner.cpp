#include "geardyn/compare_runner.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "geardyn/common/check.hpp"
#include "geardyn/common/errors.hpp"
#include "geardyn/compare_internal.hpp"
#include "geardyn/hb_report.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"
#include "geardyn/overlay_match.hpp"
#include "geardyn/stability_chart_runner.hpp"
#include "geardyn/system/mesh_core.hpp"

namespace geardyn::app {
namespace {

using namespace compare_internal;

// Floquet error target of the verdicts [-]: |λ| − 1 must be resolved, not 1e-10 (the linear hb's
// choice, hb_command.cpp kLinearStabilityTolerance).
constexpr double kFloquetTolerance = 1e-8;
// Default DTE grid: 0.2 … 2.5 × the operating mesh frequency, this many points (fewer than hb's
// 200: a comparison runs every level, and the time domain costs seconds per point).
constexpr int kDefaultGridPoints = 60;
// Stability charts: `geardyn stability-chart`'s defaults (a verdict per point, curves to 1e-3 of
// the axis span).
constexpr double kChartTolerance = 1e-6;
constexpr double kChartBoundaryTolerance = 1e-3;

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
  GEARDYN_THROW_UNLESS(s.branch_search >= 0 && s.branch_search <= 1000,
                       "--branch-search: must be in [0, 1000], got " << s.branch_search);
  GEARDYN_THROW_UNLESS(std::isfinite(s.simulate_tolerance) && s.simulate_tolerance >= 1e-14 &&
                           s.simulate_tolerance <= 1e-2,
                       "--simulate-tolerance: the local relative error per step must be in "
                       "[1e-14, 1e-2], got "
                           << s.simulate_tolerance);
  GEARDYN_THROW_UNLESS(
      std::isfinite(s.steady_tolerance) && s.steady_tolerance >= 1e-14 && s.steady_tolerance <= 1,
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

CompareResult RunCompare(const Scene& scene, const CompareSettings& input,
                         std::ostream* progress_stream) {
  const auto start = std::chrono::steady_clock::now();
  CompareSettings settings = input;
  ValidateCompareSettings(settings);
  const Progress progress(progress_stream, settings.progress);
  const bool oscillator = scene.oscillator.has_value();
  GEARDYN_THROW_UNLESS(oscillator || !scene.meshes.empty(),
                       scene.source << ": the scene has no mesh, so it has no model levels");
  CompareResult result;
  result.scene = scene.source;
  result.dimensionless = oscillator;
  if (oscillator) {
    // The oscillator's one mesh (oscillator_system.hpp).
    GEARDYN_THROW_UNLESS(
        settings.mesh.empty() || settings.mesh == "oscillator",
        "--mesh: an oscillator scene has the one mesh 'oscillator', not '" << settings.mesh << "'");
    result.mesh = "oscillator";
  } else {
    result.mesh = settings.mesh.empty() ? scene.meshes.front().name : settings.mesh;
    GEARDYN_THROW_UNLESS(std::any_of(scene.meshes.begin(), scene.meshes.end(),
                                     [&](const MeshDef& m) { return m.name == result.mesh; }),
                         "--mesh: the scene has no mesh '" << result.mesh << "'");
  }
  const auto has = [&](CompareAnalysis a) {
    return std::find(settings.analyses.begin(), settings.analyses.end(), a) !=
           settings.analyses.end();
  };
  const bool wants_dte = has(CompareAnalysis::kHb) || has(CompareAnalysis::kSimulate);
  const bool levels_given = settings.levels_given && !settings.levels.empty();
  if (settings.levels.empty()) {
    // Defaults: every level but the contact model (seconds per speed: ask for it by name).
    for (const CompareLevelInfo& l : CompareLevels()) {
      const bool oscillator_level = l.name == "slices" || l.name == "torsional" || l.name == "lti";
      if (l.name != "contact" && ParseMeshModelLevel(l.name) && (!oscillator || oscillator_level)) {
        settings.levels.push_back(l.name);
      }
    }
  }
  GEARDYN_THROW_UNLESS(
      !(std::find(settings.levels.begin(), settings.levels.end(), "contact") !=
            settings.levels.end() &&
        !has(CompareAnalysis::kSimulate) && settings.levels.size() == 1),
      "--levels: the contact level has modes, Floquet and harmonic balance of none; it needs "
      "--analyses simulate");
  result.operating_mesh_frequency_hz = scene.NominalMeshFrequencyHz();
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

  // ---- the other levels on the contact model's teeth (overlay_match.hpp)
  Scene matched = scene;
  std::vector<std::string> match_overrides;  // the same for the charts (they reload the scene)
  const bool has_contact =
      std::find(settings.levels.begin(), settings.levels.end(), "contact") != settings.levels.end();
  if (has_contact && settings.match_contact && has(CompareAnalysis::kSimulate) && !oscillator) {
    progress.Line("contact: matching the other levels' mesh stiffness and damping");
    try {
      SceneSystemOptions o;
      o.analysis = "compare (contact)";
      o.allow_contact_meshes = true;
      const Scene contact_scene = SceneAtLevel(scene, "contact");
      const SystemModel contact_model = BuildSceneSystem(contact_scene, o).model;
      const auto build_slices = [&](const std::vector<std::string>& extra) {
        std::vector<std::string> overrides = settings.overrides;
        overrides.insert(overrides.end(), extra.begin(), extra.end());
        SceneSystemOptions so;
        so.analysis = "compare (matched slices)";
        const Scene variant = settings.scene_text.empty()
                                  ? LoadScene(settings.scene_path, overrides)
                                  : ParseScene(settings.scene_text, settings.scene_path, overrides);
        return BuildSceneSystem(variant, so).model;
      };
      const std::vector<SliceMatch> matches =
          MatchSlicesToContact(contact_model, contact_scene, build_slices, &result.warnings);
      for (const SliceMatch& m : matches) {
        for (MeshDef& mesh : matched.meshes) {
          if (mesh.name != m.mesh) continue;
          mesh.model.stiffness_per_length = m.stiffness_per_length;
          mesh.model.damping = MeshDamping::FromCoefficient(m.damping);
        }
        std::ostringstream note;
        note.precision(6);
        note << "mesh " << m.mesh << " of every other level matched to the contact model: "
             << "stiffness_per_length = " << m.stiffness_per_length << " N/m² (mean mesh stiffness "
             << m.contact_mean_stiffness
             << " N/m, quasi-static at the operating torque), damping = " << m.damping
             << " N·s/m (the contact law's at the mean load); --no-match-contact keeps the "
                "scene's";
        result.notes.push_back(note.str());
        const auto exact = [](double v) {
          std::ostringstream t;
          t.precision(17);
          t << v;
          return t.str();
        };
        match_overrides.push_back("mesh." + m.mesh +
                                  ".stiffness_per_length=" + exact(m.stiffness_per_length));
        match_overrides.push_back("mesh." + m.mesh + ".damping=" + exact(m.damping));
      }
    } catch (const InvalidInput& e) {
      result.warnings.push_back(std::string("the other levels could not be matched to the contact "
                                            "model (they keep the scene's stiffness and mesh "
                                            "damping): ") +
                                e.what());
      matched = scene;
      match_overrides.clear();
    }
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
    Scene at_level;
    try {
      at_level = SceneAtLevel(level == "contact" ? scene : matched, level);
    } catch (const InvalidInput& e) {
      GEARDYN_THROW_UNLESS(!levels_given,
                           "--levels: the scene has no level '" << level << "': " << e.what());
      for (const CompareAnalysis a : settings.analyses) run.skipped[a] = e.what();
      result.runs.push_back(std::move(run));
      continue;
    }
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
        chart.scene_text = settings.scene_text;
        chart.overrides = settings.overrides;
        chart.overrides.insert(chart.overrides.end(), match_overrides.begin(),
                               match_overrides.end());
        for (const MeshDef& m : scene.meshes) {
          chart.overrides.push_back("mesh." + m.name + ".model=" + level);
        }
        if (oscillator) chart.overrides.push_back("oscillator.model=" + level);
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
          if (level == "lti" && !oscillator) {
            std::string why;
            if (std::optional<Scene> loaded = LtiWithLoadedSte(matched, &why)) {
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
          LevelDte dte =
              by_time ? TimeDomainDte(
                            forced->model, mesh, result.frequencies_hz, settings,
                            [&progress](const std::string& t) { progress.Line(t); }, level)
              : info.linear ? LinearDte(forced->model, mesh, result.frequencies_hz, &run.warnings)
                            : NonlinearDte(forced->model, mesh, result.frequencies_hz, settings);
          dte.multivalued = IsMultivalued(dte);
          const auto* linear_core = std::get_if<LinearMeshCore>(&forced->model.meshes()[mesh].core);
          if (by_time && linear_core != nullptr && linear_core->has_transmission_error()) {
            run.warnings.push_back(
                "time domain: a linear level's DTE is δ_η − ε_η (probes.hpp), not the loaded TE "
                "δ_η the other levels report; compare it with --analyses hb");
          }
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
