#include "reeve/render/cable_path.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace reeve {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

// Appends the arc of rolling `link` from body-local `arrival` to
// `departure` (both in the local z = 0 plane), endpoints excluded.
void appendArc(std::vector<Vec3>& path, const Link& link, const BodyState& body,
               const Vec3& arrival, const Vec3& departure, double max_step_rad) {
  const Vec2 a(arrival.x(), arrival.y()), d(departure.x(), departure.y());
  // wrappedArc is in [0, 2 pi r); the stored cable adds whole turns, and
  // settles the 0-or-a-full-turn ambiguity of coincident points.
  const double arc = wrappedArc(a, d, link.radius, link.orientation);
  const double turns = std::round((link.stored - arc) / (kTwoPi * link.radius));
  const double sweep = std::max(0.0, arc / link.radius + turns * kTwoPi);
  const int steps = static_cast<int>(std::ceil(sweep / max_step_rad));
  const double start = std::atan2(a.y(), a.x());
  for (int i = 1; i < steps; ++i) {
    const double angle = start + link.orientation * sweep * i / steps;
    path.push_back(body.toWorld(
        Vec3(link.radius * std::cos(angle), link.radius * std::sin(angle), 0.0)));
  }
}

}  // namespace

std::vector<Vec3> cablePath(const CableSystem& cables, int c, double max_step_rad) {
  const Cable& cable = cables.cables()[c];
  const World& world = cables.world();
  std::vector<Vec3> path;
  for (int j = 0; j < static_cast<int>(cable.joints.size()); ++j) {
    const Link& link = cable.links[j];
    if (j > 0 && link.type == LinkType::Rolling) {
      const BodyState& body = world.body(link.body);
      appendArc(path, link, body, body.toLocal(cables.endPoint(c, j - 1)),
                body.toLocal(cables.startPoint(c, j)), max_step_rad);
    }
    path.push_back(cables.startPoint(c, j));
    path.push_back(cables.endPoint(c, j));
  }
  return path;
}

}  // namespace reeve
