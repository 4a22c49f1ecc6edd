// reeve.Batch: many scenes stepped side by side on a thread pool, their
// state as arrays with a leading batch axis (issue 30).
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "batch.h"
#include "interrupt.h"
#include "py_scene.h"

namespace py = pybind11;

namespace reeve::python {
namespace {

struct PyBatch {
  std::vector<py::object> objects;  ///< the reeve.Scene objects, kept alive
  std::vector<PyScene*> scenes;
  std::unique_ptr<ThreadPool> pool;
};

std::string at(int i) { return "scene " + std::to_string(i); }

PyScene* sceneOf(const py::handle& item, int i) {
  try {
    return item.cast<PyScene*>();
  } catch (const py::cast_error&) {
    throw py::type_error("Batch: " + at(i) + ": expected a reeve.Scene, got " +
                         std::string(py::str(item.get_type().attr("__name__"))));
  }
}

std::unique_ptr<PyBatch> makeBatch(const py::object& source, std::optional<int> copies, std::optional<int> threads) {
  auto batch = std::make_unique<PyBatch>();
  const bool listed = py::isinstance<py::list>(source) || py::isinstance<py::tuple>(source);
  if (listed) {
    if (copies) throw py::value_error("Batch: copies is for one source; a list is its own scenes");
    for (const py::handle item : source) batch->objects.push_back(py::reinterpret_borrow<py::object>(item));
  } else {
    const int n = copies.value_or(1);
    if (n < 1) throw py::value_error("Batch: copies: expected a count >= 1, got " + std::to_string(n));
    if (py::isinstance<PyScene>(source) && n > 1)
      throw py::value_error("Batch: copies of a loaded reeve.Scene cannot be made; give its file, JSON text or dict");
    const py::object load = py::module_::import("reeve").attr("load");
    for (int k = 0; k < n; ++k)
      batch->objects.push_back(py::isinstance<PyScene>(source) ? source : load(source));
  }
  if (batch->objects.empty()) throw py::value_error("Batch: expected at least one scene, got none");
  for (std::size_t i = 0; i < batch->objects.size(); ++i) {
    PyScene* s = sceneOf(batch->objects[i], static_cast<int>(i));
    for (std::size_t j = 0; j < i; ++j)
      if (batch->scenes[j] == s)
        throw py::value_error("Batch: " + at(static_cast<int>(i)) + " is " + at(static_cast<int>(j)) +
                              " again (each scene is stepped by one thread)");
    s->scene.world->setThreads(1);  // the batch's threads step the scenes side by side
    batch->scenes.push_back(s);
  }
  const int n = threads.value_or(ThreadPool::cores());
  if (n < 1 || n > 1024) throw py::value_error("Batch: threads: expected 1..1024, got " + std::to_string(n));
  batch->pool = std::make_unique<ThreadPool>(std::min<int>(n, static_cast<int>(batch->scenes.size())));
  return batch;
}

void stepAll(PyBatch& b, int frames) {
  if (frames < 0) throw py::value_error("frames: expected a count >= 0, got " + std::to_string(frames));
  std::vector<BatchItem> items;
  for (PyScene* s : b.scenes) items.push_back({&s->scene, &s->energy});
  // As Scene.step: on the main thread SIGINT and SIGTERM end every scene's
  // substep under way, then Python sees the signal.
  std::optional<InterruptGuard> interrupt;
  if (onMainThread()) interrupt.emplace();
  struct Detach {
    PyBatch& b;
    ~Detach() {
      for (PyScene* s : b.scenes) s->scene.world->setInterruptFlag(nullptr);
    }
  } detach{b};
  if (interrupt)
    for (PyScene* s : b.scenes) s->scene.world->setInterruptFlag(InterruptGuard::flag());
  std::vector<BatchOutcome> outcomes;
  {
    py::gil_scoped_release release;
    outcomes = stepBatch(items, frames, *b.pool);
  }
  for (PyScene* s : b.scenes) s->scene.cables->takeEvents();  // as Scene.step: not kept
  for (std::size_t i = 0; i < outcomes.size(); ++i)
    for (const EnergyCreated& e : outcomes[i].energy_created)
      if (PyErr_WarnEx(PyExc_RuntimeWarning, ("reeve: " + at(static_cast<int>(i)) + ": " + energyCreatedMessage(e)).c_str(),
                       1) != 0)
        throw py::error_already_set();
  std::string stopped;
  int count = 0;
  for (std::size_t i = 0; i < outcomes.size(); ++i)
    if (outcomes[i].stopped && count++ == 0) stopped = at(static_cast<int>(i)) + ": " + *outcomes[i].stopped;
  const int signal = interrupt ? interrupt->received() : 0;
  interrupt.reset();
  if (count > 0)
    throwSimulationError("reeve: " + stopped +
                         (count > 1 ? " (and " + std::to_string(count - 1) + " more scenes stopped)" : std::string()));
  raiseReceivedSignal(signal);
  if (PyErr_CheckSignals() != 0) throw py::error_already_set();
}

// The number of bodies (hinges) every scene has, or ValueError.
template <class Count>
int common(const PyBatch& b, const char* what, Count count) {
  const int n = count(*b.scenes[0]);
  for (std::size_t i = 1; i < b.scenes.size(); ++i)
    if (count(*b.scenes[i]) != n)
      throw py::value_error(std::string("Batch: ") + what + " differ (" + at(0) + " has " + std::to_string(n) + ", " +
                            at(static_cast<int>(i)) + " " + std::to_string(count(*b.scenes[i])) +
                            "): read each scene's own");
  return n;
}

int bodyCount(const PyBatch& b) {
  return common(b, "body counts", [](const PyScene& s) { return s.scene.world->bodyCount(); });
}
int hingeCount(const PyBatch& b) {
  return common(b, "hinge counts", [](const PyScene& s) { return static_cast<int>(s.scene.world->hinges().size()); });
}

// (N, bodies, 3) of each body's vector.
template <class Get>
py::array_t<double> bodyRows(const PyBatch& b, Get get) {
  const int n = static_cast<int>(b.scenes.size()), m = bodyCount(b);
  py::array_t<double> out({n, m, 3});
  auto a = out.mutable_unchecked<3>();
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < m; ++k) {
      const Vec3 x = get(b.scenes[i]->scene.world->body(k));
      for (int c = 0; c < 3; ++c) a(i, k, c) = x[c];
    }
  return out;
}

// (N, hinges) of each hinge's number.
template <class Get>
py::array_t<double> hingeValues(const PyBatch& b, Get get) {
  const int n = static_cast<int>(b.scenes.size()), m = hingeCount(b);
  py::array_t<double> out({n, m});
  auto a = out.mutable_unchecked<2>();
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < m; ++k) a(i, k) = get(*b.scenes[i]->scene.world, k);
  return out;
}

