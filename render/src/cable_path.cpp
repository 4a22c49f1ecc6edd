#include "reeve/render/cable_path.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "reeve/render/slack_curve.h"

namespace reeve {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kDuplicateM = 1e-12;  // points this close to the last are dropped

Vec2 inPlane(const BodyState& body, const Vec3& world) {
  const Vec3 local = body.toLocal(world);
  return Vec2(local.x(), local.y());
}

Vec3 toWorld(const Link& link, const BodyState& body, const Vec2& p) {
  return body.toWorld(Vec3(p.x(), p.y(), link.plane_offset));
}

void push(std::vector<Vec3>& path, const Vec3& p) {
  if (path.empty() || (p - path.back()).norm() > kDuplicateM) path.push_back(p);
}

// Appends the points of `more` after its first (which repeats the last of `points`).
void appendTail(std::vector<Vec2>& points, const std::vector<Vec2>& more) {
  points.insert(points.end(), more.begin() + 1, more.end());
}

// Outward unit normal of polygon edge i (from vertex i to i + 1), and its angle.
Vec2 edgeNormal(const std::vector<Vec2>& v, int i) {
  const int n = static_cast<int>(v.size());
  const Vec2 e = v[(i + 1) % n] - v[i];
  return Vec2(e.y(), -e.x()).normalized();  // counter-clockwise polygon: right of the edge
}

double angleOf(const Vec2& u) { return std::atan2(u.y(), u.x()); }

Vec2 direction(double angle) { return Vec2(std::cos(angle), std::sin(angle)); }

// Distance (m) from the vertices' mean, inside a convex polygon, to its
// nearest edge; a circle's radius.
double inradius(const Section& s) {
  if (s.kind == Section::Kind::Circle) return s.radius;
  Vec2 c = Vec2::Zero();
  for (const Vec2& v : s.vertices) c += v / double(s.vertices.size());
  double r = std::numeric_limits<double>::infinity();
  for (int i = 0; i < static_cast<int>(s.vertices.size()); ++i)
    r = std::min(r, edgeNormal(s.vertices, i).dot(s.vertices[i] - c));
  return r;
}

// A spiral from the boundary point `start` winding `turns` turns in the
// sense `sense` (+1 counter-clockwise), `pitch` (m) further out each turn:
// the section's boundary offset outward by the distance reached so far,
// measured by the angle the boundary's normal has turned. On a polygon
// the offset curve runs parallel to each edge and round each vertex.
std::vector<Vec2> coilPoints(const Section& s, const Vec2& start, int sense, double turns,
                             double pitch, double max_step_rad) {
  const double total = kTwoPi * turns;
  const auto offset = [&](double turned) { return pitch * turned / kTwoPi; };
  std::vector<Vec2> points{start};
  if (s.kind == Section::Kind::Circle) {
    const double start_angle = angleOf(start - s.centre);
    const int steps = std::max(1, static_cast<int>(std::ceil(total / max_step_rad)));
    for (int i = 1; i <= steps; ++i) {
      const double turned = total * i / steps;
      points.push_back(s.centre + (s.radius + offset(turned)) * direction(start_angle + sense * turned));
    }
    return points;
  }
  const std::vector<Vec2>& v = s.vertices;
  const int n = static_cast<int>(v.size());
  int vertex = 0;  // tangent points on polygons are hull vertices: start at the nearest
  for (int i = 1; i < n; ++i)
    if ((v[i] - start).squaredNorm() < (v[vertex] - start).squaredNorm()) vertex = i;
  // The edges before and after vertex i in the sense of travel.
  const auto edgeIn = [&](int i) { return sense > 0 ? (i + n - 1) % n : i; };
  const auto edgeOut = [&](int i) { return sense > 0 ? i : (i + n - 1) % n; };
  double turned = 0.0;
  for (;;) {
    // Round vertex `vertex`, from the normal of the edge in to that of the edge out.
    const double from = angleOf(edgeNormal(v, edgeIn(vertex)));
    double sweep = sense * (angleOf(edgeNormal(v, edgeOut(vertex))) - from);
    sweep -= kTwoPi * std::floor(sweep / kTwoPi);
    const int steps = std::max(1, static_cast<int>(std::ceil(sweep / max_step_rad)));
    for (int i = 1; i <= steps; ++i) {
      const double t = std::min(turned + sweep * i / steps, total);
      points.push_back(v[vertex] + offset(t) * direction(from + sense * (t - turned)));
      if (t >= total) return points;
    }
    turned += sweep;
    // Along the edge out, at the offset reached.
    const int next = (vertex + sense + n) % n;
    points.push_back(v[next] + offset(turned) * edgeNormal(v, edgeOut(vertex)));
    vertex = next;
  }
}

}  // namespace

