// Narrow phase: contact points between a ground plane and a shape, and
// between two shapes (boxes, spheres, cylinders, convex hulls), for the contact rows of
// contact.h. Body-body pairs: libccd's Minkowski Portal Refinement (Snethen,
// "XenoCollide", Game Programming Gems 7) says whether they touch; the face
// of least overlap (a separating-axis test over both shapes' face normals)
// gives the normal and the reference face, and the other shape's facing
// feature clipped to it (Sutherland-Hodgman) gives the points, so a face on
// a face gets a manifold of several points with exact depths.
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

/// Contact margin (m) of a pair: points up to this far apart become contacts
/// too, whose rows act only once the solve makes them touch. Without it a
/// box that the solve pushes into its neighbour after detection finds no
/// contact until the next substep: a stack bounced every other substep and
/// walked. kContactMarginFraction of the smaller bounding radius.
inline constexpr double kContactMarginFraction = 0.02;
double contactMargin(const Shape& a, const Shape& b);

/// Appends to `out` a contact (a = kWorldBody, b = `id`) for every feature
/// point of the body below the plane or less than contactMargin above it,
/// with the combined material of the ground and `material`. Box and hull:
/// their corners; sphere: its lowest point; cylinder: the lowest point of
/// each cap rim and 16 points around each rim.
void collideGround(const GroundPlane& ground, BodyId id, const Shape& shape,
                   const BodyState& body, const ContactMaterial& material,
                   std::vector<Contact>& out);

/// Appends to `out` the contacts (normal from a into b) between two shapes
/// closer than contactMargin. A sphere on a box, cylinder or hull: one
/// point, the normal from the sphere centre's nearest point of the body (a
/// face, an edge or a corner; a cylinder's side, cap or rim) to the
/// centre, the contact carrying the body and the centre as its cores
/// (Contact::solid_a), measured as at each visit (closestCorePoints); a
/// centre inside the body is left to MPR, as the rest. A cylinder's side
/// on a box or hull where no face holds the other's feature (a log beyond
/// a table's edge): the same from its axis. Otherwise, when a face
/// normal (box and hull faces, cylinder caps) overlaps no more than MPR's
/// depth (+1e-6 m + 0.1 % of the smaller bounding radius), that face is
/// the reference and the other body's feature facing it (face, cylinder
/// side line or sphere point) is clipped to the prism over it; every clipped point less than the margin above
/// the reference plane is a contact, its point on the reference body
/// projected onto the plane. Otherwise (edge on edge, curved on curved)
/// MPR's single point and normal, the point moved onto each curved
/// surface (a cylinder's side, a sphere) where it touches along the
/// normal, so that the normal passes through the cylinder's axis or the
/// sphere's centre; where both surfaces are curved the contact carries
/// their cores (Contact::core_a), and the solve measures it again at each
/// visit. Nothing when the shapes are further apart.
void collideBodies(BodyId id_a, const Shape& shape_a, const BodyState& a, BodyId id_b,
                   const Shape& shape_b, const BodyState& b, const ContactMaterial& material,
                   std::vector<Contact>& out);

}  // namespace reeve
