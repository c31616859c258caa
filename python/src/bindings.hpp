// The pieces of the _geardyn extension module (module.cpp), one file per concern.
#pragma once

#include <pybind11/pybind11.h>

#include <chrono>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>

#include "geardyn/analysis_runs.hpp"

namespace geardyn::python {

namespace py = pybind11;

/// The report JSON as a Python object (dict, list, float, int, str, bool, None).
py::object ToPython(const nlohmann::json& j);

/// A report kept as C++ JSON until Python asks for it (ReportHolder.to_python): a modes report
/// with shapes of a 108-DOF system is ≈ 12 000 numbers, 2 ms of conversion (7 % of the run)
/// that a caller reading only the arrays never needs (docs/benchmarks.md "Python package").
struct ReportHolder {
  std::shared_ptr<const nlohmann::json> json;
};
py::object Hold(nlohmann::json report);

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

/// Wall-clock seconds since `start` (the C++ share of a call: results' cpp_wall_time_s).
inline double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void BindErrors(py::module_& m);
void BindScene(py::module_& m);
void BindSummary(py::module_& m);
void BindAnalyses(py::module_& m);
void BindMatrices(py::module_& m);
void BindTimeAndCompare(py::module_& m);

}  // namespace geardyn::python
