// reeve.Hinges and reeve.Joints: joint forces, torques and angles as numpy
// arrays, and drive targets set between steps (controllers).
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "py_scene.h"

namespace py = pybind11;

namespace reeve::python {
namespace {

std::string bodyName(const World& world, BodyId id) {
  return id == kWorldBody ? std::string("world") : world.bodyDef(id).name;
}

int checkedIndex(int k, int n, const char* what) {
  if (k < 0 || k >= n)
    throw py::index_error(std::string(what) + " " + std::to_string(k) + " out of range for " + std::to_string(n));
  return k;
}

double finiteTarget(double target) {
  if (!std::isfinite(target))
    throw py::value_error("target: expected a finite number, got " +
                          py::repr(py::float_(target)).cast<std::string>());
  return target;
}

// (t_s, target) pairs as a drive schedule: finite, times strictly
// increasing, at least one (HingeDrive::schedule).
std::vector<DriveKeyframe> keyframes(const std::vector<std::pair<double, double>>& points) {
  if (points.empty()) throw py::value_error("schedule: expected at least one (t_s, target) pair, got none");
  std::vector<DriveKeyframe> out;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const auto [t, target] = points[k];
    if (!std::isfinite(t) || !std::isfinite(target) || t < 0.0)
      throw py::value_error("schedule[" + std::to_string(k) + "]: expected a time >= 0 s and a target, both finite");
    if (k > 0 && !(t > out.back().time))
      throw py::value_error("schedule[" + std::to_string(k) + "]: expected a time after the previous keyframe's " +
                            py::repr(py::float_(out.back().time)).cast<std::string>() + " s, got " +
                            py::repr(py::float_(t)).cast<std::string>());
    out.push_back({t, target});
  }
  return out;
}

// Force and torque rows, shape (n, 3) each.
std::pair<py::array_t<double>, py::array_t<double>> wrenches(const std::vector<JointWrench>& all) {
  const int n = static_cast<int>(all.size());
  py::array_t<double> force({n, 3}), torque({n, 3});
  auto f = force.mutable_unchecked<2>();
  auto t = torque.mutable_unchecked<2>();
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) f(i, k) = all[i].force[k], t(i, k) = all[i].torque[k];
  return {force, torque};
}

std::vector<JointWrench> hingeWrenches(const World& w) {
  std::vector<JointWrench> all;
  for (int i = 0; i < static_cast<int>(w.hinges().size()); ++i) all.push_back(w.hingeWrench(i));
  return all;
}

// The id in World of entry k of the scene's "joints" (Scene::joint_kinds).
int worldId(const Scene& s, int k) {
  int id = 0;
  for (int i = 0; i < k; ++i) id += s.joint_kinds[i] == s.joint_kinds[k];
  return id;
}

JointWrench jointWrench(const Scene& s, int k) {
  const int id = worldId(s, k);
  switch (s.joint_kinds[k]) {
    case JointKind::Prismatic: return s.world->prismaticWrench(id);
    case JointKind::Spherical: return s.world->sphericalWrench(id);
    case JointKind::Fixed: return s.world->fixedWrench(id);
  }
  return {};
}

std::vector<JointWrench> jointWrenches(const Scene& s) {
  std::vector<JointWrench> all;
  for (int k = 0; k < static_cast<int>(s.joint_kinds.size()); ++k) all.push_back(jointWrench(s, k));
  return all;
}

std::pair<BodyId, BodyId> jointBodies(const Scene& s, int k) {
  const int id = worldId(s, k);
  switch (s.joint_kinds[k]) {
    case JointKind::Prismatic: return {s.world->prismatic(id).a, s.world->prismatic(id).b};
    case JointKind::Spherical: return {s.world->spherical(id).a, s.world->spherical(id).b};
    case JointKind::Fixed: return {s.world->fixedJoint(id).a, s.world->fixedJoint(id).b};
  }
  return {};
}

const char* kindName(JointKind kind) {
  switch (kind) {
    case JointKind::Prismatic: return "prismatic";
    case JointKind::Spherical: return "spherical";
    case JointKind::Fixed: return "fixed";
  }
  return "?";
}

}  // namespace

