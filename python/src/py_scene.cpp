// reeve.Scene, reeve.Settings, loading, stepping, rendering and runs.
#include "py_scene.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <csignal>
#include <optional>
#include <stdexcept>

#include "html_replay.h"
#include "reeve/scene/mjcf.h"
#include "interrupt.h"
#include "run_scene.h"

namespace py = pybind11;

namespace reeve::python {
namespace {

std::unique_ptr<PyScene> fromFile(const std::filesystem::path& path) {
  return std::make_unique<PyScene>(loadScene(path), path.string());
}

std::unique_ptr<PyScene> fromText(const std::string& text, const std::string& source) {
  return std::make_unique<PyScene>(parseScene(text, source), source, text);
}

// The bounds the scene schema puts on the solver settings.
void checkRange(const char* name, double value, double lo, double hi, bool lo_open) {
  if (!std::isfinite(value) || value > hi || (lo_open ? value <= lo : value < lo))
    throw py::value_error(std::string(name) + ": expected a number " + (lo_open ? "> " : ">= ") +
                          py::str(py::float_(lo)).cast<std::string>() +
                          " and <= " + py::str(py::float_(hi)).cast<std::string>() + ", got " +
                          py::str(py::float_(value)).cast<std::string>());
}

void step(PyScene& s, int frames) {
  if (frames < 0) throw py::value_error("frames: expected a count >= 0, got " + std::to_string(frames));
  const double dt = 1.0 / s.scene.frame_rate_hz;
  World& world = *s.scene.world;
  // On the main thread, where Python handles signals, SIGINT and SIGTERM
  // end the substep under way (World::setInterruptFlag) instead of waiting
  // for the GIL after the frame; then Python's own handlers are back and
  // the signal is raised as Python would have: KeyboardInterrupt, or
  // SIGTERM again. The world stays usable, at that substep's end.
  std::optional<InterruptGuard> interrupt;
  if (onMainThread()) interrupt.emplace();
  struct Detach {
    World& world;
    ~Detach() { world.setInterruptFlag(nullptr); }
  } detach{world};
  if (interrupt) world.setInterruptFlag(InterruptGuard::flag());
  for (int f = 0; f < frames && !(interrupt && interrupt->received()); ++f) {
    {
      py::gil_scoped_release release;  // other Python threads (a Dask worker's) run meanwhile
      world.step(dt);
    }
    if (const auto why = stopReason(s.scene)) throwSimulationError("reeve: " + *why);
    if (const auto created = s.energy.check(s.scene))
      if (PyErr_WarnEx(PyExc_RuntimeWarning, ("reeve: " + energyCreatedMessage(*created)).c_str(), 1) != 0)
        throw py::error_already_set();  // warnings turned into errors
  }
  s.scene.cables->takeEvents();  // not kept: nothing in Python reads them yet
  const int signal = interrupt ? interrupt->received() : 0;
  interrupt.reset();  // Python's handlers back
  raiseReceivedSignal(signal);
  if (PyErr_CheckSignals() != 0) throw py::error_already_set();  // off the main thread: between calls
}

py::array_t<std::uint8_t> render(PyScene& s, int width, int height) {
  if (width <= 0 || height <= 0)
    throw py::value_error("render: expected a positive width and height, got " + std::to_string(width) + "x" +
                          std::to_string(height));
  Image image;
  {
    py::gil_scoped_release release;
    if (!s.renderer || s.renderer->width() != width || s.renderer->height() != height)
      s.renderer = std::make_unique<Renderer>(width, height);
    image = s.renderer->render(*s.scene.world, *s.scene.cables,
                               sceneCamera(s.scene, static_cast<double>(width) / height));
  }
  py::array_t<std::uint8_t> out({image.height, image.width, 3});
  std::copy(image.rgb.begin(), image.rgb.end(), out.mutable_data());
  return out;
}

py::dict run(PyScene& s, std::optional<int> frames, std::optional<std::filesystem::path> csv,
             std::optional<std::filesystem::path> png_dir, std::optional<std::filesystem::path> video,
             std::optional<std::filesystem::path> events, std::optional<std::filesystem::path> html, int width,
             int height, bool force, bool strict) {
  const int n = frames.value_or(s.scene.frameCount());
  if (n < 0) throw py::value_error("frames: expected a count >= 0, got " + std::to_string(n));
  RunOutputs outputs;
  outputs.csv = csv.value_or("");
  outputs.png_dir = png_dir.value_or("");
  outputs.video = video.value_or("");
  outputs.events = events.value_or("");
  outputs.html = html.value_or("");
  outputs.width = width;
  outputs.height = height;
  outputs.force = force;
  outputs.strict = strict;
  if (std::filesystem::exists(s.source)) outputs.scene_file = s.source;
  RunResult r;
  s.energy = EnergyWatch(s.scene);  // step()'s watch goes on from where the run ends
  try {
    py::gil_scoped_release release;
    r = runScene(s.scene, n, outputs);
  } catch (const WouldOverwrite& e) {
    PyErr_SetString(PyExc_FileExistsError, e.what());
    throw py::error_already_set();
  } catch (const OutputClash& e) {
    throw py::value_error(e.what());
  } catch (const ViewerMissing& e) {
    PyErr_SetString(PyExc_FileNotFoundError, e.what());
    throw py::error_already_set();
  } catch (const std::invalid_argument& e) {
    throw py::value_error(e.what());
  } catch (const std::runtime_error& e) {
    throwSimulationError(std::string("reeve: ") + e.what());
  }
  // Stopped after a whole frame, the outputs holding the frames done, as
  // `reeve run` leaves them; then as Python would have: KeyboardInterrupt,
  // or SIGTERM again, now to the interpreter's own handler.
  raiseReceivedSignal(r.signal);
  s.energy = EnergyWatch(s.scene);
  for (const EnergyCreated& created : r.energy_created)
    if (PyErr_WarnEx(PyExc_RuntimeWarning, ("reeve: " + energyCreatedMessage(created)).c_str(), 1) != 0)
      throw py::error_already_set();
  for (const std::string& message : r.span_run_out)
    if (PyErr_WarnEx(PyExc_RuntimeWarning, ("reeve: " + message).c_str(), 1) != 0)
      throw py::error_already_set();
  py::dict result;
  result["frames"] = r.frames_done;
  result["energy_created_frames"] = r.energy_created_frames;
  result["spans_run_out"] = r.spans_run_out;
  result["physics_ms_per_frame"] = 1e3 * r.physics_s / std::max(r.frames_done, 1);
  return result;
}

py::dict energy(const PyScene& s) {
  const EnergyLedger e = energyLedger(s.scene);
  py::dict d;
  d["kinetic_J"] = e.kinetic_J;
  d["potential_J"] = e.potential_J;
  d["elastic_J"] = e.elastic_J;
  d["total_J"] = e.total_J();
  d["drive_work_J"] = e.drive_work_J;
  d["load_work_J"] = e.load_work_J;
  d["winch_work_J"] = e.winch_work_J;
  d["kinematic_work_J"] = e.kinematic_work_J;
  d["work_J"] = e.work_J();
  d["damping_J"] = e.damping_J;
  d["contact_J"] = e.contact_J;
  d["friction_J"] = e.friction_J;
  d["cable_damping_J"] = e.cable_damping_J;
  d["dissipated_J"] = e.dissipated_J();
  d["residual_J"] = e.balance_J() - s.start_balance_J;
  return d;
}

}  // namespace

bool onMainThread() {
  const py::module_ threading = py::module_::import("threading");
  return threading.attr("current_thread")().is(threading.attr("main_thread")());
}

void raiseReceivedSignal(int signal) {
  if (signal == SIGINT) {
    PyErr_SetNone(PyExc_KeyboardInterrupt);
    throw py::error_already_set();
  }
  if (signal == SIGTERM) std::raise(SIGTERM);
}

void bindScene(py::module_& m) {
  m.def("_load_file", &fromFile, py::arg("path"));
  m.def("_load_text", &fromText, py::arg("text"), py::arg("source"));
  m.def(
      "_import_mjcf",
      [](const std::filesystem::path& path, const std::string& wheels, const std::map<std::string, double>& controls) {
        if (wheels != "fixed" && wheels != "turning")
          throw py::value_error("wheels: expected \"fixed\" or \"turning\", got \"" + wheels + "\"");
        for (const auto& [name, value] : controls)
          if (!std::isfinite(value)) throw py::value_error("controls[" + name + "]: expected a finite number");
        MjcfImport model =
            importMjcf(path, {wheels == "turning" ? MjcfWheels::Turning : MjcfWheels::Fixed, controls});
        return py::make_tuple(model.scene_json, model.unmapped);
      },
      py::arg("path"), py::arg("wheels"), py::arg("controls"));
  m.def(
      "default_scene_json", [] { return std::string(defaultSceneJson()); },
      "The text of scenes/simple.json (paper Fig. 12, left), the command line's default scene.");
  m.def(
      "scene_schema_json", [] { return std::string(sceneSchemaJson()); },
      "The text of scene.schema.json (JSON Schema draft-07), which every scene is checked against.");

  py::class_<SettingsView>(
      m, "Settings",
      "The solver settings of a Scene, read and written in place; writes take effect at the next "
      "step. Ranges as in the scene schema (ValueError outside them).")
      .def_property(
          "substeps", [](const SettingsView& v) { return v.world().settings().substeps; },
          [](SettingsView& v, int n) {
            checkRange("substeps", n, 1, 100000, false);
            v.world().settings().substeps = n;
          },
          "Substeps per frame, 1..100000 (int).")
      .def_property(
          "iterations", [](const SettingsView& v) { return v.world().settings().iterations; },
          [](SettingsView& v, int n) {
            checkRange("iterations", n, 1, 100000, false);
            v.world().settings().iterations = n;
          },
          "Solver iterations per substep, 1..100000 (int).")
      .def_property(
          "threads", [](const SettingsView& v) { return v.world().threads(); },
          [](SettingsView& v, int n) {
            checkRange("threads", n, 1, 1024, false);
            v.world().setThreads(n);
          },
          "Threads the scene's islands (machines that share no body but static ones) are stepped on, 1..1024 "
          "(int; default 1). The results are the same bits for any number; a scene of one island uses one, "
          "and islands are shared only while a substep's take 20 us or more (64 Atwood machines: 1.6 to 1.7 "
          "times faster on 2 threads; README, \"Islands on threads\"). A Batch steps its scenes on one "
          "thread each.")
      .def_property(
          "frame_rate_hz", [](const SettingsView& v) { return v.scene().frame_rate_hz; },
          [](SettingsView& v, double hz) {
            checkRange("frame_rate_hz", hz, 0.0, 1e6, true);
            v.scene().frame_rate_hz = hz;
          },
          "Frames per simulated second, Hz: step() advances 1 / frame_rate_hz s per frame.")
      .def_property(
          "method", [](const SettingsView& v) { return std::string(solverMethodName(v.world().settings().solver)); },
          [](SettingsView& v, const std::string& name) {
            const auto kind = solverMethodFromName(name);
            if (!kind) throw py::value_error("method: expected \"direct\" or \"gauss-seidel\", got \"" + name + "\"");
            v.world().settings().solver = *kind;
          },
          "The solver: \"direct\" (every joint and cable solved together) or \"gauss-seidel\".")
      .def_property(
          "projection",
          [](const SettingsView& v) {
            return std::string(v.world().settings().projection == Projection::Start ? "start" : "end");
          },
          [](SettingsView& v, const std::string& name) {
            if (name != "start" && name != "end")
              throw py::value_error("projection: expected \"end\" or \"start\", got \"" + name + "\"");
            v.world().settings().projection = name == "start" ? Projection::Start : Projection::End;
          },
          "The direct solver's projection: \"end\" (XPBD, dissipative) or \"start\" (SHAKE: a pendulum keeps "
          "its swing energy); Gauss-Seidel always projects at the end.")
      .def_property(
          "gravity_m_per_s2",
          [](const SettingsView& v) {
            const Vec3 g = v.world().settings().gravity;
            return std::array<double, 3>{g.x(), g.y(), g.z()};
          },
          [](SettingsView& v, const std::array<double, 3>& g) {
            for (const double c : g)
              if (!std::isfinite(c)) throw py::value_error("gravity_m_per_s2: expected 3 finite numbers");
            v.world().settings().gravity = Vec3(g[0], g[1], g[2]);
          },
          "Gravity (m/s^2, world), 3 numbers.")
      .def("__repr__", [](const SettingsView& v) {
        const SolverSettings& s = v.world().settings();
        return "Settings(substeps=" + std::to_string(s.substeps) + ", iterations=" + std::to_string(s.iterations) +
               ", frame_rate_hz=" + py::repr(py::float_(v.scene().frame_rate_hz)).cast<std::string>() + ", method='" +
               solverMethodName(s.solver) + "')";
      });

  py::class_<PyScene>(m, "Scene",
                      "A loaded scene: bodies, joints and cables (Mueller et al., Cable Joints, SCA 2018) ready to "
                      "step. Make one with reeve.load(). Its views (settings, bodies, cables, hinges, joints) "
                      "read and write this scene; the arrays they return are copies (float64, SI units in the "
                      "names), taken when asked for. step(), render() and run() let other Python threads run "
                      "meanwhile, but use one Scene from one thread at a time.")
      .def_property_readonly(
          "name", [](const PyScene& s) { return s.scene.name; }, "The scene's name (str).")
      .def_property_readonly("description", [](const PyScene& s) { return s.scene.description; })
      .def_property_readonly(
          "source", [](const PyScene& s) { return s.source; },
          "The file it was loaded from, or \"<text>\" / \"<dict>\".")
      .def_property_readonly(
          "duration_s", [](const PyScene& s) { return s.scene.duration_s; },
          "The scene's duration_s (s): what run() simulates by default.")
      .def_property_readonly(
          "frame_count", [](const PyScene& s) { return s.scene.frameCount(); },
          "round(duration_s x frame_rate_hz) (int).")
      .def_property_readonly(
          "time_s", [](const PyScene& s) { return s.scene.world->time(); }, "Simulated time so far (s).")
      .def_property_readonly(
          "settings",
          [](py::object self) {
            return SettingsView{{self.cast<PyScene*>(), self}};
          },
          "The solver settings (reeve.Settings), writable.")
      .def("step", &step, py::arg("frames") = 1,
           "Advances `frames` frames of 1 / settings.frame_rate_hz s (each of settings.substeps substeps). "
           "Raises reeve.SimulationError, as `reeve run` stops, when the state becomes non-finite or the cable "
           "bookkeeping breaks. On Ctrl-C (SIGINT) the substep under way ends after its solver iteration in progress "
           "and KeyboardInterrupt is raised, the scene usable at time_s; SIGTERM likewise, then re-raised.")
      .def("render", &render, py::arg("width") = 1280, py::arg("height") = 720,
           "The current poses drawn as `reeve run --png` draws them (off-screen OpenGL, OSMesa): a numpy uint8 "
           "array of shape (height, width, 3), RGB, top row first. The camera is the scene's, or one that "
           "frames every body. ValueError for a size <= 0.")
      .def_property_readonly(
          "bodies",
          [](py::object self) {
            return BodiesView{{self.cast<PyScene*>(), self}};
          },
          "The rigid bodies (reeve.Bodies), in the scene's order.")
      .def_property_readonly(
          "cables",
          [](py::object self) {
            return CablesView{{self.cast<PyScene*>(), self}};
          },
          "The cables (reeve.Cables): cables[\"name\"] or cables[index].")
      .def_property_readonly(
          "hinges",
          [](py::object self) {
            return HingesView{{self.cast<PyScene*>(), self}};
          },
          "The hinges (reeve.Hinges), in the order of the scene's \"hinges\".")
      .def_property_readonly(
          "joints",
          [](py::object self) {
            return JointsView{{self.cast<PyScene*>(), self}};
          },
          "The prismatic, spherical and fixed joints (reeve.Joints), in the order of the "
          "scene's \"joints\".")
      .def("view", &viewScene, py::arg("port") = 8765, py::arg("host") = "127.0.0.1", py::arg("block") = true,
           "Runs the scene live in a browser, as `reeve view` does: from its start as its source has it (a file "
           "is reloaded when it changes on disk), with the scene's current substeps, iterations and solver. Prints "
           "the address to open. block=True serves until Ctrl-C (KeyboardInterrupt); block=False returns a "
           "reeve.Viewer serving on threads of its own (its url, stop(), a context manager). port 0 picks a free "
           "one. Raises FileNotFoundError without the viewer's files, RuntimeError when it cannot listen there.")
      .def("energy", &energy,
           "The energy ledger now (issue 28; DESIGN.md, \"Energy ledger\"), a dict of floats in J: kinetic_J, "
           "potential_J (gravity, 0 at the origin), elastic_J (compliant cables, joints, springs), total_J (their "
           "sum); since the scene was loaded: drive_work_J, load_work_J, winch_work_J, kinematic_work_J, work_J (their "
           "sum), damping_J, contact_J, friction_J (cable friction), cable_damping_J, dissipated_J (their sum); "
           "residual_J = total - total as loaded - work + "
           "dissipated: <= 0 (the integrator's own losses) unless energy was created. step() warns "
           "(RuntimeWarning) in a frame that created energy, as `reeve run` does.")
      .def("_run", &run, py::arg("frames"), py::arg("csv"), py::arg("png_dir"), py::arg("video"), py::arg("events"),
           py::arg("html"), py::arg("width"), py::arg("height"), py::arg("force"), py::arg("strict"))
      .def("__repr__", [](const PyScene& s) {
        return "<reeve.Scene '" + s.scene.name + "' from " + s.source +
               ", t = " + py::repr(py::float_(s.scene.world->time())).cast<std::string>() + " s, " +
               std::to_string(s.scene.world->bodyCount()) + " bodies, " +
               std::to_string(s.scene.cables->cables().size()) + " cables>";
      });
}

}  // namespace reeve::python
