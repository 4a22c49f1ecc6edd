// Body-local geometry of shapes for the narrow phase (collide.cpp): support
// points, supporting faces, face normals and feature points. Every output
// vector is cleared first, so callers can reuse buffers across substeps.
#pragma once

#include <vector>

#include "reeve/engine/shape.h"

namespace reeve {

/// Vertices around each cylinder cap, in its supporting face and features.
inline constexpr int kCapVertices = 16;

/// Farthest point (body-local, m) of the shape along the local direction d.
Vec3 localSupport(const Shape& s, const Vec3& d);

/// The feature of a shape that faces a direction: a convex polygon in
/// cyclic order, a segment or a point (m, body-local), with its outward
/// unit normal.
struct Face {
  std::vector<Vec3> vertices;
  Vec3 normal = Vec3::UnitZ();
};

/// The feature facing the local direction d. Box: the face whose normal is
/// nearest d. Cylinder: the cap when |d_z| >= |d_xy| (a kCapVertices-gon),
/// else the side line under d (2 vertices). Sphere: its support point.
/// Hull: the face whose normal is nearest d.
void supportingFace(const Shape& s, const Vec3& d, Face& out);

/// Outward unit normals (local) of the shape's flat faces: the six box
/// faces, the two cylinder caps, every hull face; none for a sphere.
void faceNormals(const Shape& s, std::vector<Vec3>& out);

/// Points (local) of the shape that can touch a plane whose normal points
/// into the shape along -`toward`: box corners, the point of each cylinder
/// cap rim furthest along `toward` and kCapVertices around each rim, a
/// sphere's support point, every hull vertex.
void featurePoints(const Shape& s, const Vec3& toward, std::vector<Vec3>& out);

}  // namespace reeve
