// Scene.view() and reeve.Viewer: `reeve view` from Python (issue 31).
#include <chrono>
#include <filesystem>
#include <memory>
#include <thread>

#include <pybind11/pybind11.h>

#include "py_scene.h"
#include "view_server.h"
#include "viewer_files.h"

namespace py = pybind11;

namespace reeve::python {
namespace {

struct PyViewer {
  std::unique_ptr<ViewServer> server;
};

std::unique_ptr<ViewServer> serve(const PyScene& s, int port, const std::string& host) {
  if (port < 0 || port > 65535) throw py::value_error("port: expected 0..65535, got " + std::to_string(port));
  ViewOptions o;
  o.scene = s.source;
  if (!s.text.empty()) o.scene_text = s.text;  // else a file, watched for edits
  o.host = host;
  o.port = port;
  const SolverSettings& settings = s.scene.world->settings();
  o.overrides.substeps = settings.substeps;
  o.overrides.iterations = settings.iterations;
  o.overrides.solver = settings.solver;
  try {
    auto server = std::make_unique<ViewServer>(o);
    server->start();
    return server;
  } catch (const ViewerMissing& e) {
    PyErr_SetString(PyExc_FileNotFoundError, e.what());
    throw py::error_already_set();
  }
}

}  // namespace

py::object viewScene(const PyScene& s, int port, const std::string& host, bool block) {
  auto viewer = std::make_unique<PyViewer>();
  viewer->server = serve(s, port, host);
  py::print("reeve view: '" + s.scene.name + "' at " + viewer->server->url() +
            (block ? " (Ctrl-C stops)" : " (Viewer.stop() stops)"));
  if (!block) return py::cast(std::move(viewer));
  for (;;) {
    {
      py::gil_scoped_release release;
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    if (PyErr_CheckSignals() != 0) {  // KeyboardInterrupt
      viewer->server->stop();
      throw py::error_already_set();
    }
  }
}

void bindView(py::module_& m) {
  py::class_<PyViewer>(m, "Viewer",
                       "A scene served live to a browser (Scene.view(block=False)): open `url`; stop() ends it "
                       "(so does leaving a `with` block, or the object's end).")
      .def_property_readonly("url", [](const PyViewer& v) { return v.server->url(); }, "The address to open.")
      .def_property_readonly("port", [](const PyViewer& v) { return v.server->port(); })
      .def(
          "stop",
          [](PyViewer& v) {
            py::gil_scoped_release release;
            v.server->stop();
          },
          "Ends every page's stream and stops serving; idempotent.")
      .def("__enter__", [](py::object self) { return self; })
      .def("__exit__", [](PyViewer& v, py::args) {
        py::gil_scoped_release release;
        v.server->stop();
      })
      .def("__repr__", [](const PyViewer& v) { return "<reeve.Viewer " + v.server->url() + ">"; });
}

}  // namespace reeve::python
