#include <set>
#include <stdexcept>

#include "build.h"
#include "describe.h"

namespace reeve::scene_detail {
namespace {

const char* shapeName(Shape::Type type) {
  switch (type) {
    case Shape::Type::Box:
      return "box";
    case Shape::Type::Cylinder:
      return "cylinder";
    case Shape::Type::Sphere:
      return "sphere";
  }
  return "shape";
}

LinkDef linkOf(const nlohmann::json& link, const std::string& path, const BodyNames& names,
               const World& world, const std::string& source) {
  LinkDef def;
  def.body = names.find(link.at("body"), path + "/body", source, false);
  if (link.at("type") == "attachment") {
    def.type = LinkType::Attachment;
    def.point = vec3(link.at("point_m"));
    return def;
  }
  const Shape& shape = world.bodyDef(def.body).shape;
  if (circularSectionRadius(shape) <= 0.0)
    throw SceneError(source, path + "/body",
                     "a body with a circular cross-section (cylinder or sphere) for a rolling link",
                     std::string(shapeName(shape.type)) + " " + literal(link.at("body")));
  def.type = LinkType::Rolling;
  def.orientation = link.at("orientation") == "ccw" ? 1 : -1;
  return def;
}

}  // namespace

void addCables(const nlohmann::json& cables, const BodyNames& names, const World& world,
               CableSystem& system, const std::string& source) {
  std::set<std::string> cable_names;
  for (std::size_t c = 0; c < cables.size(); ++c) {
    const nlohmann::json& cable = cables[c];
    const std::string path = "/cables/" + std::to_string(c);
    CableDef def;
    def.name = cable.at("name").get<std::string>();
    if (!cable_names.insert(def.name).second)
      throw SceneError(source, path + "/name", "a cable name not already used", quote(def.name));

    const nlohmann::json& links = cable.at("links");
    for (std::size_t k = 0; k < links.size(); ++k)
      def.links.push_back(
          linkOf(links[k], path + "/links/" + std::to_string(k), names, world, source));
    for (const std::size_t end : {std::size_t{0}, links.size() - 1})
      if (links[end].at("type") != "attachment")
        throw SceneError(source, path + "/links/" + std::to_string(end) + "/type",
                         "\"attachment\" (a cable starts and ends at an attachment)",
                         literal(links[end].at("type")));

    if (const auto rest = cable.find("rest_length_m"); rest != cable.end()) {
      const std::size_t joints = links.size() - 1;
      if (rest->size() != joints)
        throw SceneError(source, path + "/rest_length_m",
                         "an array of " + std::to_string(joints) +
                             " numbers (one rest length per cable joint: links - 1)",
                         describe(*rest));
      def.rest_lengths = rest->get<std::vector<double>>();
    }
    def.compliance = cable.value("compliance_m_per_N", 0.0);

    try {
      system.addCable(def);
    } catch (const std::invalid_argument& e) {
      throw SceneError(source, path, "a cable the solver can build", e.what());
    }
  }
}

}  // namespace reeve::scene_detail