// Checks `values` is (N, bodies, 3) and finite, and zero on the bodies no
// force moves, before anything is set; then sets field of each body.
void setBodyRows(PyBatch& b, const py::array_t<double, py::array::c_style | py::array::forcecast>& values,
                 const char* what, Vec3 BodyState::*field) {
  const int n = static_cast<int>(b.scenes.size()), m = bodyCount(b);
  if (values.ndim() != 3 || values.shape(0) != n || values.shape(1) != m || values.shape(2) != 3)
    throw py::value_error(std::string(what) + ": expected shape (" + std::to_string(n) + ", " + std::to_string(m) +
                          ", 3)");
  const auto a = values.unchecked<3>();
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < m; ++k) {
      const Vec3 x(a(i, k, 0), a(i, k, 1), a(i, k, 2));
      if (!x.allFinite())
        throw py::value_error(std::string(what) + "[" + std::to_string(i) + ", " + std::to_string(k) +
                              "]: expected 3 finite numbers");
      const World& w = *b.scenes[i]->scene.world;
      if (!x.isZero() && (w.bodyDef(k).is_static || w.body(k).kinematic))
        throw py::value_error(std::string(what) + "[" + std::to_string(i) + ", " + std::to_string(k) + "]: body '" +
                              w.bodyDef(k).name + "' is " + (w.bodyDef(k).is_static ? "static" : "kinematic") +
                              " (give it zeros)");
    }
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < m; ++k) b.scenes[i]->scene.world->body(k).*field = Vec3(a(i, k, 0), a(i, k, 1), a(i, k, 2));
}

void setDriveTargets(PyBatch& b, const py::array_t<double, py::array::c_style | py::array::forcecast>& targets) {
  const int n = static_cast<int>(b.scenes.size()), m = hingeCount(b);
  if (targets.ndim() != 2 || targets.shape(0) != n || targets.shape(1) != m)
    throw py::value_error("drive_targets: expected shape (" + std::to_string(n) + ", " + std::to_string(m) + ")");
  const auto a = targets.unchecked<2>();
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < m; ++k) {
      if (std::isnan(a(i, k))) continue;
      const std::string where = "drive_targets[" + std::to_string(i) + ", " + std::to_string(k) + "]";
      if (!std::isfinite(a(i, k))) throw py::value_error(where + ": expected a finite number or NaN (left as it is)");
      if (b.scenes[i]->scene.world->hinge(k).drive.mode == HingeDrive::Mode::None)
        throw py::value_error(where + ": hinge " + std::to_string(k) + " has no drive (or its until_s has passed)");
    }
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < m; ++k) {
      if (std::isnan(a(i, k))) continue;
      HingeDrive& d = b.scenes[i]->scene.world->hinge(k).drive;
      d.target = a(i, k);
      d.schedule.clear();
    }
}

}  // namespace