void bindJoints(py::module_& m) {
  py::class_<HingesView>(
      m, "Hinges",
      "The scene's hinges, in the order of its \"hinges\". Arrays are copies (float64) of the state now; "
      "forces and torques are what each hinge exerted on its body over the last substep (world).")
      .def("__len__", [](const HingesView& v) { return v.world().hinges().size(); })
      .def_property_readonly(
          "bodies",
          [](const HingesView& v) {
            std::vector<std::pair<std::string, std::string>> pairs;
            for (const HingeJoint& h : v.world().hinges())
              pairs.push_back({bodyName(v.world(), h.a), bodyName(v.world(), h.b)});
            return pairs;
          },
          "(body, other) names of each hinge (list of tuples; \"world\" for the world).")
      .def_property_readonly(
          "angles_rad",
          [](const HingesView& v) {
            const int n = static_cast<int>(v.world().hinges().size());
            py::array_t<double> out(n);
            for (int i = 0; i < n; ++i) out.mutable_at(i) = v.world().hingeAngle(i);
            return out;
          },
          "Angle of body relative to other (rad), 0 when loaded, counted through whole turns (2 pi after a turn), "
          "shape (n,).")
      .def_property_readonly(
          "forces_N", [](const HingesView& v) { return wrenches(hingeWrenches(v.world())).first; },
          "Force each hinge exerted on its body (N, world), shape (n, 3).")
      .def_property_readonly(
          "torques_N_m", [](const HingesView& v) { return wrenches(hingeWrenches(v.world())).second; },
          "Torque each hinge exerted on its body about its centre (N m, world), shape (n, 3).")
      .def_property_readonly(
          "drive_torques_N_m",
          [](const HingesView& v) {
            const int n = static_cast<int>(v.world().hinges().size());
            py::array_t<double> out(n);
            for (int i = 0; i < n; ++i) out.mutable_at(i) = v.world().hingeDriveTorque(i);
            return out;
          },
          "Torque each hinge's drive (motor, servo or spring) exerted about its axis (N m), shape (n,); 0 without "
          "one.")
      .def_property_readonly(
          "drive_targets",
          [](const HingesView& v) {
            const int n = static_cast<int>(v.world().hinges().size());
            py::array_t<double> out(n);
            for (int i = 0; i < n; ++i) {
              const HingeDrive& d = v.world().hinge(i).drive;
              out.mutable_at(i) = d.mode == HingeDrive::Mode::None ? std::nan("") : d.target;
            }
            return out;
          },
          "Each drive's target, rad/s (velocity drive) or rad (angle drive or spring), shape (n,); NaN without a "
          "drive.")
      .def(
          "set_drive_target",
          [](HingesView& v, int hinge, double target) {
            const int i = checkedIndex(hinge, static_cast<int>(v.world().hinges().size()), "hinge");
            HingeDrive& d = v.world().hinge(i).drive;
            if (d.mode == HingeDrive::Mode::None)
              throw py::value_error("hinge " + std::to_string(i) + " has no drive (or its until_s has passed)");
            d.target = finiteTarget(target);
            d.schedule.clear();
          },
          py::arg("hinge"), py::arg("target"),
          "Sets hinge `hinge`'s drive target from the next step on: rad/s for a velocity drive, rad (any number of "
          "turns) for an angle drive or spring; a schedule it had ends. ValueError if it has no drive.")
      .def(
          "set_drive_schedule",
          [](HingesView& v, int hinge, const std::vector<std::pair<double, double>>& schedule) {
            const int i = checkedIndex(hinge, static_cast<int>(v.world().hinges().size()), "hinge");
            HingeDrive& d = v.world().hinge(i).drive;
            if (d.mode == HingeDrive::Mode::None)
              throw py::value_error("hinge " + std::to_string(i) + " has no drive (or its until_s has passed)");
            d.schedule = keyframes(schedule);
          },
          py::arg("hinge"), py::arg("schedule"),
          "Makes hinge `hinge`'s drive target follow `schedule`, (t_s, target) pairs in simulated time, t_s "
          "strictly increasing: linear between them, held before the first and after the last (scenes/README.md, "
          "\"schedule\"). ValueError if it has no drive or the schedule is not valid.")
      .def("__repr__",
           [](const HingesView& v) { return "<reeve.Hinges: " + std::to_string(v.world().hinges().size()) + ">"; });

  py::class_<JointsView>(
      m, "Joints",
      "The scene's prismatic, spherical and fixed joints, in the order of its \"joints\". Arrays are copies "
      "(float64); forces and torques are what each joint exerted on its body over the last substep (world).")
      .def("__len__", [](const JointsView& v) { return v.scene().joint_kinds.size(); })
      .def_property_readonly(
          "types",
          [](const JointsView& v) {
            std::vector<std::string> types;
            for (const JointKind k : v.scene().joint_kinds) types.push_back(kindName(k));
            return types;
          },
          "Each joint's type (list of str): \"prismatic\", \"spherical\" or \"fixed\".")
      .def_property_readonly(
          "bodies",
          [](const JointsView& v) {
            std::vector<std::pair<std::string, std::string>> pairs;
            for (int k = 0; k < static_cast<int>(v.scene().joint_kinds.size()); ++k) {
              const auto [a, b] = jointBodies(v.scene(), k);
              pairs.push_back({bodyName(v.world(), a), bodyName(v.world(), b)});
            }
            return pairs;
          },
          "(body, other) names of each joint (list of tuples; \"world\" for the world).")
      .def_property_readonly(
          "forces_N", [](const JointsView& v) { return wrenches(jointWrenches(v.scene())).first; },
          "Force each joint exerted on its body (N, world), shape (n, 3).")
      .def_property_readonly(
          "torques_N_m", [](const JointsView& v) { return wrenches(jointWrenches(v.scene())).second; },
          "Torque each joint exerted on its body about its centre (N m, world), shape (n, 3).")
      .def(
          "set_drive_target",
          [](JointsView& v, int joint, double target) {
            const Scene& s = v.scene();
            const int k = checkedIndex(joint, static_cast<int>(s.joint_kinds.size()), "joint");
            if (s.joint_kinds[k] != JointKind::Prismatic)
              throw py::value_error("joint " + std::to_string(k) + " is " + kindName(s.joint_kinds[k]) +
                                    "; only prismatic joints have drives");
            PrismaticDrive& d = v.world().prismatic(worldId(s, k)).drive;
            if (d.mode == PrismaticDrive::Mode::None)
              throw py::value_error("joint " + std::to_string(k) + " has no drive (or its until_s has passed)");
            d.target = finiteTarget(target);
            d.schedule.clear();
          },
          py::arg("joint"), py::arg("target"),
          "Sets prismatic joint `joint`'s drive target from the next step on: m/s for a velocity drive, m for a "
          "position drive or spring; a schedule it had ends. ValueError for another joint type or no drive.")
      .def("__repr__", [](const JointsView& v) {
        return "<reeve.Joints: " + std::to_string(v.scene().joint_kinds.size()) + ">";
      });
}

}  // namespace reeve::python
