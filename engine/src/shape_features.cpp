#include "shape_features.h"

#include <cmath>
#include <numbers>

namespace reeve {
namespace {

Vec3 capVertex(const Shape& s, int k, double z) {
  const double phi = 2.0 * std::numbers::pi * k / kCapVertices;
  return Vec3(s.radius * std::cos(phi), s.radius * std::sin(phi), z);
}

// A linear scan: hulls in scenes have tens of vertices, where hill climbing
// over neighbours would save little.
int hullSupportIndex(const ConvexHull& hull, const Vec3& d) {
  int best = 0;
  double best_dot = hull.vertices[0].dot(d);
  for (int i = 1; i < static_cast<int>(hull.vertices.size()); ++i)
    if (const double dot = hull.vertices[i].dot(d); dot > best_dot) best = i, best_dot = dot;
  return best;
}

}  // namespace

Vec3 localSupport(const Shape& s, const Vec3& d) {
  switch (s.type) {
    case Shape::Type::Box:
      return Vec3(d.x() >= 0.0 ? s.half_extents.x() : -s.half_extents.x(),
                  d.y() >= 0.0 ? s.half_extents.y() : -s.half_extents.y(),
                  d.z() >= 0.0 ? s.half_extents.z() : -s.half_extents.z());
    case Shape::Type::Sphere: {
      const double len = d.norm();
      return len > 0.0 ? Vec3(s.radius * d / len) : Vec3(s.radius, 0.0, 0.0);
    }
    case Shape::Type::Cylinder: {
      const double radial = std::hypot(d.x(), d.y());
      const double z = d.z() >= 0.0 ? s.half_length : -s.half_length;
      if (radial == 0.0) return Vec3(s.radius, 0.0, z);
      return Vec3(s.radius * d.x() / radial, s.radius * d.y() / radial, z);
    }
    case Shape::Type::Hull: return s.hull->vertices[hullSupportIndex(*s.hull, d)];
  }
  return Vec3::Zero();
}

void supportingFace(const Shape& s, const Vec3& d, Face& out) {
  out.vertices.clear();
  switch (s.type) {
    case Shape::Type::Box: {
      int k = 0;
      d.cwiseAbs().maxCoeff(&k);
      const double sign = d[k] >= 0.0 ? 1.0 : -1.0;
      const int i = (k + 1) % 3, j = (k + 2) % 3;
      const Vec3& e = s.half_extents;
      for (const auto& [si, sj] : {std::pair{1.0, 1.0}, {-1.0, 1.0}, {-1.0, -1.0}, {1.0, -1.0}}) {
        Vec3 p;
        p[k] = sign * e[k];
        p[i] = si * e[i];
        p[j] = sj * e[j];
        out.vertices.push_back(p);
      }
      out.normal = sign * Vec3::Unit(k);
      return;
    }
    case Shape::Type::Cylinder: {
      const double radial = std::hypot(d.x(), d.y());
      if (std::abs(d.z()) >= radial) {
        const double z = d.z() >= 0.0 ? s.half_length : -s.half_length;
        for (int k = 0; k < kCapVertices; ++k) out.vertices.push_back(capVertex(s, k, z));
        out.normal = Vec3(0.0, 0.0, d.z() >= 0.0 ? 1.0 : -1.0);
      } else {
        const Vec3 u(d.x() / radial, d.y() / radial, 0.0);
        out.vertices.push_back(s.radius * u + Vec3(0.0, 0.0, s.half_length));
        out.vertices.push_back(s.radius * u - Vec3(0.0, 0.0, s.half_length));
        out.normal = u;
      }
      return;
    }
    case Shape::Type::Sphere:
      out.vertices.push_back(localSupport(s, d));
      out.normal = out.vertices.back() / s.radius;
      return;
    case Shape::Type::Hull: {
      const ConvexHull::Face* best = &s.hull->faces[0];
      for (const ConvexHull::Face& face : s.hull->faces)
        if (face.normal.dot(d) > best->normal.dot(d)) best = &face;
      for (int v : best->vertices) out.vertices.push_back(s.hull->vertices[v]);
      out.normal = best->normal;
      return;
    }
  }
}

void faceNormals(const Shape& s, std::vector<Vec3>& out) {
  out.clear();
  if (s.type == Shape::Type::Sphere) return;
  if (s.type == Shape::Type::Hull) {
    for (const ConvexHull::Face& face : s.hull->faces) out.push_back(face.normal);
    return;
  }
  for (int k = s.type == Shape::Type::Cylinder ? 2 : 0; k < 3; ++k) {
    out.push_back(Vec3::Unit(k));
    out.push_back(-Vec3::Unit(k));
  }
}

void featurePoints(const Shape& s, const Vec3& toward, std::vector<Vec3>& out) {
  out.clear();
  switch (s.type) {
    case Shape::Type::Box:
      for (int i = 0; i < 8; ++i)
        out.emplace_back((i & 1) ? s.half_extents.x() : -s.half_extents.x(),
                         (i & 2) ? s.half_extents.y() : -s.half_extents.y(),
                         (i & 4) ? s.half_extents.z() : -s.half_extents.z());
      return;
    case Shape::Type::Sphere:
      out.push_back(localSupport(s, toward));
      return;
    case Shape::Type::Cylinder: {
      const double radial = std::hypot(toward.x(), toward.y());
      for (double z : {-s.half_length, s.half_length}) {
        if (radial > 1e-9 * toward.norm())
          out.emplace_back(s.radius * toward.x() / radial, s.radius * toward.y() / radial, z);
        for (int k = 0; k < kCapVertices; ++k) out.push_back(capVertex(s, k, z));
      }
      return;
    }
    case Shape::Type::Hull:
      out = s.hull->vertices;
      return;
  }
}

}  // namespace reeve
