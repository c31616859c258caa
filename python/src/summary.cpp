// geardyn::Summary in Python (status name, message, error estimate, counters, time, warnings).
#include "geardyn/common/summary.hpp"

#include <pybind11/stl.h>

#include "bindings.hpp"

namespace geardyn::python {

void BindSummary(py::module_& m) {
  py::class_<Summary>(m, "Summary", "status, message, error estimate, counters, time, warnings")
      .def_property_readonly("status", [](const Summary& s) { return StatusName(s.status); })
      .def_readonly("message", &Summary::message)
      .def_readonly("error_estimate", &Summary::error_estimate)
      .def_readonly("counters", &Summary::counters)
      .def_readonly("wall_time_s", &Summary::wall_time_s)
      .def_readonly("warnings", &Summary::warnings)
      .def_property_readonly("ok", &Summary::ok)
      .def("brief_report", &Summary::BriefReport)
      .def("__repr__", [](const Summary& s) {
        return std::string("Summary(status='") + StatusName(s.status) + "', message='" + s.message +
               "')";
      });
}

}  // namespace geardyn::python