int arrivingJoint(const CableSystem& cables, int c, int k) {
  const Cable& cable = cables.cables()[c];
  for (int j = 0; j < static_cast<int>(cable.joints.size()); ++j)
    if (cable.joints[j].to == k && cables.jointEnabled(c, j)) return j;
  return -1;
}

int extraTurns(const Link& link, const BodyState& body, const Vec3& arrival,
               const Vec3& departure) {
  const double wrap = sectionWrappedArc(link.section, inPlane(body, arrival),
                                        inPlane(body, departure), link.orientation);
  return static_cast<int>(std::lround((link.arc() - wrap) / link.section.perimeter()));
}

std::vector<Vec3> wrapPath(const Link& link, const BodyState& body, const Vec3& arrival,
                           const Vec3& departure, int extra_turns, double max_step_rad) {
  const Section& s = link.section;
  const Vec2 a = inPlane(body, arrival), d = inPlane(body, departure);
  std::vector<Vec2> points = sectionArcPoints(s, a, d, link.orientation, max_step_rad);
  if (extra_turns > 0) {
    // A whole turn from d back to d, through the boundary point farthest round.
    Vec2 far = s.centre - s.radius * (d - s.centre).normalized();
    if (s.kind == Section::Kind::Polygon)
      far = *std::max_element(s.vertices.begin(), s.vertices.end(),
                              [&](const Vec2& p, const Vec2& q) {
                                return (p - d).squaredNorm() < (q - d).squaredNorm();
                              });
    for (int turn = 0; turn < extra_turns; ++turn) {
      appendTail(points, sectionArcPoints(s, d, far, link.orientation, max_step_rad));
      appendTail(points, sectionArcPoints(s, far, d, link.orientation, max_step_rad));
    }
  }
  std::vector<Vec3> world;
  world.reserve(points.size());
  for (const Vec2& p : points) world.push_back(toWorld(link, body, p));
  return world;
}

std::vector<std::vector<Vec3>> cablePaths(const CableSystem& cables, int c, double max_step_rad) {
  const Cable& cable = cables.cables()[c];
  const World& world = cables.world();
  Vec3 down = world.settings().gravity;
  if (!(down.allFinite() && down.norm() > 0.0)) down = -Vec3::UnitY();
  down.normalize();
  const int joints = static_cast<int>(cable.joints.size());
  // A closed cable starts at an active link, so that the wrap on it comes
  // first and the loop ends where it began.
  int first = 0;
  if (cable.closed)
    while (first + 1 < joints && !cables.jointEnabled(c, first)) ++first;
  // arriving[k]: the enabled joint whose span ends at link k, or -1.
  std::vector<int> arriving(cable.links.size(), -1);
  for (int j = 0; j < joints; ++j)
    if (cables.jointEnabled(c, j)) arriving[cable.joints[j].to] = j;

  std::vector<std::vector<Vec3>> paths;  // pieces ended and loose ends
  std::vector<Vec3> path;                 // the piece being drawn
  const auto hang = [&](const Vec3& from, double length) {
    if (length > 0.0) paths.push_back({from, from + length * down});
  };
  for (int step = 0; step < joints; ++step) {
    const int j = (first + step) % joints;
    const Link& link = cable.links[j];
    const CableJoint& joint = cable.joints[j];
    if (!link.active) continue;
    if (!joint.parted && !cables.jointEnabled(c, j)) continue;
    const Vec3 start = cables.startPoint(c, j), end = cables.endPoint(c, j);
    const int in = link.rolls() ? arriving[j] : -1;
    if (in >= 0) {
      const BodyState& body = world.body(link.body);
      const Vec3 arrival = cables.endPoint(c, in);
      const int turns = extraTurns(link, body, arrival, start);
      push(path, arrival);
      if (turns >= 0) {
        const auto wrap = wrapPath(link, body, arrival, start, turns, max_step_rad);
        for (std::size_t i = 1; i + 1 < wrap.size(); ++i) push(path, wrap[i]);
      }
    }
    push(path, start);
    if (joint.parted) {  // a piece ends here; the next starts after the gap
      paths.push_back(std::move(path));
      path.clear();
      hang(start, joint.tail_a);
      hang(end, joint.tail_b);
      continue;
    }
    const double rest = cables.restLength(c, j), chord = (end - start).norm();
    if (isSlack(rest, chord)) {
      const auto curve = slackCurve(start, end, rest, down, kSlackSegments);
      for (std::size_t i = 1; i + 1 < curve.size(); ++i) push(path, curve[i]);
    }
    push(path, end);
  }
  paths.push_back(std::move(path));
  paths.erase(std::remove_if(paths.begin(), paths.end(), [](const auto& p) { return p.size() < 2; }),
              paths.end());
  return paths;
}

