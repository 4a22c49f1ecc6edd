// Convex polyhedra for hull shapes: faces from qhull, mass properties from
// a tetrahedral decomposition. All lengths in m.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "reeve/engine/math.h"

namespace reeve {

/// A convex polyhedron about its body's origin: its own centre of mass
/// (uniform density), or, built with keep_frame, the frame its points were
/// given in (a body whose mass properties are given apart: BodyDef::inertia).
/// Immutable once built; shapes share it.
struct ConvexHull {
  /// A planar face: indices into `vertices`, counter-clockwise seen from
  /// outside, and its outward unit normal. Coplanar triangles are merged.
  struct Face {
    std::vector<int> vertices;
    Vec3 normal;
  };
  std::vector<Vec3> vertices;  ///< the hull's corners, m, relative to the origin
  std::vector<Face> faces;
  double volume = 0.0;         ///< m^3
  double bounding_radius = 0.0;  ///< m, the farthest vertex from the origin
  /// Inertia tensor about the origin per unit mass (m^2), in the axes the
  /// points were given in.
  Mat3 inertia_per_mass = Mat3::Zero();
  /// How far the origin was moved from the frame the points were given in
  /// (m): vertices = (corners of the given points) - input_centre_of_mass;
  /// the centre of mass, or 0 with keep_frame.
  Vec3 input_centre_of_mass = Vec3::Zero();
};

/// The convex hull of `points` (m, any frame, at least 4), moved so that
/// its centre of mass is the origin, or with `keep_frame` left where the
/// points are; points inside the hull are dropped. Throws
/// std::invalid_argument when a point is not finite, there are fewer than
/// 4 points, or they span no volume (all on a plane or a line).
std::shared_ptr<const ConvexHull> makeConvexHull(const std::vector<Vec3>& points, bool keep_frame = false);

/// The hull's cross-section with the local plane z = `z` (m): the
/// intersection points of its edges with the plane, unordered and possibly
/// repeated (Section::polygon takes their hull). Empty when the plane
/// misses the hull's interior.
std::vector<Vec2> planeSection(const ConvexHull& hull, double z);
/// planeSection() into `points` (cleared first): no heap once it holds a
/// point per face edge.
void planeSection(const ConvexHull& hull, double z, std::vector<Vec2>& points);

/// The hull's point nearest to the point `p` (both m, hull-local): on a
/// face, an edge or a corner. nullopt where p lies in the hull or on its
/// surface. Linear in the faces' corners.
std::optional<Vec3> nearestHullPoint(const ConvexHull& hull, const Vec3& p);

}  // namespace reeve
