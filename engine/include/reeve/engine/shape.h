// Body shapes: their geometry, volume and inertia. All lengths in m.
#pragma once

#include <memory>
#include <vector>

#include "reeve/engine/convex_hull.h"
#include "reeve/engine/math.h"

namespace reeve {

/// A body's shape in its local frame, centred on the body origin.
/// Box: `half_extents` (m). Cylinder: `radius` and `half_length` (m), axis
/// along local +z. Sphere: `radius` (m). Hull: the convex polyhedron
/// `hull`, whose centre of mass is the origin.
struct Shape {
  enum class Type { Box, Cylinder, Sphere, Hull };
  Type type = Type::Box;
  Vec3 half_extents = Vec3(0.5, 0.5, 0.5);
  double radius = 0.5;
  double half_length = 0.5;
  std::shared_ptr<const ConvexHull> hull;

  static Shape box(const Vec3& half_extents);
  static Shape cylinder(double radius, double half_length);
  static Shape sphere(double radius);
  /// The convex hull of `points` (m), moved so that its centre of mass is
  /// the origin (hull->input_centre_of_mass says by how much), or with
  /// `keep_frame` about the origin of the points (for a body whose centre
  /// of mass is given apart: BodyDef::inertia). Throws as makeConvexHull.
  static Shape convexHull(const std::vector<Vec3>& points, bool keep_frame = false);
};

/// Volume in m^3.
double volume(const Shape& shape);

/// Inertia tensor (kg m^2) of a solid of uniform density and total `mass`
/// (kg) about the origin (its centre of mass but for a hull built with
/// keep_frame), in local axes: diagonal for a box, cylinder or sphere, full
/// for a hull.
Mat3 inertiaTensor(const Shape& shape, double mass);

}  // namespace reeve
