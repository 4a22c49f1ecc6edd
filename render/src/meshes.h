// Triangle meshes of the unit shapes the renderer scales into bodies.
#pragma once

#include <vector>

#include "reeve/engine/convex_hull.h"
#include "reeve/engine/math.h"

namespace reeve {

/// Triangles, three vertices each, counter-clockwise seen from outside,
/// with unit normals per vertex; packed xyz floats for glDrawArrays.
struct Mesh {
  std::vector<float> positions;
  std::vector<float> normals;

  void addVertex(const Vec3& position, const Vec3& normal);
  int vertexCount() const { return static_cast<int>(positions.size() / 3); }
};

/// A mesh drawn in a body's colour plus an accent part drawn darker, so
/// that a turning round body visibly turns.
struct TwoToneMesh {
  Mesh main, accent;
};

/// The cube [-1, 1]^3 with flat faces.
Mesh unitBox();

/// The faces of `hull` (m, its local frame), flat, each a triangle fan.
Mesh hullMesh(const ConvexHull& hull);

/// Cylinder of radius 1 about local z from z = -1 to 1, sides smooth with
/// `segments` facets, flat caps; accent: two opposite quarters of each cap.
TwoToneMesh unitCylinder(int segments);

/// Sphere of radius 1 in `slices` x `stacks` facets; accent: two opposite
/// quarter lunes about local z.
TwoToneMesh unitSphere(int slices, int stacks);

/// Torus about local z: centre line of radius 1 in the z = 0 plane, tube
/// of radius `tube`, `segments` facets round the axis and `sides` round the
/// tube.
Mesh unitTorus(double tube, int segments, int sides);

/// Appends `unit` moved by `pose` (translation * rotation * scaling):
/// positions transformed, normals by the inverse transpose, renormalized.
void appendTransformed(Mesh& mesh, const Mesh& unit, const Eigen::Affine3d& pose);

/// Appends a tube of `radius` (m) along the polyline `path` with `sides`
/// smooth facets around. Segments meet in mitre joints where the path
/// turns gently; at sharper turns and at both ends a copy of `ball` (a unit
/// sphere) rounds the tube off.
void appendTube(Mesh& mesh, const std::vector<Vec3>& path, double radius, int sides,
                const Mesh& ball);

}  // namespace reeve