void bindBatch(py::module_& m) {
  using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;
  py::class_<PyBatch>(
      m, "Batch",
      "Many scenes stepped side by side on a pool of threads, with the GIL released: copies of one machine for a "
      "controller search or a learning loop, or different machines. Each scene's state after a step is the same bit "
      "for bit as stepping it alone, whatever the number of threads. The arrays have a leading batch axis (scene "
      "i first) and are copies; the scenes themselves (`scenes`) are ordinary reeve.Scene objects for everything "
      "else. Use a Batch from one Python thread at a time, and do not step its scenes elsewhere meanwhile.")
      .def(py::init(&makeBatch), py::arg("source"), py::arg("copies") = py::none(), py::arg("threads") = py::none(),
           "Batch(source, copies=None, threads=None). source: what reeve.load() takes (a path, JSON text or a dict), "
           "loaded `copies` times (default 1), or a list of reeve.Scene objects (each once; they are shared, not "
           "copied). threads: 1..1024, default the machine's cores; never more than there are scenes. "
           "ValueError or TypeError for anything else, reeve.SceneError for a source that cannot be loaded.")
      .def("__len__", [](const PyBatch& b) { return b.scenes.size(); })
      .def_property_readonly(
          "scenes", [](const PyBatch& b) { return b.objects; }, "The scenes (list of reeve.Scene), in batch order.")
      .def_property_readonly(
          "threads", [](const PyBatch& b) { return b.pool->threads(); }, "Threads the batch steps on (int).")
      .def("step", &stepAll, py::arg("frames") = 1,
           "Advances every scene `frames` frames (of its own 1 / frame_rate_hz s). A scene that stops (non-finite "
           "state, broken cable bookkeeping) is left where it stopped while the others run their frames; then "
           "reeve.SimulationError names it. A frame that created energy warns (RuntimeWarning) naming its scene. "
           "Ctrl-C and SIGTERM as Scene.step: each scene ends the substep it is in, so after step(n) with a large n "
           "the scenes may stand at different times (each thread steps one scene's frames, then the next's; see "
           "time_s).")
      .def_property_readonly(
          "time_s",
          [](const PyBatch& b) {
            py::array_t<double> out(static_cast<py::ssize_t>(b.scenes.size()));
            for (std::size_t i = 0; i < b.scenes.size(); ++i) out.mutable_at(i) = b.scenes[i]->scene.world->time();
            return out;
          },
          "Each scene's simulated time (s), shape (N,).")
      .def_property_readonly(
          "positions_m", [](const PyBatch& b) { return bodyRows(b, [](const BodyState& s) { return s.x; }); },
          "Centres of mass (m, world), shape (N, bodies, 3). ValueError where the scenes' body counts differ.")
      .def_property_readonly(
          "orientations",
          [](const PyBatch& b) {
            const int n = static_cast<int>(b.scenes.size()), m = bodyCount(b);
            py::array_t<double> out({n, m, 4});
            auto a = out.mutable_unchecked<3>();
            for (int i = 0; i < n; ++i)
              for (int k = 0; k < m; ++k) {
                const Quat& q = b.scenes[i]->scene.world->body(k).q;
                a(i, k, 0) = q.w(), a(i, k, 1) = q.x(), a(i, k, 2) = q.y(), a(i, k, 3) = q.z();
              }
            return out;
          },
          "Unit quaternions body -> world (w, x, y, z), shape (N, bodies, 4).")
      .def_property_readonly(
          "linear_velocities_m_per_s",
          [](const PyBatch& b) { return bodyRows(b, [](const BodyState& s) { return s.v; }); },
          "Velocities of the centres of mass (m/s), shape (N, bodies, 3).")
      .def_property_readonly(
          "angular_velocities_rad_per_s",
          [](const PyBatch& b) { return bodyRows(b, [](const BodyState& s) { return s.omega; }); },
          "Angular velocities (rad/s, world), shape (N, bodies, 3).")
      .def_property_readonly(
          "hinge_angles_rad",
          [](const PyBatch& b) { return hingeValues(b, [](const World& w, int k) { return w.hingeAngle(k); }); },
          "Hinge angles (rad, through whole turns), shape (N, hinges). ValueError where the hinge counts differ.")
      .def_property_readonly(
          "hinge_drive_torques_N_m",
          [](const PyBatch& b) { return hingeValues(b, [](const World& w, int k) { return w.hingeDriveTorque(k); }); },
          "Torque of each hinge's drive about its axis (N m), shape (N, hinges); 0 without one.")
      .def("set_applied_forces",
           [](PyBatch& b, const Array& f) { setBodyRows(b, f, "applied_forces_N", &BodyState::applied_force); },
           py::arg("forces_N"),
           "Sets the force (N, world) through each body's centre of mass in every substep until set again, shape "
           "(N, bodies, 3); zeros on static and kinematic bodies. Checked whole before anything is set (ValueError).")
      .def("set_applied_torques",
           [](PyBatch& b, const Array& t) { setBodyRows(b, t, "applied_torques_N_m", &BodyState::applied_torque); },
           py::arg("torques_N_m"), "As set_applied_forces, for torques (N m, world).")
      .def("set_hinge_drive_targets", &setDriveTargets, py::arg("targets"),
           "Sets hinge drive targets, shape (N, hinges): rad/s for a velocity drive, rad for an angle drive or "
           "spring; NaN leaves a hinge as it is. A schedule it had ends. ValueError (nothing set) for a target on a "
           "hinge without a drive.")
      .def("__repr__", [](const PyBatch& b) {
        return "<reeve.Batch: " + std::to_string(b.scenes.size()) + " scenes on " + std::to_string(b.pool->threads()) +
               " threads>";
      });
}

}  // namespace reeve::python
