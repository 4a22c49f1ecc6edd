#include "scene_points.h"

#include <cmath>

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
  for (int c = 0; c < static_cast<int>(cables.cables().size()); ++c)
    for (int j = 0; j < static_cast<int>(cables.cables()[c].joints.size()); ++j) {
      points.push_back(cables.startPoint(c, j));
      points.push_back(cables.endPoint(c, j));
    }
  return points;
}

}  // namespace reeve