std::vector<Vec3> spoolCoil(const CableSystem& cables, int c, int k, double pitch,
                            double max_step_rad, double min_full_band) {
  const Cable& cable = cables.cables()[c];
  const int last = static_cast<int>(cable.links.size()) - 1;
  if (cable.closed || (k != 0 && k != last)) return {};
  const Link& link = cable.links[k];
  if (!link.active || !link.rolls() || !(link.stored > 0.0)) return {};
  const int joint = k == 0 ? 0 : arrivingJoint(cables, c, k);
  if (joint < 0 || !cables.jointEnabled(c, joint)) return {};
  const BodyState& body = cables.world().body(link.body);
  const Vec3 tangent = k == 0 ? cables.startPoint(c, joint) : cables.endPoint(c, joint);
  const Section& s = link.section;
  const double turns = std::min(link.arc() / s.perimeter(), double(kMaxCoilTurns));
  // A spacing that does not depend on the turns, so the coil's thickness
  // follows the stored cable all the way down.
  const double spacing = std::min(pitch, std::max(inradius(s), min_full_band) / kMaxCoilTurns);
  // The cable on the spool continues the span backwards from the first
  // link, forwards into the last.
  const int sense = k == 0 ? -link.orientation : link.orientation;
  const auto points =
      coilPoints(s, inPlane(body, tangent), sense, turns, spacing, max_step_rad);
  std::vector<Vec3> world;
  world.reserve(points.size());
  world.push_back(tangent);
  for (std::size_t i = 1; i < points.size(); ++i) world.push_back(toWorld(link, body, points[i]));
  return world;
}

std::vector<Vec3> sectionOutline(const Link& link, const BodyState& body, double max_step_rad) {
  const Section& s = link.section;
  std::vector<Vec3> outline;
  if (s.kind == Section::Kind::Circle) {
    const int steps = std::max(3, static_cast<int>(std::ceil(kTwoPi / max_step_rad)));
    for (int i = 0; i <= steps; ++i)
      outline.push_back(toWorld(link, body, s.centre + s.radius * direction(kTwoPi * (i % steps) / steps)));
  } else {
    for (const Vec2& p : s.vertices) outline.push_back(toWorld(link, body, p));
    outline.push_back(outline.front());
  }
  return outline;
}

bool sectionMatchesShape(const Link& link, const Shape& shape) {
  if (link.type != LinkType::Rolling && link.type != LinkType::Hybrid) return false;
  const Section& s = link.section;
  const double z = std::abs(link.plane_offset);
  const auto near = [](double a, double b) {
    return std::abs(a - b) <= 1e-9 * std::max(std::abs(a), std::abs(b));
  };
  switch (shape.type) {
    case Shape::Type::Cylinder:
      return s.kind == Section::Kind::Circle && s.centre.isZero() && near(s.radius, shape.radius) &&
             z <= shape.half_length * (1.0 + 1e-9);
    case Shape::Type::Sphere:
      return s.kind == Section::Kind::Circle && s.centre.isZero() && z < shape.radius &&
             near(s.radius, std::sqrt(shape.radius * shape.radius - z * z));
    case Shape::Type::Box: {
      const double hx = shape.half_extents.x(), hy = shape.half_extents.y();
      if (s.kind != Section::Kind::Polygon || s.vertices.size() != 4 ||
          z > shape.half_extents.z() * (1.0 + 1e-9))
        return false;
      for (const Vec2& p : s.vertices)
        if (!near(std::abs(p.x()), hx) || !near(std::abs(p.y()), hy)) return false;
      // Four hull vertices at (+-hx, +-hy) are the four corners.
      return true;
    }
    case Shape::Type::Hull: {
      std::vector<Vec2> points = planeSection(*shape.hull, link.plane_offset);
      if (s.kind != Section::Kind::Polygon || points.empty()) return false;
      const std::vector<Vec2> own = Section::polygon(std::move(points)).vertices;
      if (own.size() != s.vertices.size()) return false;
      for (std::size_t i = 0; i < own.size(); ++i)
        if (!near(own[i].x(), s.vertices[i].x()) || !near(own[i].y(), s.vertices[i].y()))
          return false;
      return true;
    }
  }
  return false;
}

}  // namespace reeve
