// _geardyn: the compiled half of the geardyn Python package (python/geardyn/ is the other half:
// the documented, typed API wraps these functions). Every function releases the GIL while the C++
// library computes; arrays are returned as numpy copies that own their memory.
#include "bindings.hpp"

namespace geardyn::python {

py::object ToPython(const nlohmann::json& j) {
  static py::object* loads = nullptr;
  if (loads == nullptr) loads = new py::object(py::module_::import("json").attr("loads"));
  return (*loads)(j.dump());
}

PythonProgress::PythonProgress(py::object callback) : callback_(std::move(callback)) {}

app::ProgressLine PythonProgress::Line() {
  if (callback_.is_none()) return {};
  return [this](const std::string& line) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (error_) return;
    py::gil_scoped_acquire gil;
    try {
      std::string text = line;
      while (!text.empty() && text.back() == '\n') text.pop_back();
      callback_(text);
    } catch (py::error_already_set&) {
      error_ = std::current_exception();
    }
  };
}

void PythonProgress::Rethrow() {
  if (error_) std::rethrow_exception(error_);
}

}  // namespace geardyn::python

PYBIND11_MODULE(_geardyn, m) {
  m.doc() = "geardyn's compiled core (use the geardyn package, not this module)";
  geardyn::python::BindErrors(m);
  geardyn::python::BindSummary(m);
  geardyn::python::BindScene(m);
  geardyn::python::BindAnalyses(m);
  geardyn::python::BindMatrices(m);
  geardyn::python::BindTimeAndCompare(m);
}
