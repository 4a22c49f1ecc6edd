// Sections: construction (convex hull), area moments and distances along
// the boundary (paper sec. 3.2 and 3.4, Alg. 1 surfaceDist, Alg. 2 line 2).
// Tangents are in section_tangent.cpp.
#include "reeve/cable/section.h"

#include "reeve/engine/math.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <utility>

namespace reeve {
namespace {

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// `length` reduced into [0, period).
double wrapPositive(double length, double period) {
  double r = std::fmod(length, period);
  if (r < 0.0) r += period;
  return r < period ? r : 0.0;  // a tiny negative r rounds up to period
}

}  // namespace

Section Section::circle(double radius, const Vec2& centre) {
  if (!(radius > 0.0 && std::isfinite(radius)))
    throw std::invalid_argument("circle section: radius must be > 0 and finite");
  if (!centre.allFinite()) throw std::invalid_argument("circle section: the centre is not finite");
  Section s;
  s.radius = radius;
  s.centre = centre;
  return s;
}

Section Section::polygon(std::vector<Vec2> points) {
  for (const Vec2& p : points)
    if (!std::isfinite(p.x()) || !std::isfinite(p.y()))
      throw std::invalid_argument("polygon section: a point is not finite");
  Section s;
  if (!s.setPolygon(points)) throw std::invalid_argument("polygon section: the convex hull has zero area");
  return s;
}

bool Section::setPolygon(std::vector<Vec2>& points) {
  for (const Vec2& p : points)
    if (!std::isfinite(p.x()) || !std::isfinite(p.y())) return false;
  std::sort(points.begin(), points.end(), [](const Vec2& a, const Vec2& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3) return false;
  // Andrew's monotone chain: lower hull left to right, upper hull back.
  // `push` pops while the stack holds at least `keep` points (two make a
  // turn; the upper hull never pops the lower one); popping on cross <= 0
  // drops collinear points.
  const std::size_t n = points.size();
  std::vector<Vec2>& hull = vertices;
  hull.resize(2 * n);
  std::size_t k = 0;
  const auto push = [&](const Vec2& p, std::size_t keep) {
    while (k >= keep && cross(hull[k - 1] - hull[k - 2], p - hull[k - 2]) <= 0.0) --k;
    hull[k++] = p;
  };
  for (std::size_t i = 0; i < n; ++i) push(points[i], 2);
  for (std::size_t i = n - 1, lower = k + 1; i-- > 0;) push(points[i], lower);
  hull.resize(k - 1);  // the last point repeats the first
  kind = Kind::Polygon;
  radius = 0.0;
  centre.setZero();
  return hull.size() >= 3;
}

Section boxSection(double hx, double hy) {
  if (!(hx > 0.0 && hy > 0.0 && std::isfinite(hx) && std::isfinite(hy)))
    throw std::invalid_argument("box section: half extents must be > 0 and finite");
  return Section::polygon({Vec2(-hx, -hy), Vec2(hx, -hy), Vec2(hx, hy), Vec2(-hx, hy)});
}

double Section::perimeter() const {
  if (kind == Kind::Circle) return 2.0 * std::numbers::pi * radius;
  double length = 0.0;
  for (std::size_t i = 0; i < vertices.size(); ++i)
    length += (vertices[(i + 1) % vertices.size()] - vertices[i]).norm();
  return length;
}

double boundaryPosition(const Section& section, const Vec2& p) {
  if (section.kind == Section::Kind::Circle) {
    const Vec2 r = p - section.centre;
    return wrapPositive(section.radius * std::atan2(r.y(), r.x()), section.perimeter());
  }
  // Nearest point edge by edge; `along` is the position of edge i's start.
  const std::vector<Vec2>& v = section.vertices;
  double along = 0.0, best = 0.0, best_d2 = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Vec2 edge = v[(i + 1) % v.size()] - v[i];
    const double length = edge.norm();
    const double t = std::clamp((p - v[i]).dot(edge) / (length * length), 0.0, 1.0);
    const double d2 = (v[i] + t * edge - p).squaredNorm();
    if (d2 < best_d2) {
      best_d2 = d2;
      best = along + t * length;
    }
    along += length;
  }
  return wrapPositive(best, along);
}

Vec2 boundaryPoint(const Section& section, double position) {
  position = wrapPositive(position, section.perimeter());
  if (section.kind == Section::Kind::Circle) {
    const double angle = position / section.radius;
    return section.centre + section.radius * Vec2(std::cos(angle), std::sin(angle));
  }
  const std::vector<Vec2>& v = section.vertices;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Vec2 edge = v[(i + 1) % v.size()] - v[i];
    const double length = edge.norm();
    if (position <= length) return v[i] + (position / length) * edge;
    position -= length;
  }
  return v.front();
}

