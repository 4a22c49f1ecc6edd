#include "meshes.h"

#include <cmath>
#include <numbers>

namespace reeve {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

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

}  // namespace reeve
