// reeve.SceneError (a ValueError carrying file, json_path, expected, found)
// and reeve.SimulationError (a RuntimeError: a run that had to stop).
#include "py_scene.h"

namespace py = pybind11;

namespace reeve::python {
namespace {

PyObject* scene_error = nullptr;
PyObject* simulation_error = nullptr;

}  // namespace

void throwSimulationError(const std::string& message) {
  PyErr_SetString(simulation_error, message.c_str());
  throw py::error_already_set();
}

void bindErrors(py::module_& m) {
  static py::exception<SceneError> scene_exc(m, "SceneError", PyExc_ValueError);
  scene_exc.doc() =
      "A scene that cannot be loaded: the message the command line prints (FILE: JSON_PATH: expected "
      "EXPECTED, got FOUND), and the parts as attributes: file, json_path (a JSON Pointer, \"\" for the "
      "root), expected, found; line and column (1-based) for a JSON syntax error, else 0.";
  scene_error = scene_exc.ptr();
  static py::exception<std::runtime_error> sim_exc(m, "SimulationError", PyExc_RuntimeError);
  sim_exc.doc() =
      "A simulation that had to stop: a non-finite state, the cable bookkeeping broken (a spool that ran "
      "out of cable, a diverged solve), or a rigid cable stretched between bodies that cannot move. The "
      "message says where, when and what to try.";
  simulation_error = sim_exc.ptr();
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const SceneError& e) {
      py::object error = py::reinterpret_borrow<py::object>(scene_error)(e.what());
      error.attr("file") = e.file();
      error.attr("json_path") = e.jsonPath();
      error.attr("expected") = e.expected();
      error.attr("found") = e.found();
      error.attr("line") = e.line();
      error.attr("column") = e.column();
      PyErr_SetObject(scene_error, error.ptr());
    }
  });
}

}  // namespace reeve::python
