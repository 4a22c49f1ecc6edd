#include "reeve/engine/body.h"

#include <cmath>
#include <stdexcept>

#include "reeve/engine/fp_exceptions.h"

namespace reeve {

MotionKeyframe motionAt(const std::vector<MotionKeyframe>& motion, double t) {
  const auto [i, s] = keyframeAt(motion, t);
  MotionKeyframe m = motion[i];
  if (s > 0.0) {
    m.velocity += s * (motion[i + 1].velocity - m.velocity);
    m.angular_velocity += s * (motion[i + 1].angular_velocity - m.angular_velocity);
  }
  m.time = t;
  return m;
}

BodyState makeBodyState(const BodyDef& def) {
  BodyState s;
  s.x = s.x_prev = def.position;
  s.q = s.q_prev = def.orientation.normalized();
  if (!isValid(def.material))
    throw std::invalid_argument("body '" + def.name +
                                "': frictions must be finite and >= 0, restitution in [0, 1]");
  if (!def.motion.empty()) {
    if (def.is_static) throw std::invalid_argument("body '" + def.name + "': a static body has no motion");
    if (!timesIncrease(def.motion))
      throw std::invalid_argument("body '" + def.name + "': its motion's times must be finite and increase strictly");
    for (const MotionKeyframe& m : def.motion)
      if (!m.velocity.allFinite() || !m.angular_velocity.allFinite())
        throw std::invalid_argument("body '" + def.name + "': its motion's velocities must be finite");
    s.kinematic = true;
    s.v = def.motion.front().velocity;
    s.omega = def.motion.front().angular_velocity;
    return s;
  }
  if (def.is_static) return s;
  s.v = def.linear_velocity;
  s.omega = def.angular_velocity;
  const FloatingPointExceptionsMasked overflow_is_tested;  // density x volume, the inertia
  const double m = def.mass > 0.0 ? def.mass : def.density * volume(def.shape);
  if (!isRepresentableMass(m))
    throw std::invalid_argument("body '" + def.name + "': a dynamic body needs a mass between 1e-100 and 1e100 kg");
  s.inv_mass = 1.0 / m;
  if (def.inertia != Vec3::Zero()) {
    if (!(def.mass > 0.0))
      throw std::invalid_argument("body '" + def.name + "': moments of inertia need a mass, not a density");
    if (!(def.inertia.minCoeff() > 0.0))
      throw std::invalid_argument("body '" + def.name + "': moments of inertia must be positive");
    s.inertia = def.inertia.asDiagonal();
  } else {
    s.inertia = inertiaTensor(def.shape, m);
  }
  const Vec3 moments = s.inertia.diagonal();
  if (!isRepresentableMass(moments.minCoeff()) || !isRepresentableMass(moments.maxCoeff()))
    throw std::invalid_argument("body '" + def.name +
                                "': a dynamic body needs moments of inertia between 1e-100 and 1e100 kg m^2");
  s.inv_inertia = s.inertia.inverse();
  if (!(def.linear_damping >= 0.0) || !(def.angular_damping >= 0.0))
    throw std::invalid_argument("body '" + def.name + "': damping must be >= 0 per second");
  s.linear_damping = def.linear_damping;
  s.angular_damping = def.angular_damping;
  return s;
}

}  // namespace reeve
