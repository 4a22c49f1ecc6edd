// reeve.Cables and reeve.Cable: each cable's joints (tensions, rest
// lengths, lengths) and links (types, stored cable) as numpy arrays.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "py_scene.h"

namespace py = pybind11;

namespace reeve::python {
namespace {

const char* linkTypeName(LinkType type) {
  switch (type) {
    case LinkType::Attachment: return "attachment";
    case LinkType::Pinhole: return "pinhole";
    case LinkType::Rolling: return "rolling";
    case LinkType::Hybrid: return "hybrid";
  }
  return "?";
}

CableView cableOf(const CablesView& v, const std::variant<int, std::string>& key) {
  const auto& cables = v.scene().cables->cables();
  const int n = static_cast<int>(cables.size());
  if (const int* i = std::get_if<int>(&key)) {
    const int k = *i < 0 ? *i + n : *i;
    if (k < 0 || k >= n)
      throw py::index_error("cable index " + std::to_string(*i) + " out of range for " + std::to_string(n) +
                            " cables");
    return CableView{{v.owner, v.keep}, k};
  }
  const std::string& name = std::get<std::string>(key);
  for (int c = 0; c < n; ++c)
    if (cables[c].name == name) return CableView{{v.owner, v.keep}, c};
  throw py::key_error("no cable named '" + name + "' in scene '" + v.scene().name + "'");
}

const Cable& cable(const CableView& v) {
  return v.scene().cables->cables()[v.index];
}

// One number per joint of the cable, shape (joints,).
template <class Get>
py::array_t<double> perJoint(const CableView& v, Get get) {
  const int n = static_cast<int>(cable(v).joints.size());
  py::array_t<double> out(n);
  for (int j = 0; j < n; ++j) out.mutable_at(j) = get(*v.scene().cables, v.index, j);
  return out;
}

// One value per link of the cable: get(link), shape (links,).
template <class T, class Get>
py::array_t<T> perLink(const CableView& v, Get get) {
  const auto& links = cable(v).links;
  py::array_t<T> out(static_cast<py::ssize_t>(links.size()));
  for (std::size_t k = 0; k < links.size(); ++k) out.mutable_at(k) = get(links[k]);
  return out;
}

}  // namespace

void bindCables(py::module_& m) {
  py::class_<CableView>(
      m, "Cable",
      "One cable: links (attachments, pinholes, rolling and hybrid links, in the scene's order) and between "
      "each link and the next a cable joint, a unilateral distance constraint (paper sec. 3). Arrays are "
      "copies (float64) of the state now.")
      .def_property_readonly("name", [](const CableView& v) { return cable(v).name; })
      .def_property_readonly(
          "closed", [](const CableView& v) { return cable(v).closed; },
          "Whether the cable is a closed loop (a belt).")
      .def_property_readonly(
          "tensions_N",
          [](const CableView& v) {
            return perJoint(v, [](const CableSystem& c, int i, int j) { return c.tension(i, j); });
          },
          "Tension of each joint (N) over the last substep, shape (joints,); 0 while slack or merged away.")
      .def_property_readonly(
          "rest_lengths_m",
          [](const CableView& v) {
            return perJoint(v, [](const CableSystem& c, int i, int j) { return c.restLengthNow(i, j); });
          },
          "Rest length of each joint (m), shape (joints,): the cable between its two tangent points, as of the "
          "poses now.")
      .def_property_readonly(
          "lengths_m",
          [](const CableView& v) {
            return perJoint(v, [](const CableSystem& c, int i, int j) { return c.length(i, j); });
          },
          "Current straight length of each joint's span (m), shape (joints,); longer than the rest length by "
          "the stretch.")
      .def_property_readonly(
          "joint_enabled",
          [](const CableView& v) {
            const int n = static_cast<int>(cable(v).joints.size());
            py::array_t<bool> out(n);
            for (int j = 0; j < n; ++j) out.mutable_at(j) = v.scene().cables->jointEnabled(v.index, j);
            return out;
          },
          "Whether each joint exists now (its link is active, merge and split, paper sec. 4.3; and it has not "
          "parted at the cable's breaking tension), shape (joints,).")
      .def_property_readonly(
          "stored_m",
          [](const CableView& v) {
            py::array_t<double> out(static_cast<py::ssize_t>(cable(v).links.size()));
            for (int k = 0; k < static_cast<int>(cable(v).links.size()); ++k)
              out.mutable_at(k) = v.scene().cables->storedNow(v.index, k);
            return out;
          },
          "Cable stored on each link (m), shape (links,): wound on a rolling or hybrid end or a winch's drum, "
          "and after a break the loose cable hanging from the link; 0 elsewhere.")
      .def_property_readonly(
          "slip_speeds_m_per_s",
          [](const CableView& v) { return perLink<double>(v, [](const Link& l) { return l.slip_speed; }); },
          "Slip speed of each link (m/s), shape (links,): cable sliding forward (towards the next link) over "
          "the body or through the hole, measured as the last substep started, over the one before it; 0 "
          "where it sticks, rolls or is tied.")
      .def_property_readonly(
          "slipping",
          [](const CableView& v) { return perLink<bool>(v, [](const Link& l) { return l.slides(); }); },
          "Whether the cable slides over or through each link now, shape (links,): frictionless pinholes "
          "and wraps always, friction links (mu) while their capstan bound is exceeded.")
      .def_property_readonly(
          "link_types",
          [](const CableView& v) {
            std::vector<std::string> types;
            for (const Link& l : cable(v).links) types.push_back(linkTypeName(l.type));
            return types;
          },
          "Each link's type (list of str): \"attachment\", \"pinhole\", \"rolling\" or \"hybrid\".")
      .def_property_readonly(
          "link_bodies",
          [](const CableView& v) {
            std::vector<std::string> names;
            for (const Link& l : cable(v).links)
              names.push_back(l.body == kWorldBody ? "world" : v.world().bodyDef(l.body).name);
            return names;
          },
          "The body of each link (list of str).")
      .def_property_readonly(
          "total_length_m", [](const CableView& v) { return v.scene().cables->totalLength(v.index); },
          "Rest lengths plus stored cable (m): conserved while the cable runs over its links.")
      .def_property_readonly(
          "winch_pull_N",
          [](const CableView& v) -> std::optional<double> {
            if (!cable(v).winch) return std::nullopt;
            return v.scene().cables->winchPull(v.index);
          },
          "The pull of the cable's winch (N) over the last substep; None without a winch.")
      .def(
          "command_winch",
          [](CableView& v, std::optional<double> speed_m_per_s, std::optional<double> stored_m) {
            if (!cable(v).winch) throw py::value_error("cable '" + cable(v).name + "' has no winch");
            if (speed_m_per_s.has_value() == stored_m.has_value())
              throw py::value_error("expected exactly one of speed_m_per_s and stored_m");
            WinchDef winch = *cable(v).winch;
            winch.speed = speed_m_per_s.value_or(0.0);
            winch.target_stored = stored_m;
            winch.schedule.clear();
            try {
              v.scene().cables->setWinch(v.index, winch);
            } catch (const std::invalid_argument& e) {
              throw py::value_error(e.what());
            }
          },
          py::kw_only(), py::arg("speed_m_per_s") = py::none(), py::arg("stored_m") = py::none(),
          "Commands the cable's winch from now on, replacing the scene's schedule: reel at speed_m_per_s "
          "(m/s of cable, > 0 hauls in) or towards stored_m (m on the drum) at its max speed. ValueError "
          "without a winch, with both or neither, or out of range (a speed above max_speed_m_per_s, a "
          "negative or non-finite value).")
      .def(
          "set_rest_length",
          [](CableView& v, int joint, double rest_length_m) {
            const int n = static_cast<int>(cable(v).joints.size());
            if (joint < 0 || joint >= n)
              throw py::index_error("joint " + std::to_string(joint) + " out of range for " + std::to_string(n) +
                                    " joints");
            if (!std::isfinite(rest_length_m) || rest_length_m < 0.0)
              throw py::value_error("rest_length_m: expected a finite number >= 0, got " +
                                    py::repr(py::float_(rest_length_m)).cast<std::string>());
            v.scene().cables->setRestLength(v.index, joint, rest_length_m);
          },
          py::arg("joint"), py::arg("rest_length_m"),
          "Sets a joint's rest length (m, >= 0): a winch paying out or hauling in cable. The cable's total length "
          "becomes what it then is.")
      .def("__repr__", [](const CableView& v) {
        return "<reeve.Cable '" + cable(v).name + "': " + std::to_string(cable(v).links.size()) + " links, " +
               std::to_string(cable(v).joints.size()) + " joints>";
      });

  py::class_<CablesView>(m, "Cables", "The scene's cables: cables[\"name\"], cables[index], len(), iteration, `in`.")
      .def("__len__", [](const CablesView& v) { return v.scene().cables->cables().size(); })
      .def("__getitem__", &cableOf, py::arg("key"))
      .def("__contains__",
           [](const CablesView& v, const std::string& name) {
             for (const Cable& c : v.scene().cables->cables())
               if (c.name == name) return true;
             return false;
           })
      .def("__iter__",
           [](const CablesView& v) {
             py::list all;
             for (int c = 0; c < static_cast<int>(v.scene().cables->cables().size()); ++c)
               all.append(py::cast(CableView{{v.owner, v.keep}, c}));
             return py::iter(all);
           })
      .def_property_readonly(
          "names",
          [](const CablesView& v) {
            std::vector<std::string> names;
            for (const Cable& c : v.scene().cables->cables()) names.push_back(c.name);
            return names;
          },
          "Cable names (list of str), in the scene's order.")
      .def("__repr__", [](const CablesView& v) {
        return "<reeve.Cables: " + std::to_string(v.scene().cables->cables().size()) + ">";
      });
}

}  // namespace reeve::python
