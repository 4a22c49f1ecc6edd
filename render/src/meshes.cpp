#include "meshes.h"

#include <cmath>
#include <cstddef>
#include <numbers>

namespace reeve {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kMitreMaxTurnRad = 45.0 * std::numbers::pi / 180.0;  // tube joints

// Sector i of n (around local z) is an accent when it falls in the first
// or third quarter turn.
bool inAccentQuarter(int i, int n) { return (4 * i / n) % 2 == 0; }

Vec3 onCircle(double angle, double z) { return Vec3(std::cos(angle), std::sin(angle), z); }

}  // namespace

void Mesh::addVertex(const Vec3& position, const Vec3& normal) {
  for (int k = 0; k < 3; ++k) {
    positions.push_back(static_cast<float>(position[k]));
    normals.push_back(static_cast<float>(normal[k]));
  }
}

Mesh unitBox() {
  Mesh mesh;
  for (int axis = 0; axis < 3; ++axis)
    for (double side : {-1.0, 1.0}) {
      Vec3 n = Vec3::Zero();
      n[axis] = side;
      // u x v = n, so (c, c+u, c+u+v, c+v) runs counter-clockwise about n.
      Vec3 u = Vec3::Zero(), v = Vec3::Zero();
      u[(axis + 1) % 3] = 1.0;
      v[(axis + 2) % 3] = side;
      const Vec3 corners[4] = {n - u - v, n + u - v, n + u + v, n - u + v};
      for (int k : {0, 1, 2, 0, 2, 3}) mesh.addVertex(corners[k], n);
    }
  return mesh;
}

Mesh hullMesh(const ConvexHull& hull) {
  Mesh mesh;
  for (const ConvexHull::Face& face : hull.faces)
    for (std::size_t i = 1; i + 1 < face.vertices.size(); ++i)
      for (std::size_t k : {std::size_t{0}, i, i + 1})
        mesh.addVertex(hull.vertices[face.vertices[k]], face.normal);
  return mesh;
}

TwoToneMesh unitCylinder(int segments) {
  TwoToneMesh mesh;
  for (int i = 0; i < segments; ++i) {
    const double a0 = kTwoPi * i / segments, a1 = kTwoPi * (i + 1) / segments;
    const Vec3 n0 = onCircle(a0, 0.0), n1 = onCircle(a1, 0.0);
    const Vec3 b0 = onCircle(a0, -1.0), b1 = onCircle(a1, -1.0);
    const Vec3 t0 = onCircle(a0, 1.0), t1 = onCircle(a1, 1.0);
    Mesh& side = mesh.main;
    side.addVertex(b0, n0), side.addVertex(b1, n1), side.addVertex(t1, n1);
    side.addVertex(b0, n0), side.addVertex(t1, n1), side.addVertex(t0, n0);
    Mesh& cap = inAccentQuarter(i, segments) ? mesh.accent : mesh.main;
    cap.addVertex(Vec3(0, 0, 1), Vec3::UnitZ()), cap.addVertex(t0, Vec3::UnitZ());
    cap.addVertex(t1, Vec3::UnitZ());
    cap.addVertex(Vec3(0, 0, -1), -Vec3::UnitZ()), cap.addVertex(b1, -Vec3::UnitZ());
    cap.addVertex(b0, -Vec3::UnitZ());
  }
  return mesh;
}

TwoToneMesh unitSphere(int slices, int stacks) {
  TwoToneMesh mesh;
  const auto point = [&](int i, int k) {
    const double polar = std::numbers::pi * k / stacks;
    return Vec3(std::sin(polar) * std::cos(kTwoPi * i / slices),
                std::sin(polar) * std::sin(kTwoPi * i / slices), std::cos(polar));
  };
  for (int i = 0; i < slices; ++i) {
    Mesh& lune = inAccentQuarter(i, slices) ? mesh.accent : mesh.main;
    for (int k = 0; k < stacks; ++k) {
      const Vec3 p00 = point(i, k), p10 = point(i + 1, k);
      const Vec3 p01 = point(i, k + 1), p11 = point(i + 1, k + 1);
      // On a unit sphere the normal is the position. Skip the degenerate
      // triangle at each pole.
      if (k > 0) lune.addVertex(p00, p00), lune.addVertex(p01, p01), lune.addVertex(p10, p10);
      if (k + 1 < stacks)
        lune.addVertex(p10, p10), lune.addVertex(p01, p01), lune.addVertex(p11, p11);
    }
  }
  return mesh;
}

