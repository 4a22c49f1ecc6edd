// The Python module's C++ side (_reeve): a loaded scene and the views of its
// state that share it. Doc strings are in the bind*() functions.
#pragma once

#include <pybind11/pybind11.h>

#include <memory>
#include <string>
#include <utility>

#include "reeve/render/renderer.h"
#include "reeve/scene/energy.h"
#include "reeve/scene/scene.h"

namespace reeve::python {

/// A scene loaded from Python, with the renderer its render() reuses.
struct PyScene {
  PyScene(Scene scene_, std::string source_, std::string text_ = {})
      : scene(std::move(scene_)), source(std::move(source_)), text(std::move(text_)),
        start_balance_J(energyLedger(scene).balance_J()), energy(scene) {}
  Scene scene;
  std::string source;                  ///< file name, "<text>" or "<dict>": for messages
  std::string text;                    ///< the JSON it was loaded from; empty for a file
  std::unique_ptr<Renderer> renderer;  ///< made by the first render(), remade for another size
  double start_balance_J;              ///< EnergyLedger::balance_J as loaded: energy()'s residual_J
  EnergyWatch energy;                  ///< step()'s watch: warns of energy created
};

/// The views (Settings, Bodies, Cables, Cable, Hinges, Joints) hold a
/// reference to the Python Scene, so it lives as long as any of them, and
/// read it on every access.
struct View {
  PyScene* owner;
  pybind11::object keep;  ///< the Python Scene object
  Scene& scene() const { return owner->scene; }
  World& world() const { return *owner->scene.world; }
};

struct SettingsView : View {};
struct BodiesView : View {};
struct CablesView : View {};
struct CableView : View {
  int index;  ///< CableSystem's cable index
};
struct HingesView : View {};
struct JointsView : View {};

void bindErrors(pybind11::module_& m);
void bindScene(pybind11::module_& m);
void bindBodies(pybind11::module_& m);
void bindCables(pybind11::module_& m);
void bindJoints(pybind11::module_& m);
void bindBatch(pybind11::module_& m);
void bindView(pybind11::module_& m);
/// Scene.view() (py_view.cpp): `reeve view` on the scene's source.
pybind11::object viewScene(const PyScene& s, int port, const std::string& host, bool block);

/// Raises reeve.SimulationError (a RuntimeError) with `message`.
[[noreturn]] void throwSimulationError(const std::string& message);

/// Whether this is Python's main thread, where it handles signals.
bool onMainThread();

/// After a call that `signal` ended (InterruptGuard): SIGINT as Python
/// would have, KeyboardInterrupt; SIGTERM raised again, now to the
/// interpreter's own handler. Nothing for 0.
void raiseReceivedSignal(int signal);

}  // namespace reeve::python
