// _geardyn: the compiled half of the geardyn Python package (python/geardyn/ is the other half:
// the documented, typed API wraps these functions). Every function releases the GIL while the C++
// library computes; arrays are returned as numpy copies that own their memory.
#include <cmath>
#include <cstdint>

#include "bindings.hpp"
#include "geardyn/common/errors.hpp"

namespace geardyn::python {

// Node by node (no JSON text in between: dumping and parsing a report with mode shapes or a
// long nonlinear trace cost 4–20 ms, 13 % of a 35 ms modes run; docs/benchmarks.md).
py::object ToPython(const nlohmann::json& j) {
  switch (j.type()) {
    case nlohmann::json::value_t::null:
    case nlohmann::json::value_t::discarded:
      return py::none();
    case nlohmann::json::value_t::boolean:
      return py::bool_(j.get<bool>());
    case nlohmann::json::value_t::number_integer:
      return py::int_(j.get<std::int64_t>());
    case nlohmann::json::value_t::number_unsigned:
      return py::int_(j.get<std::uint64_t>());
    case nlohmann::json::value_t::number_float: {
      // As the command's JSON prints them (nlohmann writes null): a non-finite number is "not
      // available", and a script comparing reports must see the same None.
      const double v = j.get<double>();
      return std::isfinite(v) ? py::object(py::float_(v)) : py::object(py::none());
    }
    case nlohmann::json::value_t::string:
      return py::str(j.get_ref<const std::string&>());
    case nlohmann::json::value_t::array: {
      py::list list(j.size());
      std::size_t i = 0;
      for (const nlohmann::json& v : j) list[i++] = ToPython(v);
      return py::object(std::move(list));
    }
    case nlohmann::json::value_t::object: {
      py::dict dict;
      for (auto it = j.begin(); it != j.end(); ++it) dict[py::str(it.key())] = ToPython(it.value());
      return py::object(std::move(dict));
    }
    case nlohmann::json::value_t::binary:
      break;
  }
  throw InternalError("a report holds binary JSON data");
}

py::object Hold(nlohmann::json report) {
  return py::cast(ReportHolder{std::make_shared<const nlohmann::json>(std::move(report))});
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
  namespace gp = geardyn::python;
  gp::py::class_<gp::ReportHolder>(m, "ReportHolder",
                                   "a command's JSON report, converted on demand")
      .def("to_python", [](const gp::ReportHolder& h) { return gp::ToPython(*h.json); })
      .def(
          "dump", [](const gp::ReportHolder& h, int indent) { return h.json->dump(indent); },
          gp::py::arg("indent") = 2);
  geardyn::python::BindErrors(m);
  geardyn::python::BindSummary(m);
  geardyn::python::BindScene(m);
  geardyn::python::BindAnalyses(m);
  geardyn::python::BindMatrices(m);
  geardyn::python::BindTimeAndCompare(m);
}
