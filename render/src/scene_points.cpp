#include "scene_points.h"

#include <cmath>
#include <limits>
#include <numbers>

#include "reeve/render/cable_path.h"

namespace reeve {

Vec3 worldHalfExtents(const Shape& shape, const Quat& q) {
  switch (shape.type) {
    case Shape::Type::Box: return q.toRotationMatrix().cwiseAbs() * shape.half_extents;
    case Shape::Type::Cylinder: {
      const Vec3 axis = q * Vec3::UnitZ();
      const Vec3 across = (Vec3::Ones() - axis.cwiseProduct(axis)).cwiseMax(0.0).cwiseSqrt();
      return shape.radius * across + shape.half_length * axis.cwiseAbs();
    }
    case Shape::Type::Sphere: return Vec3::Constant(shape.radius);
    case Shape::Type::Hull: {
      Vec3 half = Vec3::Zero();
      for (const Vec3& v : shape.hull->vertices) half = half.cwiseMax((q * v).cwiseAbs());
      return half;
    }
  }
  return Vec3::Zero();
}

std::vector<Vec3> scenePoints(const World& world, const CableSystem& cables) {
  std::vector<Vec3> points;
  for (BodyId id = 0; id < world.bodyCount(); ++id) {
    const BodyState& body = world.body(id);
    const Vec3 half = worldHalfExtents(world.bodyDef(id).shape, body.q);
    for (int corner = 0; corner < 8; ++corner)
      points.push_back(body.x + Vec3(corner & 1 ? half.x() : -half.x(),
                                     corner & 2 ? half.y() : -half.y(),
                                     corner & 4 ? half.z() : -half.z()));
  }
  constexpr double kStepRad = 2.0 * std::numbers::pi / 16.0;  // coarse: an outline will do
  for (int c = 0; c < static_cast<int>(cables.cables().size()); ++c) {
    for (const auto& path : cablePaths(cables, c, kStepRad)) points.insert(points.end(), path.begin(), path.end());
    const Cable& cable = cables.cables()[c];
    for (const Link& link : cable.links)
      if (link.type == LinkType::Rolling || link.type == LinkType::Hybrid) {
        const auto outline = sectionOutline(link, world.body(link.body), kStepRad);
        points.insert(points.end(), outline.begin(), outline.end());
      }
    // Spool coils at their widest, whatever the cable's drawn thickness.
    const int last = static_cast<int>(cable.links.size()) - 1;
    for (int k : {0, last}) {
      const auto coil = spoolCoil(cables, c, k, std::numeric_limits<double>::infinity(), kStepRad);
      points.insert(points.end(), coil.begin(), coil.end());
    }
  }
  return points;
}

}  // namespace reeve
