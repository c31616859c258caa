// Scenes from Python: a built-in or file path (LoadScene) or TOML text (ParseScene), with
// `path=value` overrides; an opaque handle the analyses take.
#include <pybind11/stl.h>

#include <optional>

#include "bindings.hpp"
#include "geardyn/info_report.hpp"
#include "geardyn/models/scene/builtin_scenes.hpp"
#include "geardyn/models/scene/scene_reader.hpp"

namespace geardyn::python {

void BindScene(py::module_& m) {
  py::class_<Scene>(m, "Scene", "a validated scene (geardyn.Scene wraps it)")
      .def_readonly("source", &Scene::source)
      .def_readonly("title", &Scene::title)
      .def_property_readonly("mesh_frequency_hz", &Scene::NominalMeshFrequencyHz)
      .def_property_readonly("mesh_names",
                             [](const Scene& s) {
                               std::vector<std::string> names;
                               for (const auto& mesh : s.meshes) names.push_back(mesh.name);
                               return names;
                             })
      .def_property_readonly("is_oscillator",
                             [](const Scene& s) { return s.oscillator.has_value(); });
  m.def(
      "load_scene",
      [](const std::string& path_or_builtin, const std::vector<std::string>& overrides) {
        py::gil_scoped_release release;
        return LoadScene(path_or_builtin, overrides);
      },
      py::arg("path_or_builtin"), py::arg("overrides") = std::vector<std::string>{});
  m.def(
      "parse_scene",
      [](const std::string& text, const std::string& source,
         const std::vector<std::string>& overrides) {
        py::gil_scoped_release release;
        return ParseScene(text, source, overrides);
      },
      py::arg("text"), py::arg("source"), py::arg("overrides") = std::vector<std::string>{});
  m.def("builtin_scene_names", &BuiltinSceneNames);
  m.def(
      "builtin_scene_text",
      [](const std::string& name) -> std::optional<std::string> {
        const auto text = BuiltinSceneText(name);
        if (!text) return std::nullopt;
        return std::string(*text);
      },
      py::arg("name"));
  m.def(
      "info",
      [](const Scene& scene) {
        nlohmann::json report;
        {
          py::gil_scoped_release release;
          report = app::MakeInfoReport(scene);
        }
        return py::make_tuple(ToPython(report), app::FormatInfoText(report));
      },
      py::arg("scene"));
}

}  // namespace geardyn::python
