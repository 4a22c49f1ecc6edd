#include "reeve/engine/shape.h"

#include <numbers>

namespace reeve {

Shape Shape::box(const Vec3& half_extents) {
  Shape s;
  s.type = Type::Box;
  s.half_extents = half_extents;
  return s;
}

Shape Shape::cylinder(double radius, double half_length) {
  Shape s;
  s.type = Type::Cylinder;
  s.radius = radius;
  s.half_length = half_length;
  return s;
}

Shape Shape::sphere(double radius) {
  Shape s;
  s.type = Type::Sphere;
  s.radius = radius;
  return s;
}

Shape Shape::convexHull(const std::vector<Vec3>& points, bool keep_frame) {
  Shape s;
  s.type = Type::Hull;
  s.hull = makeConvexHull(points, keep_frame);
  return s;
}

double volume(const Shape& s) {
  using std::numbers::pi;
  switch (s.type) {
    case Shape::Type::Box: return 8.0 * s.half_extents.prod();
    case Shape::Type::Cylinder: return pi * s.radius * s.radius * 2.0 * s.half_length;
    case Shape::Type::Sphere: return 4.0 / 3.0 * pi * s.radius * s.radius * s.radius;
    case Shape::Type::Hull: return s.hull->volume;
  }
  return 0.0;
}

Mat3 inertiaTensor(const Shape& s, double m) {
  switch (s.type) {
    case Shape::Type::Box: {
      const Vec3 e2 = s.half_extents.cwiseProduct(s.half_extents);
      return (m / 3.0 * Vec3(e2.y() + e2.z(), e2.x() + e2.z(), e2.x() + e2.y())).asDiagonal();
    }
    case Shape::Type::Cylinder: {
      const double r2 = s.radius * s.radius;
      const double l = 2.0 * s.half_length;
      const double side = m * (3.0 * r2 + l * l) / 12.0;
      return Vec3(side, side, 0.5 * m * r2).asDiagonal();
    }
    case Shape::Type::Sphere: return Mat3::Identity() * (0.4 * m * s.radius * s.radius);
    case Shape::Type::Hull: return m * s.hull->inertia_per_mass;
  }
  return Mat3::Zero();
}

}  // namespace reeve
