// The pieces of the _geardyn extension module (module.cpp), one file per concern.
#pragma once

#include <pybind11/pybind11.h>

#include <exception>
#include <functional>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>

#include "geardyn/analysis_runs.hpp"

namespace geardyn::python {

namespace py = pybind11;

/// The report JSON as a Python object (json.loads of its text: dict, list, float, None).
py::object ToPython(const nlohmann::json& j);

/// @brief A ProgressLine that calls a Python callable (or nothing when it is None) with the GIL
/// held. An exception the callable raises stops further calls; Rethrow() raises it after the run.
class PythonProgress {
 public:
  explicit PythonProgress(py::object callback);
  app::ProgressLine Line();
  /// Raises the callback's exception, if any (call with the GIL held, after the run).
  void Rethrow();

 private:
  py::object callback_;
  std::mutex mutex_;
  std::exception_ptr error_;
};

void BindErrors(py::module_& m);
void BindScene(py::module_& m);
void BindSummary(py::module_& m);
void BindAnalyses(py::module_& m);
void BindMatrices(py::module_& m);
void BindTimeAndCompare(py::module_& m);

}  // namespace geardyn::python
