#include "reeve/engine/math.h"

#include <Eigen/SVD>

namespace reeve {

Quat rotationBetween(const Vec3& from, const Vec3& to) { return Quat::FromTwoVectors(from, to); }

}  // namespace reeve
