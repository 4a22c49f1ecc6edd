#include "reeve/engine/collide.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include <ccd/ccd.h>

namespace reeve {
namespace {

constexpr int kRimPoints = 16;  // samples around each cylinder cap rim

/// Farthest point (body-local) of the shape along the body-local direction d.
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
  }
  return Vec3::Zero();
}

Vec3 worldSupport(const Shape& s, const BodyState& body, const Vec3& dir) {
  return body.toWorld(localSupport(s, body.q.conjugate() * dir));
}

/// Calls f(local point) for each feature point of the shape; `toward` is
/// the body-local direction the features should reach furthest in.
template <class F>
void forEachFeature(const Shape& s, const Vec3& toward, F&& f) {
  switch (s.type) {
    case Shape::Type::Box:
      for (int i = 0; i < 8; ++i)
        f(Vec3((i & 1) ? s.half_extents.x() : -s.half_extents.x(),
               (i & 2) ? s.half_extents.y() : -s.half_extents.y(),
               (i & 4) ? s.half_extents.z() : -s.half_extents.z()));
      return;
    case Shape::Type::Sphere:
      f(localSupport(s, toward));
      return;
    case Shape::Type::Cylinder: {
      const double radial = std::hypot(toward.x(), toward.y());
      for (double z : {-s.half_length, s.half_length}) {
        if (radial > 1e-9 * toward.norm())
          f(Vec3(s.radius * toward.x() / radial, s.radius * toward.y() / radial, z));
        for (int k = 0; k < kRimPoints; ++k) {
          const double phi = 2.0 * std::numbers::pi * k / kRimPoints;
          f(Vec3(s.radius * std::cos(phi), s.radius * std::sin(phi), z));
        }
      }
      return;
    }
  }
}

/// Body-local point p inside the shape, with `slack` (m) added all round.
bool inside(const Shape& s, const Vec3& p, double slack) {
  switch (s.type) {
    case Shape::Type::Box:
      return (p.cwiseAbs() - s.half_extents).maxCoeff() <= slack;
    case Shape::Type::Sphere: return p.norm() <= s.radius + slack;
    case Shape::Type::Cylinder:
      return std::hypot(p.x(), p.y()) <= s.radius + slack &&
             std::abs(p.z()) <= s.half_length + slack;
  }
  return false;
}

double leastDimension(const Shape& s) {
  switch (s.type) {
    case Shape::Type::Box: return 2.0 * s.half_extents.minCoeff();
    case Shape::Type::Sphere: return 2.0 * s.radius;
    case Shape::Type::Cylinder: return 2.0 * std::min(s.radius, s.half_length);
  }
  return 0.0;
}

Contact makeContact(BodyId id_a, const BodyState& a, const Vec3& p_a, BodyId id_b,
                    const BodyState& b, const Vec3& p_b, const Vec3& n,
                    const ContactMaterial& m) {
  Contact c;
  c.a = id_a;
  c.b = id_b;
  c.local_a = a.toLocal(p_a);
  c.local_b = b.toLocal(p_b);
  c.normal = n;
  c.static_friction = m.static_friction;
  c.dynamic_friction = m.dynamic_friction;
  c.restitution = m.restitution;
  const Vec3 v = (b.v + b.omega.cross(p_b - b.x)) - (a.v + a.omega.cross(p_a - a.x));
  c.normal_speed_before = n.dot(v);
  return c;
}

// libccd glue: an object is a shape at a pose.
struct CcdObject {
  const Shape* shape;
  const BodyState* body;
};

void ccdSupport(const void* obj, const ccd_vec3_t* dir, ccd_vec3_t* out) {
  const auto* o = static_cast<const CcdObject*>(obj);
  const Vec3 p = worldSupport(*o->shape, *o->body, Vec3(dir->v[0], dir->v[1], dir->v[2]));
  ccdVec3Set(out, p.x(), p.y(), p.z());
}

void ccdCenter(const void* obj, ccd_vec3_t* out) {
  const Vec3& x = static_cast<const CcdObject*>(obj)->body->x;
  ccdVec3Set(out, x.x(), x.y(), x.z());
}

}  // namespace

double boundingRadius(const Shape& s) {
  switch (s.type) {
    case Shape::Type::Box: return s.half_extents.norm();
    case Shape::Type::Sphere: return s.radius;
    case Shape::Type::Cylinder: return std::hypot(s.radius, s.half_length);
  }
  return 0.0;
}

