#include <cmath>
#include <stdexcept>
#include <string>

#include "common.h"

namespace reeve::machines {
namespace {

// Skilling's TransposetoAxes for 3 dimensions of `bits` bits: the Hilbert
// index in transposed form (its bits dealt round-robin to x[0], x[1],
// x[2], most significant first) becomes the point's coordinates.
void transposeToAxes(unsigned x[3], int bits) {
  const unsigned N = 2u << (bits - 1);
  unsigned t = x[2] >> 1;  // Gray decode
  for (int i = 2; i > 0; --i) x[i] ^= x[i - 1];
  x[0] ^= t;
  for (unsigned Q = 2; Q != N; Q <<= 1) {  // undo excess work
    const unsigned P = Q - 1;
    for (int i = 2; i >= 0; --i) {
      if (x[i] & Q) {
        x[0] ^= P;
      } else {
        t = (x[0] ^ x[i]) & P;
        x[0] ^= t;
        x[i] ^= t;
      }
    }
  }
}

// A unit vector normal to the unit `d`.
Vec3 normalTo(const Vec3& d) { return d.cross(std::abs(d.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).normalized(); }

}  // namespace

std::vector<Vec3> hilbertCurve(int level) {
  if (level < 1 || level > 6) throw std::invalid_argument("hilbertCurve: level must be in [1, 6]");
  const unsigned count = 1u << (3 * level);
  std::vector<Vec3> points;
  points.reserve(count);
  for (unsigned h = 0; h < count; ++h) {
    unsigned x[3] = {0, 0, 0};
    for (int bit = 3 * level - 1, k = 0; bit >= 0; --bit, ++k)
      if (h >> bit & 1u) x[k % 3] |= 1u << (level - 1 - k / 3);
    transposeToAxes(x, level);
    points.emplace_back(x[0], x[1], x[2]);
  }
  return points;
}

Hilbert hilbert(const HilbertSpec& spec) {
  Hilbert m;
  m.spec = spec;
  m.scene = detail::emptyScene("hilbert" + std::to_string(spec.level) + " (generated)", spec.gravity, spec.budget);
  m.scene.description = "A cable along a 3D Hilbert curve of hinged wheels, wound in by a motor on the first (paper Fig. 1 right, Fig. 18).";
  World& world = *m.scene.world;
  const std::vector<Vec3> curve = hilbertCurve(spec.level);
  const int n = static_cast<int>(curve.size());
  // The cable's direction leaving each point: along the curve, and down
  // from the last wheel to the load.
  std::vector<Vec3> out(n);
  for (int k = 0; k + 1 < n; ++k) out[k] = curve[k + 1] - curve[k];
  out[n - 1] = -Vec3::UnitY();
  // Axes: normal to the turn where the curve turns (the cable then goes
  // round the wheel counter-clockwise about it), the previous wheel's where
  // it runs straight (the cable then crosses over, clockwise).
  std::vector<Vec3> axis(n);
  std::vector<int> orientation(n, 1);
  axis[0] = normalTo(out[0]);
  for (int k = 1; k < n; ++k) {
    const Vec3 turn = out[k - 1].cross(out[k]);
    if (turn.norm() > 1e-9) {
      axis[k] = turn.normalized();
    } else {
      axis[k] = std::abs(axis[k - 1].dot(out[k])) < 1e-9 ? axis[k - 1] : normalTo(out[k]);
      orientation[k] = -orientation[k - 1];
    }
  }
  CableDef cable;
  cable.name = "rope";
  for (int k = 0; k < n; ++k) {
    const Vec3 at = spec.pitch_m * curve[k];
    const BodyId w = detail::addWheel(world, "wheel" + std::to_string(k), spec.radius_m, spec.wheel_kg, at, axis[k]);
    m.wheels.push_back(w);
    HingeDef hinge{w, kWorldBody, at, axis[k]};
    if (k == 0) {
      // Winding in turns the spool against the cable's travel round it.
      hinge.drive = {HingeDrive::Mode::Velocity, -orientation[0] * spec.motor_speed_rad_per_s, spec.motor_torque_Nm};
      m.motor = world.addHinge(hinge);
      cable.links.push_back(LinkDef::hybrid(w, orientation[0], 2.0 * spec.pitch_m * n));
    } else {
      world.addHinge(hinge);
      cable.links.push_back(LinkDef::rolling(w, orientation[k]));
    }
  }
  // The load hangs below the last wheel's departure point: the wheel lies
  // on the left of the cable's travel for a counter-clockwise link.
  const Vec3 last = spec.pitch_m * curve[n - 1];
  const Vec3 departure = last - orientation[n - 1] * spec.radius_m * axis[n - 1].cross(out[n - 1]);
  const double box = 0.1;
  m.load = detail::addBox(world, "load", Vec3::Constant(box), spec.load_kg, departure - Vec3(0.0, 2.0 + box, 0.0));
  cable.links.push_back(LinkDef::attachment(m.load, Vec3(0.0, box, 0.0)));
  m.cable = m.scene.cables->addCable(cable);
  return m;
}

}  // namespace reeve::machines
