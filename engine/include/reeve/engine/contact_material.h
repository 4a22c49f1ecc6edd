// Surface materials of contacts (Müller et al. 2020, sec. 3.5): friction
// coefficients and restitution, per body and for the ground plane.
#pragma once

namespace reeve {

/// Contact properties of a surface. Coefficients are dimensionless.
/// `static_friction` (mu_s >= 0) bounds the tangential positional
/// correction that keeps a contact stuck; `dynamic_friction` (mu_d >= 0)
/// brakes sliding with force mu_d |f_n|; `restitution` (e in [0, 1]) is the
/// ratio of normal separating to approaching speed (SCA 2020, eq. 26-34).
struct ContactMaterial {
  double static_friction = 0.5;
  double dynamic_friction = 0.3;
  double restitution = 0.0;
};

/// The material of a contact between surfaces `a` and `b`: each of the three
/// coefficients is the mean of the two (so a pair of equal materials keeps
/// its values, and the order does not matter).
inline ContactMaterial combine(const ContactMaterial& a, const ContactMaterial& b) {
  return {0.5 * (a.static_friction + b.static_friction),
          0.5 * (a.dynamic_friction + b.dynamic_friction),
          0.5 * (a.restitution + b.restitution)};
}

/// True when all coefficients are finite, the frictions >= 0 and the
/// restitution in [0, 1].
bool isValid(const ContactMaterial& m);

}  // namespace reeve