Mesh unitTorus(double tube, int segments, int sides) {
  Mesh mesh;
  const auto vertex = [&](int i, int k) {
    const Vec3 radial = onCircle(kTwoPi * i / segments, 0.0);
    const double a = kTwoPi * k / sides;
    const Vec3 normal = std::cos(a) * radial + std::sin(a) * Vec3::UnitZ();
    mesh.addVertex(radial + tube * normal, normal);
  };
  for (int i = 0; i < segments; ++i)
    for (int k = 0; k < sides; ++k) {
      vertex(i, k), vertex(i + 1, k), vertex(i + 1, k + 1);
      vertex(i, k), vertex(i + 1, k + 1), vertex(i, k + 1);
    }
  return mesh;
}

void appendTransformed(Mesh& mesh, const Mesh& unit, const Eigen::Affine3d& pose) {
  const Eigen::Matrix3d normal_matrix = pose.linear().inverse().transpose();
  for (int v = 0; v < unit.vertexCount(); ++v) {
    const Vec3 p = Eigen::Vector3f(&unit.positions[3 * v]).cast<double>();
    const Vec3 n = Eigen::Vector3f(&unit.normals[3 * v]).cast<double>();
    mesh.addVertex(pose * p, (normal_matrix * n).normalized());
  }
}

void appendTube(Mesh& mesh, const std::vector<Vec3>& path, double radius, int sides,
                const Mesh& ball) {
  std::vector<Vec3> points;
  for (const Vec3& p : path)
    if (points.empty() || p != points.back()) points.push_back(p);
  const auto addBall = [&](const Vec3& centre) {
    appendTransformed(mesh, ball, Eigen::Translation3d(centre) * Eigen::Scaling(radius));
  };
  if (points.empty()) return;
  addBall(points.front());
  addBall(points.back());
  const int segments = static_cast<int>(points.size()) - 1;
  std::vector<Vec3> directions;
  for (int i = 0; i < segments; ++i) directions.push_back((points[i + 1] - points[i]).normalized());
  // Normal of the plane that ends a segment at point k: the bisector of
  // the two directions when the turn is gentle (both segments end on the
  // same ellipse), else square to `own` with a ball over the corner.
  const auto jointNormal = [&](int k, const Vec3& own) -> Vec3 {
    if (k == 0 || k == segments) return own;
    const Vec3& in = directions[k - 1];
    const Vec3& out = directions[k];
    return in.dot(out) >= std::cos(kMitreMaxTurnRad) ? (in + out).normalized() : own;
  };
  // Rings are parallel-transported from segment to segment so that the
  // mitred ends of neighbours match vertex for vertex.
  Vec3 u = directions[0].unitOrthogonal();
  for (int i = 0; i < segments; ++i) {
    const Vec3& t = directions[i];
    if (i > 0) {
      u = (rotationBetween(directions[i - 1], t) * u).normalized();
      if (directions[i - 1].dot(t) < std::cos(kMitreMaxTurnRad)) addBall(points[i]);
    }
    const Vec3 v = t.cross(u);
    const Vec3 start_normal = jointNormal(i, t), end_normal = jointNormal(i + 1, t);
    // The point at `offset` from the axis at `centre`, slid along the axis
    // onto the joint plane through `centre` with `normal`.
    const auto onPlane = [&](const Vec3& centre, const Vec3& offset, const Vec3& normal) {
      return Vec3(centre + offset - t * (offset.dot(normal) / t.dot(normal)));
    };
    for (int k = 0; k < sides; ++k) {
      const double a0 = kTwoPi * k / sides, a1 = kTwoPi * (k + 1) / sides;
      const Vec3 n0 = std::cos(a0) * u + std::sin(a0) * v;
      const Vec3 n1 = std::cos(a1) * u + std::sin(a1) * v;
      const Vec3 b0 = onPlane(points[i], radius * n0, start_normal);
      const Vec3 b1 = onPlane(points[i], radius * n1, start_normal);
      const Vec3 e0 = onPlane(points[i + 1], radius * n0, end_normal);
      const Vec3 e1 = onPlane(points[i + 1], radius * n1, end_normal);
      mesh.addVertex(b0, n0), mesh.addVertex(b1, n1), mesh.addVertex(e1, n1);
      mesh.addVertex(b0, n0), mesh.addVertex(e1, n1), mesh.addVertex(e0, n0);
    }
  }
}

}  // namespace reeve
