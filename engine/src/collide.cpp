#include "reeve/engine/collide.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include <ccd/ccd.h>

#include "clip.h"
#include "shape_features.h"

namespace reeve {
namespace {

Vec3 worldSupport(const Shape& s, const BodyState& body, const Vec3& dir) {
  return body.toWorld(localSupport(s, body.q.conjugate() * dir));
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
  double margin;  // m, added all round
};

void ccdSupport(const void* obj, const ccd_vec3_t* dir, ccd_vec3_t* out) {
  const auto* o = static_cast<const CcdObject*>(obj);
  const Vec3 d(dir->v[0], dir->v[1], dir->v[2]);
  const double len = d.norm();
  const Vec3 p = worldSupport(*o->shape, *o->body, d) + (len > 0.0 ? o->margin / len : 0.0) * d;
  ccdVec3Set(out, p.x(), p.y(), p.z());
}

// The point of a curved surface that touches along the unit world
// direction `out` (outward from the shape), nearest to the world point
// `near`: on a cylinder's side, the point of the side line under `out`
// nearest to `near`; on a sphere, its support point. Then the normal
// through it passes through the cylinder's axis or the sphere's centre,
// as the force of a curved contact must. (MPR's point is merely inside the
// overlap: 2 um beside a thin rod's axis, which turned the rod's weight on
// a wheel into a torque about the rod's axis, and its tiny inertia about
// that axis into hundreds of rad/s of spin that friction made a roll
// along the wheel.) nullopt for flat features (boxes, hulls, cylinder
// caps): MPR's point stands there.
std::optional<Vec3> curvedSurfacePoint(const Shape& s, const BodyState& body, const Vec3& out,
                                       const Vec3& near) {
  const Vec3 d = body.q.conjugate() * out;
  if (s.type == Shape::Type::Sphere) return body.toWorld(localSupport(s, d));
  if (s.type != Shape::Type::Cylinder) return std::nullopt;
  const double radial = std::hypot(d.x(), d.y());
  if (!(radial > std::abs(d.z()))) return std::nullopt;  // a cap faces `out`
  const Vec3 local = body.toLocal(near);
  const double z = std::clamp(local.z(), -s.half_length, s.half_length);
  return body.toWorld(Vec3(s.radius * d.x() / radial, s.radius * d.y() / radial, z));
}

// A box, cylinder or hull as a contact's solid core; a sphere is none.
ContactSolid solidOf(const Shape& shape) {
  switch (shape.type) {
    case Shape::Type::Box: return {ContactSolid::Kind::Box, shape.half_extents, nullptr};
    case Shape::Type::Cylinder:
      return {ContactSolid::Kind::Cylinder, Vec3(shape.radius, shape.radius, shape.half_length), nullptr};
    case Shape::Type::Hull: return {ContactSolid::Kind::Hull, Vec3::Zero(), shape.hull.get()};
    case Shape::Type::Sphere: break;
  }
  return {};
}

// A sphere, or a cylinder's side, on a box, cylinder or hull, exactly: the
// contact takes the body whole as one core and the sphere's centre or the
// cylinder's axis as the other (Contact::solid_a, core_a), and measures it
// as the solve will at each visit (closestCorePoints): the normal runs
// from the body's point nearest the centre (on a face, an edge or a
// corner; a cylinder's side, cap or rim), or nearest the axis' nearest
// stretch, to that centre or axis point, and the separation is their
// distance less the radius. MPR's normal runs along the ray between the
// centres: a ball 2 mm beyond a table's edge rested on it with an upright
// normal, 0.8 mm above it, one rolling off the edge (or a drum's rim) was
// thrown up (236 J in a frame for 1 kg at 0.5 m/s), and a log beyond the
// edge rested there too. False, with nothing added, where the centre or
// axis lies in the body or a cap touches (MPR's then).
bool curvedOnSolid(BodyId id_a, const Shape& shape_a, const BodyState& a, BodyId id_b, const Shape& shape_b,
                   const BodyState& b, const ContactMaterial& material, double margin, std::vector<Contact>& out) {
  const auto curved = [](const Shape& s) { return s.type == Shape::Type::Sphere || s.type == Shape::Type::Cylinder; };
  const bool solid_a = !curved(shape_a) || (shape_a.type == Shape::Type::Cylinder && shape_b.type == Shape::Type::Sphere);
  const Shape& round = solid_a ? shape_b : shape_a;
  Contact probe;
  (solid_a ? probe.solid_a : probe.solid_b) = solidOf(solid_a ? shape_a : shape_b);
  probe.core_a = solid_a ? 0.0 : round.type == Shape::Type::Sphere ? 0.0 : round.half_length;
  probe.core_b = solid_a ? (round.type == Shape::Type::Sphere ? 0.0 : round.half_length) : 0.0;
  (solid_a ? probe.radius_b : probe.radius_a) = round.radius;
  Vec3 P, Q;
  if (!closestCorePoints(probe, a.x, a.q, b.x, b.q, P, Q)) return false;
  const Vec3 n = (Q - P).normalized();
  if ((Q - P).norm() - probe.radius_a - probe.radius_b >= margin) return true;  // apart
  out.push_back(makeContact(id_a, a, P + probe.radius_a * n, id_b, b, Q - probe.radius_b * n, n, material));
  Contact& c = out.back();
  c.core_a = probe.core_a;
  c.core_b = probe.core_b;
  c.radius_a = probe.radius_a;
  c.radius_b = probe.radius_b;
  c.solid_a = probe.solid_a;
  c.solid_b = probe.solid_b;
  return true;
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
    case Shape::Type::Hull: return s.hull->bounding_radius;
  }
  return 0.0;
}

double contactMargin(const Shape& a, const Shape& b) {
  return kContactMarginFraction * std::min(boundingRadius(a), boundingRadius(b));
}

void collideGround(const GroundPlane& ground, BodyId id, const Shape& shape,
                   const BodyState& body, const ContactMaterial& material,
                   std::vector<Contact>& out) {
  // Depth of a feature point p below the plane: height - n . p.
  const Vec3& n = ground.normal;
  const ContactMaterial m = combine(ground.material, material);
  const BodyState world;  // the fixed frame: plane points are world points
  const double margin = contactMargin(shape, shape);
  thread_local std::vector<Vec3> points;
  featurePoints(shape, body.q.conjugate() * -n, points);
  for (const Vec3& local : points) {
    const Vec3 p = body.toWorld(local);
    const double depth = ground.height_m - n.dot(p);
    if (depth > -margin) out.push_back(makeContact(kWorldBody, world, p + depth * n, id, body, p, n, m));
  }
}

void collideBodies(BodyId id_a, const Shape& shape_a, const BodyState& a, BodyId id_b,
                   const Shape& shape_b, const BodyState& b, const ContactMaterial& material,
                   std::vector<Contact>& out) {
  // The features clipped below. Room, at the first pair tested, for the
  // largest primitive feature clipped (a cylinder's 16-gon cap cut by
  // another: at most 32 points) and most hulls' faces: a feature first met
  // after the first frame then allocates nothing (NoAllocation:
  // rope_segments under Gauss-Seidel first met a cap in its second frame).
  thread_local Face ref_face, inc_face;
  thread_local std::vector<Vec3> scratch;
  constexpr std::size_t kFaceRoom = 4 * kCapVertices;
  for (std::vector<Vec3>* v : {&ref_face.vertices, &inc_face.vertices, &scratch})
    if (v->capacity() < kFaceRoom) v->reserve(kFaceRoom);
  // a grows by the margin, so MPR finds pairs up to that far apart; depth
  // below is the true one, negative for a gap.
  const double margin = contactMargin(shape_a, shape_b);
  const auto sphere = [](const Shape& s) { return s.type == Shape::Type::Sphere; };
  if (sphere(shape_a) != sphere(shape_b) && curvedOnSolid(id_a, shape_a, a, id_b, shape_b, b, material, margin, out))
    return;
  const CcdObject obj_a{&shape_a, &a, margin}, obj_b{&shape_b, &b, 0.0};
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
  depth -= margin;
  // MPR's depth is along the ray between the shapes' centres, not the
  // least: for a box sliding on a long ramp its normal is off the ramp's by
  // up to 45 deg. Take instead the face normal (of a, or of b reversed) of
  // least overlap when it overlaps no more than MPR's depth plus a little:
  // that face is the exact separating axis, and the reference face of the
  // manifold. Otherwise (edge on edge) MPR's normal stands.
  const auto overlap = [&](const Vec3& u) {  // how far b sinks into a along u
    return u.dot(worldSupport(shape_a, a, u)) - u.dot(worldSupport(shape_b, b, -u));
  };
  const double tolerance =
      1e-6 + 1e-3 * std::min(boundingRadius(shape_a), boundingRadius(shape_b));
  double best = depth + tolerance;
  const BodyState* reference = nullptr;
  Vec3 axis = Vec3::Zero();  // from a into b
  thread_local std::vector<Vec3> normals;
  for (const BodyState* body : {&a, &b}) {
    const bool is_a = body == &a;
    faceNormals(is_a ? shape_a : shape_b, normals);
    for (const Vec3& local : normals) {
      const Vec3 u = is_a ? Vec3(a.q * local) : Vec3(-(b.q * local));
      const double o = overlap(u);
      if (o < -margin) return;  // a separating axis: further apart than the margin
      if (o < best) {
        best = o;
        axis = u;
        reference = body;
      }
    }
  }
  if (reference) {
    // Clip the incident feature (face, side line or point) of the other
    // body to the prism over the reference face; its points below the
    // reference plane are the manifold, with depths to that plane.
    n = axis;
    const bool ref_a = reference == &a;
    const BodyState& incident = ref_a ? b : a;
    const Shape& ref_shape = ref_a ? shape_a : shape_b;
    const Shape& inc_shape = ref_a ? shape_b : shape_a;
    const Vec3 out_ref = ref_a ? n : Vec3(-n);  // outward normal of the reference face
    supportingFace(ref_shape, reference->q.conjugate() * out_ref, ref_face);
    supportingFace(inc_shape, incident.q.conjugate() * -out_ref, inc_face);
    for (Vec3& v : ref_face.vertices) v = reference->toWorld(v);
    for (Vec3& v : inc_face.vertices) v = incident.toWorld(v);
    clipToPrism(ref_face.vertices, n, inc_face.vertices, scratch);
    const double plane = n.dot(ref_face.vertices[0]);
    const std::size_t first = out.size();
    for (const Vec3& p : inc_face.vertices) {
      // Separation along n of the incident point and the plane.
      const double C = ref_a ? n.dot(p) - plane : plane - n.dot(p);
      if (C >= margin) continue;
      if (ref_a) out.push_back(makeContact(id_a, a, p - C * n, id_b, b, p, n, material));
      else out.push_back(makeContact(id_a, a, p, id_b, b, p + C * n, n, material));
    }
    if (out.size() > first) return;
  }
  const auto cylinder = [](const Shape& s) { return s.type == Shape::Type::Cylinder; };
  const auto flat = [](const Shape& s) { return s.type == Shape::Type::Box || s.type == Shape::Type::Hull; };
  if (((cylinder(shape_a) && flat(shape_b)) || (flat(shape_a) && cylinder(shape_b))) &&
      curvedOnSolid(id_a, shape_a, a, id_b, shape_b, b, material, margin, out))
    return;
  // Edge on edge, or a curved surface on anything but a face: MPR's point,
  // on each curved surface moved to where that surface touches along n.
  const Vec3 mid(pos.v[0], pos.v[1], pos.v[2]);
  const std::optional<Vec3> curved_a = curvedSurfacePoint(shape_a, a, n, mid);
  const std::optional<Vec3> curved_b = curvedSurfacePoint(shape_b, b, -n, mid);
  const Vec3 p_a = curved_a.value_or(Vec3(mid + 0.5 * depth * n));
  const Vec3 p_b = curved_b.value_or(Vec3(mid - 0.5 * depth * n));
  if ((p_b - p_a).dot(n) >= margin) return;
  out.push_back(makeContact(id_a, a, p_a, id_b, b, p_b, n, material));
  if (curved_a && curved_b) {  // both sides curved: measured again at each visit
    Contact& c = out.back();
    c.core_a = shape_a.type == Shape::Type::Sphere ? 0.0 : shape_a.half_length;
    c.core_b = shape_b.type == Shape::Type::Sphere ? 0.0 : shape_b.half_length;
    c.radius_a = shape_a.radius;
    c.radius_b = shape_b.radius;
  }
}

}  // namespace reeve
