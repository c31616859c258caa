// The analyses of the geardyn subcommands (analysis_runs.hpp) with their results as dicts of
// numpy arrays (copies that own their memory), the command's JSON report, its text and the
// Summary. The GIL is released while the C++ library computes.
#include <pybind11/eigen.h>
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <optional>

#include "bindings.hpp"
#include "geardyn/common/check.hpp"
#include "geardyn/mesh_report.hpp"

namespace geardyn::python {
namespace {

template <typename T>
py::array_t<T> Array(const std::vector<T>& v) {
  py::array_t<T> a(static_cast<py::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

py::array_t<double> Array(const std::vector<std::uint8_t>& v) {
  py::array_t<double> a(static_cast<py::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

py::dict Common(app::RunReport& run, const Summary& summary) {
  py::dict d;
  d["report"] = Hold(std::move(run.report));
  d["text"] = run.text;
  d["exit_code"] = run.exit_code;
  d["summary"] = summary;
  return d;
}

py::dict Modes(const Scene& scene, int num_modes, const std::string& method, bool shapes,
               bool damped, bool loaded, const std::string& out_dir) {
  app::ModesSettings settings;
  settings.num_modes = num_modes;
  settings.method = method;
  settings.shapes = shapes;
  settings.damped = damped;
  settings.loaded = loaded;
  std::optional<app::ModesRun> run;
  const auto start = std::chrono::steady_clock::now();
  {
    py::gil_scoped_release release;
    run.emplace(app::RunModesAnalysis(scene, settings, out_dir));
  }
  const double cpp_time = SecondsSince(start);
  const ModalResult& r = run->result;
  py::dict d = Common(*run, r.summary);
  d["cpp_wall_time_s"] = cpp_time;
  d["frequencies_hz"] = VectorX(r.frequencies_hz);
  d["eigenvalues"] = VectorX(r.eigenvalues);
  d["shapes"] = MatrixX(r.shapes);
  d["dof_names"] = r.dof_names;
  d["kinetic_fractions"] = MatrixX(r.kinetic_fractions);
  d["body_kinetic_fractions"] = MatrixX(r.body_kinetic_fractions);
  d["body_names"] = r.body_names;
  d["strain_fractions"] = MatrixX(r.strain_fractions);
  d["strain_names"] = r.strain_names;
  d["modal_damping_ratios"] = VectorX(r.modal_damping_ratios);
  std::vector<std::string> labels;
  for (ModeType t : r.labels) labels.emplace_back(ToString(t));
  d["labels"] = labels;
  d["num_rigid_body_modes"] = r.num_rigid_body_modes;
  d["method_used"] = ToString(r.method_used);
  return d;
}

py::dict Floquet(const Scene& scene, const std::string& method, double tolerance, int nev,
                 long max_approximant_period, const std::string& out_dir) {
  app::FloquetSettings settings;
  settings.method = method;
  settings.tolerance = tolerance;
  settings.nev = nev;
  // The command's --max-approximant-period bound, checked here (CLI11 checks the flag's).
  if (max_approximant_period < 0 || max_approximant_period > 10000) {
    throw InvalidInput("--max-approximant-period: must be in [0, 10000] mesh cycles, got " +
                       std::to_string(max_approximant_period));
  }
  settings.max_approximant_period = max_approximant_period;
  std::optional<app::FloquetRun> run;
  const auto start = std::chrono::steady_clock::now();
  {
    py::gil_scoped_release release;
    run.emplace(app::RunFloquetAnalysis(scene, settings, out_dir));
  }
  const double cpp_time = SecondsSince(start);
  const FloquetResult& r = run->result;
  py::dict d = Common(*run, r.summary);
  d["cpp_wall_time_s"] = cpp_time;
  d["multipliers"] = VectorXc(r.multipliers);
  d["exponents"] = VectorXc(r.exponents);
  d["mesh_frequency_hz"] = run->mesh_frequency_hz;
  d["period_s"] = r.period_s;
  d["period_meshes"] = r.period_meshes;
  d["max_abs_multiplier"] = r.max_abs_multiplier;
  d["stability_margin"] = r.stability_margin;
  d["verdict"] = ToString(r.verdict);
  d["stable"] = r.verdict == FloquetVerdict::kUndetermined ? py::object(py::none())
                                                           : py::object(py::bool_(r.stable()));
  d["marginal"] = r.marginal;
  d["method_used"] = ToString(r.method_used);
  return d;
}

py::dict Hb(const Scene& scene, const app::HbRunSettings& settings, const std::string& out_dir,
            py::object progress) {
  PythonProgress sink(std::move(progress));
  std::optional<app::HbRun> run;
  const auto start = std::chrono::steady_clock::now();
  {
    py::gil_scoped_release release;
    run.emplace(app::RunHbAnalysis(scene, settings, out_dir, sink.Line()));
  }
  const double cpp_time = SecondsSince(start);
  sink.Rethrow();
  Summary summary;  // the report carries the statuses of the points and of the sweep
  summary.status = run->exit_code == 0 ? Status::kSuccess : Status::kNumericalIssue;
  py::dict d = Common(*run, summary);
  d["cpp_wall_time_s"] = cpp_time;
  d["nonlinear"] = run->nonlinear;
  return d;
}

py::dict Chart(const std::string& source, const std::string& text,
               const std::vector<std::string>& overrides, const app::ChartRunSettings& settings,
               const std::string& out_dir, py::object progress) {
  PythonProgress sink(std::move(progress));
  std::optional<app::ChartRun> run;
  const auto start = std::chrono::steady_clock::now();
  {
    py::gil_scoped_release release;
    run.emplace(app::RunChartAnalysis(source, text, overrides, settings, out_dir, sink.Line()));
  }
  const double cpp_time = SecondsSince(start);
  sink.Rethrow();
  const StabilityChartResult& c = run->run.chart;
  py::dict d = Common(*run, c.summary);
  d["cpp_wall_time_s"] = cpp_time;
  std::vector<double> x, y;
  for (int i = 0; i < c.x_axis.num_points; ++i) x.push_back(c.x_axis.Value(i));
  for (int i = 0; i < c.y_axis.num_points; ++i) y.push_back(c.y_axis.Value(i));
  d["x"] = Array(x);
  d["y"] = Array(y);
  d["x_path"] = c.x_axis.name;
  d["y_path"] = c.y_axis.name;
  d["max_abs_multiplier"] = Array(c.max_abs_multiplier);
  d["error_estimate"] = Array(c.error_estimate);
  d["mesh_frequency_hz"] = Array(c.mesh_frequency_hz);
  d["ok"] = Array(c.ok);
  d["stable"] = Array(c.stable);
  d["region"] = Array(c.region);
  py::list curves;
  for (const TransitionCurve& t : c.curves) {
    curves.append(py::make_tuple(Array(t.x), Array(t.y), t.closed));
  }
  d["curves"] = curves;
  return d;
}

py::dict Mesh(const Scene& scene, std::optional<double> samples, std::optional<double> cycles) {
  app::MeshSamplingOptions options;
  options.samples_per_mesh = samples;
  options.cycles = cycles;
  std::string why;
  GEARDYN_THROW_UNLESS(options.IsValid(&why), why);
  GEARDYN_THROW_UNLESS(!scene.oscillator,
                       scene.source << ": an oscillator scene has no gear mesh to sample");
  std::vector<app::MeshSamples> tables;
  nlohmann::json report;
  {
    py::gil_scoped_release release;
    report = app::MakeMeshReport(scene, options, &tables);
  }
  py::dict d;
  d["report"] = Hold(std::move(report));
  py::list meshes;
  for (const app::MeshSamples& s : tables) {
    py::dict t;
    t["name"] = s.mesh_name;
    t["cycle"] = Array(s.cycle);
    t["stiffness"] = Array(s.stiffness);
    t["load_centre"] = Array(s.load_centre);
    t["kappa"] = Array(s.kappa);
    t["mu"] = Array(s.mu);
    t["te_eta"] = Array(s.te_eta);
    t["te_zeta"] = Array(s.te_zeta);
    meshes.append(t);
  }
  d["meshes"] = meshes;
  return d;
}

}  // namespace

void BindAnalyses(py::module_& m) {
  m.def("modes", &Modes, py::arg("scene"), py::arg("num_modes"), py::arg("method"),
        py::arg("shapes"), py::arg("damped"), py::arg("loaded"), py::arg("out_dir"));
  m.def("floquet", &Floquet, py::arg("scene"), py::arg("method"), py::arg("tolerance"),
        py::arg("nev"), py::arg("max_approximant_period"), py::arg("out_dir"));
  m.def(
      "hb",
      [](const Scene& scene, const std::string& mesh_frequency, int harmonics,
         std::optional<double> tolerance, bool linear, bool nonlinear, const std::string& stability,
         int monodromy_steps, int branch_search, const std::string& out_dir, py::object progress) {
        app::HbRunSettings s;
        s.settings.mesh_frequency = mesh_frequency;
        s.settings.harmonics = harmonics;
        s.harmonics_given = harmonics != 0;
        if (tolerance) {
          s.settings.tolerance = *tolerance;
          s.tolerance_given = true;
        }
        s.settings.linear = linear;
        s.settings.progress = !progress.is_none();
        s.nonlinear = nonlinear;
        s.stability = stability;
        s.monodromy_steps = monodromy_steps;
        s.branch_search = branch_search;
        return Hb(scene, s, out_dir, std::move(progress));
      },
      py::arg("scene"), py::arg("mesh_frequency"), py::arg("harmonics"), py::arg("tolerance"),
      py::arg("linear"), py::arg("nonlinear"), py::arg("stability"), py::arg("monodromy_steps"),
      py::arg("branch_search"), py::arg("out_dir"), py::arg("progress"));
  m.def(
      "stability_chart",
      [](const std::string& source, const std::string& text,
         const std::vector<std::string>& overrides, const std::string& x, const std::string& y,
         int threads, const std::string& method, double tolerance, double boundary_tolerance,
         int max_order, bool difference, bool curves, const std::string& out_dir,
         py::object progress) {
        app::ChartRunSettings s;
        s.x = x;
        s.y = y;
        s.threads = threads;
        s.method = method;
        s.tolerance = tolerance;
        s.boundary_tolerance = boundary_tolerance;
        s.max_order = max_order;
        s.difference = difference;
        s.curves = curves;
        return Chart(source, text, overrides, s, out_dir, std::move(progress));
      },
      py::arg("source"), py::arg("text"), py::arg("overrides"), py::arg("x"), py::arg("y"),
      py::arg("threads"), py::arg("method"), py::arg("tolerance"), py::arg("boundary_tolerance"),
      py::arg("max_order"), py::arg("difference"), py::arg("curves"), py::arg("out_dir"),
      py::arg("progress"));
  m.def("mesh", &Mesh, py::arg("scene"), py::arg("samples"), py::arg("cycles"));
}

}  // namespace geardyn::python
