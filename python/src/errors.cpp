// C++ exceptions as Python exceptions, with the C++ message as their text:
// InvalidInput → geardyn.InputError (a ValueError), SceneError → geardyn.SceneError (an
// InputError with .source, .line, .key, .reason), InternalError → geardyn.InternalError.
#include "geardyn/common/errors.hpp"

#include "bindings.hpp"
#include "geardyn/models/scene/scene_reader.hpp"

namespace geardyn::python {

void BindErrors(py::module_& m) {
  static py::exception<InvalidInput> input_error(m, "InputError", PyExc_ValueError);
  static py::exception<SceneError> scene_error(m, "SceneError", input_error.ptr());
  static py::exception<InternalError> internal_error(m, "InternalError", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const SceneError& e) {
      // py::exception's call operator only sets the error; the instance needs the type's call.
      const py::object type = py::reinterpret_borrow<py::object>(scene_error.ptr());
      py::object error = type(e.what());
      error.attr("source") = e.source();
      error.attr("line") = e.line();
      error.attr("key") = e.key();
      error.attr("reason") = e.reason();
      error.attr("override") = e.override_spec();
      PyErr_SetObject(scene_error.ptr(), error.ptr());
    } catch (const InvalidInput& e) {
      input_error(e.what());
    } catch (const InternalError& e) {
      internal_error(e.what());
    }
  });
}

}  // namespace geardyn::python