void collideGround(const GroundPlane& ground, BodyId id, const Shape& shape,
                   const BodyState& body, const ContactMaterial& material,
                   std::vector<Contact>& out) {
  // Depth of a feature point p below the plane: height - n . p.
  const Vec3& n = ground.normal;
  const ContactMaterial m = combine(ground.material, material);
  const BodyState world;  // the fixed frame: plane points are world points
  forEachFeature(shape, body.q.conjugate() * -n, [&](const Vec3& local) {
    const Vec3 p = body.toWorld(local);
    const double depth = ground.height_m - n.dot(p);
    if (depth > 0.0) out.push_back(makeContact(kWorldBody, world, p + depth * n, id, body, p, n, m));
  });
}

void collideBodies(BodyId id_a, const Shape& shape_a, const BodyState& a, BodyId id_b,
                   const Shape& shape_b, const BodyState& b, const ContactMaterial& material,
                   std::vector<Contact>& out) {
  const CcdObject obj_a{&shape_a, &a}, obj_b{&shape_b, &b};
  ccd_t ccd;
  CCD_INIT(&ccd);
  ccd.support1 = ccdSupport;
  ccd.support2 = ccdSupport;
  ccd.center1 = ccdCenter;
  ccd.center2 = ccdCenter;
  ccd.max_iterations = 100;
  ccd.mpr_tolerance = 1e-9;
  ccd_real_t depth = 0.0;
  ccd_vec3_t dir, pos;
  // MPR: translating b by depth along dir separates them, so dir runs from a into b.
  if (ccdMPRPenetration(&obj_a, &obj_b, &ccd, &depth, &dir, &pos) != 0) return;
  Vec3 n(dir.v[0], dir.v[1], dir.v[2]);
  if (!(depth > 0.0) || !n.allFinite() || !(n.norm() > 0.0)) return;
  n.normalize();
  // MPR's normal of a face resting on a face is off by ~1e-3 rad, which
  // walked a stack of boxes sideways. Take instead the face axis (box
  // faces, cylinder caps) of least overlap when it overlaps no more than
  // MPR's depth plus a little: that is the exact separating axis.
  {
    const auto overlap = [&](const Vec3& u) {
      const double hi_a = u.dot(worldSupport(shape_a, a, u));
      const double lo_b = u.dot(worldSupport(shape_b, b, -u));
      return hi_a - lo_b;  // how far b sinks into a along u
    };
    const double tolerance = 1e-6 + 1e-3 * std::min(leastDimension(shape_a), leastDimension(shape_b));
    double best = depth + tolerance;
    Vec3 best_axis = Vec3::Zero();
    const auto consider = [&](const Shape& s, const BodyState& body) {
      for (int k = 0; k < 3; ++k) {
        if (s.type == Shape::Type::Sphere || (s.type == Shape::Type::Cylinder && k < 2)) continue;
        Vec3 u = body.q * Vec3::Unit(k);
        if (u.dot(n) < 0.0) u = -u;
        if (u.dot(n) < 0.9) continue;  // a face far from MPR's normal is not this contact's
        if (const double o = overlap(u); o >= 0.0 && o < best) {
          best = o;
          best_axis = u;
        }
      }
    };
    consider(shape_a, a);
    consider(shape_b, b);
    if (best_axis != Vec3::Zero()) {
      n = best_axis;
      depth = best;
    }
  }

  const std::size_t first = out.size();
  const double slack = 0.01 * std::min(leastDimension(shape_a), leastDimension(shape_b));
  // Highest point of a along n and lowest of b.
  const double top_a = n.dot(worldSupport(shape_a, a, n));
  const double bottom_b = n.dot(worldSupport(shape_b, b, -n));
  forEachFeature(shape_b, b.q.conjugate() * -n, [&](const Vec3& local) {
    const Vec3 p = b.toWorld(local);
    const double d = top_a - n.dot(p);
    if (d > 0.0 && inside(shape_a, a.toLocal(p), slack))
      out.push_back(makeContact(id_a, a, p + d * n, id_b, b, p, n, material));
  });
  forEachFeature(shape_a, a.q.conjugate() * n, [&](const Vec3& local) {
    const Vec3 p = a.toWorld(local);
    const double d = n.dot(p) - bottom_b;
    if (d > 0.0 && inside(shape_b, b.toLocal(p), slack))
      out.push_back(makeContact(id_a, a, p, id_b, b, p - d * n, n, material));
  });
  if (out.size() == first) {
    const Vec3 mid(pos.v[0], pos.v[1], pos.v[2]);
    out.push_back(makeContact(id_a, a, mid + 0.5 * depth * n, id_b, b, mid - 0.5 * depth * n, n,
                              material));
  }
}

}  // namespace reeve
