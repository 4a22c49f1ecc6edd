// Collision-free shape descriptions: they give mass, inertia and, for
// cables, cross-sections. All lengths in m.
#pragma once

#include "reeve/engine/math.h"

namespace reeve {

/// A body's shape in its local frame, centred on the body origin.
/// Box: `half_extents` (m). Cylinder: `radius` and `half_length` (m), axis
/// along local +z. Sphere: `radius` (m).
struct Shape {
  enum class Type { Box, Cylinder, Sphere };
  Type type = Type::Box;
  Vec3 half_extents = Vec3(0.5, 0.5, 0.5);
  double radius = 0.5;
  double half_length = 0.5;

  static Shape box(const Vec3& half_extents);
  static Shape cylinder(double radius, double half_length);
  static Shape sphere(double radius);
};

/// Volume in m^3.
double volume(const Shape& shape);

/// Principal moments of inertia (kg m^2) of a solid of uniform density and
/// total `mass` (kg), about the local axes through the origin.
Vec3 principalInertia(const Shape& shape, double mass);

/// Radius (m) of the circular cross-section in the local z = const plane,
/// or 0 when that section is not a circle (a box). Cables roll on it.
double circularSectionRadius(const Shape& shape);

}  // namespace reeve
