#include "build.h"
#include "describe.h"

namespace reeve::scene_detail {

void addHinges(const nlohmann::json& hinges, const BodyNames& names, World& world,
               const std::string& source) {
  for (std::size_t i = 0; i < hinges.size(); ++i) {
    const nlohmann::json& h = hinges[i];
    const std::string path = "/hinges/" + std::to_string(i);
    HingeDef def;
    def.body = names.find(h.at("body"), path + "/body", source, false);
    const nlohmann::json other = h.value("other", nlohmann::json("world"));
    def.other = names.find(other, path + "/other", source, true);
    if (def.other == def.body)
      throw SceneError(source, path + "/other",
                       "\"world\" or a body other than the hinge's body " + literal(h.at("body")),
                       literal(other));
    def.anchor = vec3(h.at("anchor_m"));
    def.axis = vec3(h.at("axis"));
    if (def.axis.squaredNorm() == 0.0)
      throw SceneError(source, path + "/axis", "a non-zero hinge axis", literal(h.at("axis")));
    def.compliance = h.value("compliance", 0.0);
    if (const auto limit = h.find("limit"); limit != h.end())
      def.limit = angleLimit(*limit, path + "/limit", source);
    if (const auto drive = h.find("drive"); drive != h.end())
      def.drive = hingeDrive(*drive, path + "/drive", source);
    world.addHinge(def);
  }
}

}  // namespace reeve::scene_detail
