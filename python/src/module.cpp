// _reeve: the compiled half of the Python package `reeve` (python/reeve).
#include <pybind11/pybind11.h>

#include "py_scene.h"

PYBIND11_MODULE(_reeve, m) {
  m.doc() = "Reeve's C++ core; import the package `reeve`, not this module.";
  m.attr("__version__") = REEVE_VERSION;
  m.attr("_SOURCE_SCENES_DIR") = REEVE_SCENES_DIR;
  reeve::python::bindErrors(m);
  reeve::python::bindScene(m);
  reeve::python::bindBodies(m);
  reeve::python::bindCables(m);
  reeve::python::bindJoints(m);
  reeve::python::bindBatch(m);
  reeve::python::bindView(m);
}