double sectionSurfaceDistance(const Section& section, const Vec2& old_point, const Vec2& new_point,
                              int orientation, double turn_rad) {
  const double perimeter = section.perimeter();
  // Counter-clockwise length from new to old, up to whole perimeters: the
  // one nearest what the turn predicts.
  const Vec2 from = new_point - section.centre, to = old_point - section.centre;  // a polygon's centre is 0
  const double ccw = section.kind == Section::Kind::Circle  // one angle: new to old
                         ? section.radius * atan2Small(from.x() * to.y() - from.y() * to.x(), from.dot(to))
                         : boundaryPosition(section, old_point) - boundaryPosition(section, new_point);
  double predicted = section.radius * turn_rad;
  if (section.kind == Section::Kind::Polygon) {
    double shorter = wrapPositive(ccw, perimeter);
    if (shorter > 0.5 * perimeter) shorter -= perimeter;
    predicted = shorter + perimeter * std::round(turn_rad / (2.0 * std::numbers::pi));
  }
  return orientation * (ccw + perimeter * std::round((predicted - ccw) / perimeter));
}

double sectionWrappedArc(const Section& section, const Vec2& arrival, const Vec2& departure,
                         int orientation) {
  return wrapPositive(
      orientation * (boundaryPosition(section, departure) - boundaryPosition(section, arrival)),
      section.perimeter());
}

std::vector<Vec2> sectionArcPoints(const Section& section, const Vec2& arrival,
                                   const Vec2& departure, int orientation, double max_step_rad) {
  if (!(max_step_rad > 0.0))
    throw std::invalid_argument("sectionArcPoints: max_step_rad must be > 0");
  const double arc = sectionWrappedArc(section, arrival, departure, orientation);
  std::vector<Vec2> points{arrival};
  if (section.kind == Section::Kind::Circle) {
    const double angle = arc / section.radius;
    const int steps = std::max(1, static_cast<int>(std::ceil(angle / max_step_rad)));
    const Vec2 r = arrival - section.centre;
    const double start = std::atan2(r.y(), r.x());
    for (int k = 1; k < steps; ++k) {
      const double a = start + orientation * angle * k / steps;
      points.push_back(section.centre + section.radius * Vec2(std::cos(a), std::sin(a)));
    }
  } else {
    // Vertices strictly between the ends, ordered by the length travelled.
    const double perimeter = section.perimeter(), eps = 1e-12 * perimeter;
    const double start = boundaryPosition(section, arrival);
    std::vector<std::pair<double, Vec2>> passed;
    for (const Vec2& vertex : section.vertices) {
      const double travelled =
          wrapPositive(orientation * (boundaryPosition(section, vertex) - start), perimeter);
      if (travelled > eps && travelled < arc - eps) passed.emplace_back(travelled, vertex);
    }
    std::sort(passed.begin(), passed.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    for (const auto& [travelled, vertex] : passed) points.push_back(vertex);
  }
  points.push_back(departure);
  return points;
}

}  // namespace reeve
