#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>

#include "build.h"
#include "describe.h"

namespace reeve::scene_detail {
namespace {

// The "section" object of a rolling or hybrid link at `path`: {radius_m,
// centre_m} or {polygon_m} (schema-checked), the polygon's convex hull
// taken.
Section sectionOf(const nlohmann::json& section, const std::string& path,
                  const std::string& source) {
  if (const auto radius = section.find("radius_m"); radius != section.end()) {
    Vec2 centre = Vec2::Zero();
    if (const auto c = section.find("centre_m"); c != section.end()) {
      centre = Vec2(c->at(0).get<double>(), c->at(1).get<double>());
      if (!centre.allFinite()) throw SceneError(source, path + "/centre_m", "a finite [x, y]", literal(*c));
    }
    try {
      return Section::circle(radius->get<double>(), centre);
    } catch (const std::invalid_argument&) {
      throw SceneError(source, path + "/radius_m", "a finite radius > 0", literal(*radius));
    }
  }
  const nlohmann::json& polygon = section.at("polygon_m");
  std::vector<Vec2> points;
  for (const nlohmann::json& p : polygon)
    points.emplace_back(p.at(0).get<double>(), p.at(1).get<double>());
  try {
    return Section::polygon(std::move(points));
  } catch (const std::invalid_argument&) {
    throw SceneError(source, path + "/polygon_m", "a polygon with non-zero area",
                     literal(polygon) + " (its convex hull has zero area: the points lie on one line)");
  }
}

LinkType linkTypeOf(const nlohmann::json& type) {
  if (type == "rolling") return LinkType::Rolling;
  if (type == "pinhole") return LinkType::Pinhole;
  if (type == "hybrid") return LinkType::Hybrid;
  return LinkType::Attachment;
}

// Body-local coordinates in the scene are relative to `origin` (m, see
// hullOrigin), the engine's to the body's centre of mass.
LinkDef linkOf(const nlohmann::json& link, const std::string& path, const BodyNames& names,
               const World& world, const std::string& source) {
  LinkDef def;
  def.body = names.find(link.at("body"), path + "/body", source, false);
  def.type = linkTypeOf(link.at("type"));
  const Vec3 origin = hullOrigin(world.bodyDef(def.body).shape);
  if (const auto mu = link.find("mu"); mu != link.end()) def.mu = mu->get<double>();
  if (def.type == LinkType::Attachment || def.type == LinkType::Pinhole) {
    def.point = vec3(link.at("point_m")) - origin;
    return def;
  }
  // Rolling and hybrid links. Without "section" CableSystem::addCable takes
  // the body shape's own cut by the cable plane.
  def.orientation = link.at("orientation") == "ccw" ? 1 : -1;
  if (const auto stored = link.find("stored_m"); stored != link.end())
    def.stored = stored->get<double>();
  if (const auto section = link.find("section"); section != link.end()) {
    def.section = sectionOf(*section, path + "/section", source);
    for (Vec2& p : def.section.vertices) p -= origin.head<2>();
    if (def.section.kind == Section::Kind::Circle) def.section.centre -= origin.head<2>();
  }
  def.plane_offset = link.value("plane_offset_m", 0.0) - origin.z();
  def.active = link.value("active", true);
  return def;
}

// Where link k of a cable of n links may be what it is: no pinhole ends of
// open cables, hybrid links only there, ends active, no stored cable on a
// link the cable does not touch yet.
void checkLinkPlace(const nlohmann::json& link, const LinkDef& def, std::size_t k, std::size_t n,
                    bool closed, const std::string& path, const std::string& source) {
  const bool end = !closed && (k == 0 || k + 1 == n);
  const std::string which = k == 0 ? "first" : "last";
  if (def.type == LinkType::Pinhole && end)
    throw SceneError(source, path + "/type",
                     "\"attachment\", \"rolling\" or \"hybrid\" as the " + which +
                         " link of an open cable (a cable slides through a pinhole, so a pinhole "
                         "cannot end it)",
                     literal(link.at("type")));
  if (def.type == LinkType::Hybrid && !end)
    throw SceneError(source, path + "/type",
                     closed ? std::string("\"attachment\", \"rolling\" or \"pinhole\" in a closed "
                                          "cable (hybrid links are spool ends of open cables)")
                            : std::string("\"attachment\", \"rolling\" or \"pinhole\" for an "
                                          "interior link (hybrid links are only the first or "
                                          "last link of an open cable)"),
                     literal(link.at("type")));
  if (def.mu && end)
    throw SceneError(source, path + "/mu",
                     "no mu on the " + which +
                         " link of an open cable (the cable is fixed to its end; friction acts where "
                         "it can slide: interior rolling links and pinholes)",
                     literal(link.at("mu")));
  if (!def.active && end)
    throw SceneError(source, path + "/active",
                     "true for the " + which +
                         " link of an open cable (only interior rolling links can start inactive)",
                     "false");
  if (!def.active && link.contains("stored_m"))
    throw SceneError(source, path + "/stored_m",
                     "no stored_m on an inactive link (the cable does not touch it yet; it is "
                     "split in with the arc it then wraps)",
                     literal(link.at("stored_m")));
}

// The "winch" object of the cable at `path` (schema-checked), for a cable
// built from `links`: an open cable whose winch end is an attachment,
// commands in order of time, each with exactly one mode, speeds within
// the maximum.
WinchDef winchOf(const nlohmann::json& winch, const nlohmann::json& links, bool closed,
                 const std::string& path, const std::string& source) {
  const std::string at = path + "/winch";
  if (closed)
    throw SceneError(source, at, "no winch on a closed cable (a winch reels an end of an open cable)",
                     "a winch on a closed cable");
  WinchDef def;
  def.at_start = winch.at("end") == "first";
  const std::size_t k = def.at_start ? 0 : links.size() - 1;
  if (links[k].at("type") != "attachment")
    throw SceneError(source, path + "/links/" + std::to_string(k) + "/type",
                     "\"attachment\" for the winch's end link (the drum it reels the cable onto)",
                     literal(links[k].at("type")));
  def.max_speed = winch.value("max_speed_m_per_s", def.max_speed);
  def.max_pull = winch.value("max_pull_N", def.max_pull);
  const nlohmann::json& commands = winch.at("commands");
  for (std::size_t i = 0; i < commands.size(); ++i) {
    const nlohmann::json& command = commands[i];
    const std::string cp = at + "/commands/" + std::to_string(i);
    WinchCommand c;
    c.from_s = command.at("from_s").get<double>();
    if (i > 0 && !(c.from_s > def.schedule.back().from_s))
      throw SceneError(source, cp + "/from_s",
                       "a time after the command before's (" + number(def.schedule.back().from_s) + " s)",
                       literal(command.at("from_s")));
    const bool speed = command.contains("speed_m_per_s"), stored = command.contains("stored_m");
    if (speed == stored)
      throw SceneError(source, cp, "exactly one of \"speed_m_per_s\" (speed mode) and \"stored_m\" (length mode)",
                       speed ? "both" : "neither");
    if (speed) {
      c.speed = command.at("speed_m_per_s").get<double>();
      if (std::abs(c.speed) > def.max_speed)
        throw SceneError(source, cp + "/speed_m_per_s",
                         "a speed within max_speed_m_per_s (" + number(def.max_speed) + ")",
                         literal(command.at("speed_m_per_s")));
    } else {
      c.target_stored = command.at("stored_m").get<double>();
    }
    def.schedule.push_back(c);
  }
  return def;
}

}  // namespace

void addCables(const nlohmann::json& cables, const BodyNames& names, CableSystem& system,
               const std::string& source) {
  std::set<std::string> cable_names;
  for (std::size_t c = 0; c < cables.size(); ++c) {
    const nlohmann::json& cable = cables[c];
    const std::string path = "/cables/" + std::to_string(c);
    CableDef def;
    def.name = cable.at("name").get<std::string>();
    if (!cable_names.insert(def.name).second)
      throw SceneError(source, path + "/name", "a cable name not already used", quote(def.name));
    def.closed = cable.value("closed", false);

    const nlohmann::json& links = cable.at("links");
    for (std::size_t k = 0; k < links.size(); ++k) {
      const std::string link_path = path + "/links/" + std::to_string(k);
      def.links.push_back(linkOf(links[k], link_path, names, system.world(), source));
      checkLinkPlace(links[k], def.links.back(), k, links.size(), def.closed, link_path, source);
    }
    bool only_pinholes = true;
    for (const LinkDef& link : def.links) only_pinholes &= link.type == LinkType::Pinhole;
    if (def.closed && only_pinholes)
      throw SceneError(source, path + "/links",
                       "a link other than a pinhole in a closed cable (attachment or rolling: "
                       "something the cable holds on to)",
                       "only pinhole links (" + std::to_string(links.size()) + ")");

    if (const auto rest = cable.find("rest_length_m"); rest != cable.end()) {
      const std::size_t joints = def.closed ? links.size() : links.size() - 1;
      if (rest->size() != joints)
        throw SceneError(source, path + "/rest_length_m",
                         "an array of " + std::to_string(joints) +
                             " numbers (one rest length per cable joint: " +
                             (def.closed ? "links, for a closed cable)"
                                         : "links - 1, for an open cable)"),
                         describe(*rest));
      def.rest_lengths = rest->get<std::vector<double>>();
      for (std::size_t j = 0; j < joints; ++j)
        if (!def.links[j].active && def.rest_lengths[j] != 0.0)
          throw SceneError(source, path + "/rest_length_m/" + std::to_string(j),
                           "0 for the joint leaving inactive link " + std::to_string(j) +
                               " (it has no span until the link is split in)",
                           literal(rest->at(j)));
    }
    def.compliance = cable.value("compliance_m_per_N", 0.0);
    if (const auto damping = cable.find("damping_N_s_per_m"); damping != cable.end()) {
      def.damping = damping->get<double>();
      if (def.damping > 0.0 && def.compliance == 0.0)
        throw SceneError(source, path + "/damping_N_s_per_m",
                         "no damping without compliance_m_per_N > 0 (a rigid cable does not stretch)",
                         literal(*damping));
    }
    def.breaking_tension = cable.value("breaking_tension_N", def.breaking_tension);
    std::optional<WinchDef> winch;
    if (const auto w = cable.find("winch"); w != cable.end())
      winch = winchOf(*w, links, def.closed, path, source);

    try {
      const int index = system.addCable(def);
      if (winch) system.setWinch(index, *winch);
    } catch (const std::invalid_argument& e) {
      throw SceneError(source, path, "a cable the solver can build", e.what());
    }
  }
}

void addJunctions(const nlohmann::json& junctions, CableSystem& system, const std::string& source) {
  std::set<std::string> names;
  std::map<int, std::string> joined;  // cable -> the path of the branch that took it
  for (std::size_t i = 0; i < junctions.size(); ++i) {
    const nlohmann::json& junction = junctions[i];
    const std::string path = "/junctions/" + std::to_string(i);
    JunctionDef def;
    def.name = junction.at("name").get<std::string>();
    if (!names.insert(def.name).second)
      throw SceneError(source, path + "/name", "a junction name not already used", quote(def.name));
    const nlohmann::json& branches = junction.at("branches");
    for (std::size_t b = 0; b < branches.size(); ++b) {
      const std::string branch_path = path + "/branches/" + std::to_string(b);
      const std::string name = branches[b].at("cable").get<std::string>();
      int found = -1;
      for (std::size_t c = 0; c < system.cables().size(); ++c)
        if (system.cables()[c].name == name) found = static_cast<int>(c);
      if (found < 0) throw SceneError(source, branch_path + "/cable", "the name of a cable", quote(name));
      if (const auto [at, fresh] = joined.emplace(found, branch_path); !fresh)
        throw SceneError(source, branch_path + "/cable", "a cable in no other branch",
                         quote(name) + " (already at " + at->second + ")");
      def.cables.push_back(found);
      def.divisors.push_back(branches[b].value("divisor", 1.0));
      if (const std::string problem = system.branchProblem(found); !problem.empty())
        throw SceneError(source, branch_path + "/cable", "a cable that can be a junction's branch",
                         quote(name) + ", which " + problem);
    }
    try {
      system.addJunction(def);
    } catch (const std::invalid_argument& e) {
      throw SceneError(source, path, "a junction the solver can build", e.what());
    }
  }
}

}  // namespace reeve::scene_detail
