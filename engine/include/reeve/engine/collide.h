// Narrow phase: contact points between a ground plane and a shape, and
// between two shapes (boxes, spheres, cylinders), for the contact rows of
// contact.h. Body-body pairs use libccd's Minkowski Portal Refinement for
// the normal (Snethen, "XenoCollide", Game Programming Gems 7); points come
// from shape features (box corners, cylinder cap rims, a sphere's support
// point) that lie inside the other shape, so a face resting on a face gets
// a stable manifold of several points rather than MPR's single one.
#pragma once

#include <vector>

#include "reeve/engine/body.h"
#include "reeve/engine/contact.h"
#include "reeve/engine/contact_material.h"

namespace reeve {

/// An infinite static plane {p : normal . p = height_m}; solid on the side
/// opposite `normal`. `normal` is a unit world vector (World::setGround
/// normalizes it); `height_m` in m.
struct GroundPlane {
  Vec3 normal = Vec3::UnitY();
  double height_m = 0.0;
  ContactMaterial material;
};

/// Radius (m) of the smallest sphere about the body origin that holds the
/// shape: the broad phase's bound.
double boundingRadius(const Shape& shape);

/// Appends to `out` a contact (a = kWorldBody, b = `id`) for every feature
/// point of the body below the plane, with the combined material of the
/// ground and `material`. Box: its corners; sphere: its lowest point;
/// cylinder: the lowest point of each cap rim and 16 points around each rim.
void collideGround(const GroundPlane& ground, BodyId id, const Shape& shape,
                   const BodyState& body, const ContactMaterial& material,
                   std::vector<Contact>& out);

/// Appends to `out` the contacts (normal from a into b) between two
/// overlapping shapes: the feature points of each inside the other (with a
/// lateral slack of 1 % of the smaller shape's least dimension), depths
/// measured along the MPR normal; MPR's single point when no feature is
/// inside (edge on edge). Nothing when the shapes are apart.
void collideBodies(BodyId id_a, const Shape& shape_a, const BodyState& a, BodyId id_b,
                   const Shape& shape_b, const BodyState& b, const ContactMaterial& material,
                   std::vector<Contact>& out);

}  // namespace reeve
