// `geardyn simulate` and `geardyn compare` (analysis_runs.hpp): their reports as dicts; their
// settings as keyword arguments (python/geardyn/_analyses.py documents them).
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <optional>

#include "bindings.hpp"
#include "geardyn/compare_levels.hpp"
#include "geardyn/progress_stream.hpp"

namespace geardyn::python {
namespace {

py::dict Report(app::RunReport& run) {
  py::dict d;
  d["report"] = Hold(std::move(run.report));
  d["text"] = run.text;
  d["exit_code"] = run.exit_code;
  return d;
}

}  // namespace

void BindTimeAndCompare(py::module_& m) {
  m.def(
      "simulate",
      [](const Scene& scene, const std::string& scene_text, const std::string& mesh_frequency,
         const std::string& sweep, const std::vector<double>& torques,
         const std::string& integrator, std::optional<double> tolerance,
         std::optional<double> steady_tolerance, std::optional<int> max_periods,
         std::optional<int> record_periods, std::optional<int> samples_per_period,
         std::optional<double> max_step, int threads, bool quasi_static, bool full_period,
         bool overlay_hb, const std::string& out_dir, py::object progress) {
        app::SimulateSettings s;
        s.mesh_frequency = mesh_frequency;
        s.sweep = sweep;
        s.torques = torques;
        s.integrator = integrator;
        if (tolerance) s.tolerance = *tolerance;
        if (steady_tolerance) s.steady_tolerance = *steady_tolerance;
        if (max_periods) s.max_periods = *max_periods;
        if (record_periods) s.record_periods = *record_periods;
        if (samples_per_period) s.samples_per_period = *samples_per_period;
        if (max_step) s.max_step = *max_step;
        s.threads = threads;
        s.quasi_static = quasi_static;
        s.full_period = full_period;
        s.overlay_hb = overlay_hb;
        s.progress = !progress.is_none();
        PythonProgress sink(std::move(progress));
        std::optional<app::SimulateRun> run;
        const auto start = std::chrono::steady_clock::now();
        {
          py::gil_scoped_release release;
          run.emplace(app::RunSimulateAnalysis(scene, scene_text, s, out_dir, sink.Line()));
        }
        const double cpp_time = SecondsSince(start);
        sink.Rethrow();
        py::dict d = Report(*run);
        d["cpp_wall_time_s"] = cpp_time;
        py::dict histories;
        if (run->history) {
          const TimeResponse& r = *run->history;
          d["time_s"] = VectorX(r.time);
          for (const MeshTimeHistory& h : r.meshes) {
            py::dict mesh;
            mesh["dte_m"] = VectorX(h.dte);
            mesh["force_n"] = VectorX(h.force);
            histories[py::str(h.name)] = mesh;
          }
        }
        d["histories"] = histories;
        return d;
      },
      py::arg("scene"), py::arg("scene_text"), py::arg("mesh_frequency"), py::arg("sweep"),
      py::arg("torques"), py::arg("integrator"), py::arg("tolerance"), py::arg("steady_tolerance"),
      py::arg("max_periods"), py::arg("record_periods"), py::arg("samples_per_period"),
      py::arg("max_step"), py::arg("threads"), py::arg("quasi_static"), py::arg("full_period"),
      py::arg("overlay_hb"), py::arg("out_dir"), py::arg("progress"));
  m.def(
      "compare",
      [](const Scene& scene, const std::string& scene_text,
         const std::vector<std::string>& overrides, std::optional<std::string> levels,
         const std::string& analyses, const std::string& reference, const std::string& mesh,
         const std::string& mesh_frequency, int num_modes, int nonlinear_harmonics,
         int branch_search, int max_periods, int threads, bool match_contact,
         const std::string& chart_x, const std::string& chart_y, const std::string& out_dir,
         py::object progress) {
        app::CompareSettings s;
        s.levels_given = levels.has_value();
        if (levels) s.levels = app::ParseCompareLevels(*levels);
        s.analyses = app::ParseCompareAnalyses(analyses);
        s.reference = reference;
        s.mesh = mesh;
        s.mesh_frequency = mesh_frequency;
        s.num_modes = num_modes;
        s.nonlinear_harmonics = nonlinear_harmonics;
        s.branch_search = branch_search;
        s.max_periods = max_periods;
        s.threads = threads;
        s.match_contact = match_contact;
        s.chart_x = chart_x;
        s.chart_y = chart_y;
        s.scene_path = scene.source;
        s.scene_text = scene_text;
        s.overrides = overrides;
        s.progress = !progress.is_none();
        PythonProgress sink(std::move(progress));
        std::optional<app::CompareRun> run;
        const auto start = std::chrono::steady_clock::now();
        {
          py::gil_scoped_release release;
          app::ProgressStream err(sink.Line());
          run.emplace(app::RunCompareAnalysis(scene, s, out_dir, &err));
        }
        const double cpp_time = SecondsSince(start);
        sink.Rethrow();
        py::dict d = Report(*run);
        d["cpp_wall_time_s"] = cpp_time;
        return d;
      },
      py::arg("scene"), py::arg("scene_text"), py::arg("overrides"), py::arg("levels"),
      py::arg("analyses"), py::arg("reference"), py::arg("mesh"), py::arg("mesh_frequency"),
      py::arg("num_modes"), py::arg("nonlinear_harmonics"), py::arg("branch_search"),
      py::arg("max_periods"), py::arg("threads"), py::arg("match_contact"), py::arg("chart_x"),
      py::arg("chart_y"), py::arg("out_dir"), py::arg("progress"));
}

}  // namespace geardyn::python
