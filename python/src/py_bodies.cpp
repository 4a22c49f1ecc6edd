// reeve.Bodies: the rigid bodies' state as numpy arrays, and setting it
// between steps.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <array>
#include <cmath>
#include <string>
#include <variant>
#include <vector>

#include "py_scene.h"

namespace py = pybind11;

namespace reeve::python {
namespace {

using BodyKey = std::variant<int, std::string>;

// A body by index (negative from the end, as Python's) or name; IndexError
// or KeyError otherwise.
BodyId bodyOf(const View& v, const BodyKey& key) {
  const int n = v.world().bodyCount();
  if (const int* i = std::get_if<int>(&key)) {
    const int k = *i < 0 ? *i + n : *i;
    if (k < 0 || k >= n)
      throw py::index_error("body index " + std::to_string(*i) + " out of range for " + std::to_string(n) +
                            " bodies");
    return k;
  }
  const std::string& name = std::get<std::string>(key);
  if (const auto id = v.world().findBody(name)) return *id;
  throw py::key_error("no body named '" + name + "' in scene '" + v.scene().name + "'");
}

// One flag per body, shape (n,).
template <class Get>
py::array_t<bool> flags(const View& v, Get get) {
  const int n = v.world().bodyCount();
  py::array_t<bool> out(n);
  for (BodyId b = 0; b < n; ++b) out.mutable_at(b) = get(b);
  return out;
}

// Each body's vector as an (n, 3) array.
template <class Get>
py::array_t<double> rows3(const View& v, Get get) {
  const int n = v.world().bodyCount();
  py::array_t<double> out({n, 3});
  auto a = out.mutable_unchecked<2>();
  for (int b = 0; b < n; ++b) {
    const Vec3 x = get(v.world().body(b), b);
    for (int k = 0; k < 3; ++k) a(b, k) = x[k];
  }
  return out;
}

Vec3 finite3(const std::array<double, 3>& x, const char* what) {
  for (const double c : x)
    if (!std::isfinite(c)) throw py::value_error(std::string(what) + ": expected 3 finite numbers");
  return Vec3(x[0], x[1], x[2]);
}

// Velocities and loads on a body that never moves would be silently lost.
BodyId movingBody(const View& v, const BodyKey& key, const char* what) {
  const BodyId id = bodyOf(v, key);
  if (v.world().bodyDef(id).is_static)
    throw py::value_error(std::string(what) + ": body '" + v.world().bodyDef(id).name + "' is static");
  if (v.world().body(id).kinematic)
    throw py::value_error(std::string(what) + ": body '" + v.world().bodyDef(id).name +
                          "' is kinematic (its \"motion\" sets its velocities, and no force moves it)");
  return id;
}

}  // namespace

void bindBodies(py::module_& m) {
  py::class_<BodiesView>(
      m, "Bodies",
      "The scene's rigid bodies, in its order; index them by position or name. The array properties are "
      "copies (float64, world frame, SI units in the name) of the state now; set state with the set_* methods "
      "between steps. A body is an int (negative counts from the end) or its name.")
      .def("__len__", [](const BodiesView& v) { return v.world().bodyCount(); })
      .def_property_readonly(
          "names",
          [](const BodiesView& v) {
            std::vector<std::string> names;
            for (int b = 0; b < v.world().bodyCount(); ++b) names.push_back(v.world().bodyDef(b).name);
            return names;
          },
          "Names (list of str, n).")
      .def(
          "index", [](const BodiesView& v, const std::string& name) { return bodyOf(v, name); }, py::arg("name"),
          "The position of the body called `name`; KeyError if there is none.")
      .def_property_readonly(
          "positions_m", [](const BodiesView& v) { return rows3(v, [](const BodyState& b, BodyId) { return b.x; }); },
          "Centres of mass (m), shape (n, 3).")
      .def_property_readonly(
          "orientations",
          [](const BodiesView& v) {
            const int n = v.world().bodyCount();
            py::array_t<double> out({n, 4});
            auto a = out.mutable_unchecked<2>();
            for (int b = 0; b < n; ++b) {
              const Quat& q = v.world().body(b).q;
              a(b, 0) = q.w(), a(b, 1) = q.x(), a(b, 2) = q.y(), a(b, 3) = q.z();
            }
            return out;
          },
          "Unit quaternions body -> world, (w, x, y, z), shape (n, 4).")
      .def_property_readonly(
          "linear_velocities_m_per_s",
          [](const BodiesView& v) { return rows3(v, [](const BodyState& b, BodyId) { return b.v; }); },
          "Velocities of the centres of mass (m/s), shape (n, 3).")
      .def_property_readonly(
          "angular_velocities_rad_per_s",
          [](const BodiesView& v) { return rows3(v, [](const BodyState& b, BodyId) { return b.omega; }); },
          "Angular velocities (rad/s, world), shape (n, 3).")
      .def_property_readonly(
          "masses_kg",
          [](const BodiesView& v) {
            const int n = v.world().bodyCount();
            py::array_t<double> out(n);
            for (int b = 0; b < n; ++b) out.mutable_at(b) = v.world().bodyMass(b);
            return out;
          },
          "Masses (kg), shape (n,); 0 for static bodies.")
      .def_property_readonly(
          "static", [](const BodiesView& v) { return flags(v, [&](BodyId b) { return v.world().bodyDef(b).is_static; }); },
          "Whether each body is static (bool), shape (n,).")
      .def_property_readonly(
          "kinematic", [](const BodiesView& v) { return flags(v, [&](BodyId b) { return v.world().body(b).kinematic; }); },
          "Whether each body is kinematic (bool), shape (n,): moved by its \"motion\", whatever pushes on it.")
      .def_property_readonly(
          "applied_forces_N",
          [](const BodiesView& v) { return rows3(v, [](const BodyState& b, BodyId) { return b.applied_force; }); },
          "The forces set with set_applied_force (N, world), shape (n, 3).")
      .def_property_readonly(
          "applied_torques_N_m",
          [](const BodiesView& v) { return rows3(v, [](const BodyState& b, BodyId) { return b.applied_torque; }); },
          "The torques set with set_applied_torque (N m, world), shape (n, 3).")
      .def(
          "set_position",
          [](BodiesView& v, const BodyKey& body, const std::array<double, 3>& x) {
            v.world().body(bodyOf(v, body)).x = finite3(x, "position_m");
          },
          py::arg("body"), py::arg("position_m"),
          "Moves a body's centre of mass to `position_m` (m, world; 3 numbers). Its cables find their new tangent "
          "points in the next substep; a span moved far past its rest length is pulled back hard.")
      .def(
          "set_orientation",
          [](BodiesView& v, const BodyKey& body, const std::array<double, 4>& wxyz) {
            Quat q(wxyz[0], wxyz[1], wxyz[2], wxyz[3]);
            const double norm = q.norm();
            if (!std::isfinite(norm) || std::abs(norm - 1.0) > 1e-6)
              throw py::value_error("orientation: expected a unit quaternion (w, x, y, z), got norm " +
                                    py::repr(py::float_(norm)).cast<std::string>());
            q.normalize();
            v.world().body(bodyOf(v, body)).q = q;
          },
          py::arg("body"), py::arg("orientation"),
          "Sets a body's orientation, a unit quaternion (w, x, y, z) body -> world. A wheel with cable on it "
          "must turn less than half a turn from where it was (its cable counts the turn).")
      .def(
          "set_linear_velocity",
          [](BodiesView& v, const BodyKey& body, const std::array<double, 3>& vel) {
            v.world().body(movingBody(v, body, "linear_velocity_m_per_s")).v =
                finite3(vel, "linear_velocity_m_per_s");
          },
          py::arg("body"), py::arg("velocity_m_per_s"),
          "Sets the velocity of a body's centre of mass (m/s, world). ValueError for a static or kinematic body.")
      .def(
          "set_angular_velocity",
          [](BodiesView& v, const BodyKey& body, const std::array<double, 3>& w) {
            v.world().body(movingBody(v, body, "angular_velocity_rad_per_s")).omega =
                finite3(w, "angular_velocity_rad_per_s");
          },
          py::arg("body"), py::arg("angular_velocity_rad_per_s"),
          "Sets a body's angular velocity (rad/s, world). ValueError for a static or kinematic body.")
      .def(
          "set_applied_force",
          [](BodiesView& v, const BodyKey& body, const std::array<double, 3>& f) {
            v.world().body(movingBody(v, body, "applied_force_N")).applied_force = finite3(f, "applied_force_N");
          },
          py::arg("body"), py::arg("force_N"),
          "Applies a force (N, world) through the body's centre of mass in every substep until set again "
          "(zeros to remove it). ValueError for a static body.")
      .def(
          "set_applied_torque",
          [](BodiesView& v, const BodyKey& body, const std::array<double, 3>& t) {
            v.world().body(movingBody(v, body, "applied_torque_N_m")).applied_torque =
                finite3(t, "applied_torque_N_m");
          },
          py::arg("body"), py::arg("torque_N_m"),
          "Applies a torque (N m, world) in every substep until set again. A hinged wheel the direct solver "
          "turns about a fixed axle takes the part along the axle. ValueError for a static body.")
      .def("__repr__",
           [](const BodiesView& v) { return "<reeve.Bodies: " + std::to_string(v.world().bodyCount()) + ">"; });
}

}  // namespace reeve::python
