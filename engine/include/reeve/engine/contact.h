// Contacts: a non-penetration row per point, static friction as positional
// rows on the tangential motion and twist of the contact patch, and the
// velocity pass with dynamic friction, twisting friction and restitution (Müller, Macklin, Chentanez, Jeschke, Kim, "Detailed Rigid
// Body Simulation with Extended Position Based Dynamics", SCA 2020, sec.
// 3.5 and Alg. 2 lines 20-24).
//
// Sign convention (correction.h): the normal n is the gradient of the
// separation with respect to body b; it points from a into b and pushes b
// away from a. The ground is body a = kWorldBody.
#pragma once

#include <vector>

#include "reeve/engine/body.h"

namespace reeve {

struct ConvexHull;

/// A body that a contact takes whole as its core (Contact::solid_a): a box
/// of half extents `size` (m), a cylinder of radius size.x() and half
/// length size.z() about its local z (m), or the hull `hull` (its shape's,
/// which outlives the contact).
struct ContactSolid {
  enum class Kind : unsigned char { None, Box, Cylinder, Hull };
  Kind kind = Kind::None;
  Vec3 size = Vec3::Zero();
  const ConvexHull* hull = nullptr;
};

/// One contact point, made fresh each substep by the narrow phase
/// (collide.h) after integration, so its lambdas are those of one substep.
struct Contact {
  BodyId a = kWorldBody, b = 0;
  Vec3 local_a = Vec3::Zero();  // m, body-local point of a's surface (world point for the ground)
  Vec3 local_b = Vec3::Zero();  // m, body-local point of b's surface
  Vec3 normal = Vec3::UnitY();  // world, unit, from a into b
  double static_friction = 0.0;   // mu_s, combined (contact_material.h)
  double dynamic_friction = 0.0;  // mu_d
  double restitution = 0.0;       // e
  /// n . (v_b - v_a) at the contact point (m/s) when the contact was found,
  /// after integration and before the position solve: SCA 2020's v~_n.
  double normal_speed_before = 0.0;
  double lambda_n = 0.0;  // kg m, >= 0: accumulated normal correction this substep
  /// A curved pair (cylinder sides, spheres; a sphere on a box, hull or
  /// cylinder), measured again at each visit (remeasureCurvedContact): each
  /// body's core, a segment along its local z of half length `core_*` (m;
  /// 0 for a sphere's centre), and the radius about it (m); or, where
  /// `solid_*` is not None, the body itself, radius 0 (closestCorePoints).
  /// core_a < 0: the points stay body-fixed.
  double core_a = -1.0, core_b = -1.0, radius_a = 0.0, radius_b = 0.0;
  ContactSolid solid_a, solid_b;
};

/// The contact points one narrow-phase call found between two bodies,
/// `count` consecutive entries from `first` of the contact list; they share
/// a normal, a material and one static friction bound.
struct ContactManifold {
  BodyId a = kWorldBody, b = 0;  // the pair, as its contacts name it
  int first = 0, count = 0;
  /// Sum of the static friction corrections (kg m, world, normal to n) of
  /// all points this substep: the manifold's friction, whose size static
  /// friction may not push past mu_s x sum of lambda_n.
  Vec3 friction_impulse = Vec3::Zero();
  /// Sum of the static twist corrections (kg m^2, about n) this substep.
  double twist_impulse = 0.0;
  /// The patch (describePatch), set at detection: its centre, body-local on
  /// a and on b (m), and the lever arm of twisting friction (m).
  Vec3 centre_a = Vec3::Zero(), centre_b = Vec3::Zero();
  double patch_radius = 0.0;
  /// The patch has area (three or more points not on one line): its
  /// pressure can shift from point to point and hold the bodies from
  /// tilting against each other.
  bool patch_has_area = false;
  /// Static friction's anchor (anchorFriction): body-local points of a and
  /// b (m) that lay together along the patch when it began to stick, and
  /// b's orientation relative to a then (q_a^-1 q_b).
  Vec3 anchor_a = Vec3::Zero(), anchor_b = Vec3::Zero();
  Quat anchor_turn = Quat::Identity();
  bool anchor_kept = false;  // from an earlier substep, not this one's start
  /// lambda_n of the whole manifold (kg m) at its last visit, before
  /// static friction; `kept_pressure`: with a kept anchor, or in a
  /// FrictionPool that held its body in the last substep, the `pressure`
  /// of the earlier substep's manifold it came from: a floor under the
  /// bound of a hold against a body that constraints do not move (not of
  /// one redone free where a level hold tipped), and under a pooled
  /// manifold's capacity (solveContactPositions).
  double pressure = 0.0, kept_pressure = 0.0;
  /// The same pair's manifold in the last substep (findContacts): its
  /// `pressure` and `stuck`, 0 and false where there was none.
  double last_pressure = 0.0;
  bool last_stuck = false;
  /// Static friction held the anchor at the manifold's last visit
  /// (solveContactPositions): the next substep may keep it.
  bool stuck = false;
  /// The direct solve's static friction rows hold its anchor within their
  /// bound this iteration (DirectSolver::pressContacts): its visit then
  /// presses the normals only and counts it stuck.
  bool friction_rows = false;
  /// mu_s x the pressure (kg m) its last visit bounded its friction by:
  /// what it adds to its FrictionPool's capacity; 0 before a visit.
  double friction_capacity = 0.0;
  /// Its FrictionPool (the World's, this substep; World::poolFriction),
  /// -1 for none; its SupportGroup, -1 for none.
  int pool = -1, group = -1;
};

/// The static friction that one moving body's manifolds share: those by
/// which it presses, along normals within kPoolAngle of each other, on
/// bodies that constraints do not move and that move as one (static
/// ones; kinematic ones moving alike). A plank across two fixed posts or a
/// box on three fixed balls is held by all its supports' friction
/// together, spread among them as their pressures allow: any spread with
/// each |f_j| <= mu_s,j |f_n,j| holds it (rigid-body statics leave the
/// spread open), so holding needs only the total within the sum of their
/// bounds. Each manifold still holds the body's whole slip at its own
/// anchor, all or nothing, and may then take the friction its fellows'
/// pressures leave spare (solveContactPositions). Against supports that
/// move on their own the pressures cannot be pooled: friction one takes
/// beyond its own bound would push that body past Coulomb's law.
struct FrictionPool {
  /// Sums over its manifolds (kg m), brought up to date at each visit:
  /// their friction_impulse, friction_capacity and pressure.
  Vec3 friction = Vec3::Zero();
  double capacity = 0.0, pressure = 0.0;
  /// One of its manifolds stuck in the last substep (last_stuck): the pool
  /// held its body there, and each manifold's bound keeps the pressure it
  /// had then as a floor (kept_pressure; World::poolFriction). Without,
  /// the settling of a box placed on a bed of 64 balls pressed them 0.77 x
  /// its weight in its third substep, and every hold let go.
  bool held_before = false;
  /// Its compound patch (describePool), body-local on the moving body
  /// (m): the convex hull of all its manifolds' points seen along their
  /// normal, `hull_count` vertices from `hull` (World's storage, set for
  /// the substep), its centre and the lever arm of its twisting friction,
  /// as describePatch's. A hold keeps the body level on it unless the
  /// pressure's centre would leave it, and holds its twist with that arm:
  /// a box on three balls yawed about n under a hold at one of them.
  const Vec3* hull = nullptr;
  int hull_count = 0;
  Vec3 centre = Vec3::Zero();
  double radius = 0.0;
};

/// Describes `pool`'s compound patch from `points`, all its manifolds'
/// points on the moving body, body-local (m), seen along `n`
/// (unit, body-local): appends its hull's vertices to `hull` and sets
/// hull_count, centre and radius (hull is left for the caller to point
/// at its vertices, once `hull` no longer grows).
void describePool(FrictionPool& pool, const std::vector<Vec3>& points, const Vec3& n, std::vector<Vec3>& hull);

/// The manifolds by which one moving body presses on supports that move
/// as one, whatever their normals, where they are not all one
/// FrictionPool (a log in a V-groove, a block between two jaws, a ladder
/// on a floor against a wall): `count` indices from `members` into
/// `manifolds` (the World's, this substep). A hold may take what those
/// outside its own pool leave spare along its direction t: each lends
/// max(0, friction_capacity |P t| - |friction_impulse|), P its tangent
/// plane's projector (|P t| = sqrt(1 - (n . t)^2)). The sides of a V lend
/// all of theirs along the groove, a wall nothing to a ladder's foot
/// sliding away from it.
struct SupportGroup {
  const ContactManifold* manifolds = nullptr;
  const int* members = nullptr;
  int count = 0;
};

/// Largest angle (rad) between two manifolds' normals that one
/// FrictionPool takes: for parallel normals the pooled bound is exact,
/// within a few degrees it is off by 1 - cos (0.4 % at this angle).
inline constexpr double kPoolAngle = 0.09;

/// The closest points P (on a's core) and Q (on b's) of a curved pair's
/// cores (Contact::core_a) with a at (x_a, q_a) and b at (x_b, q_b), world
/// (m); the contact's normal runs from P to Q, its points r_a and r_b
/// along it off them. Two segments P(s) = x_a + s u_a and Q(t) = x_b + t
/// u_b, |s| <= core_a, |t| <= core_b: closest where s = cos_ab t - cu and t
/// = cos_ab s + fu (cos_ab = u_a . u_b, cu = u_a . r, fu = u_b . r, r = x_a
/// - x_b), clamped in turn (Ericson, "Real-Time Collision Detection",
/// 5.1.9); near parallel (|cos_ab| > 0.99: a line contact, a log on a log)
/// they are closest all along their overlap, and that formula's s jumps
/// between its ends: there P is the middle of the overlap of b's segment,
/// seen along a's axis, with a's (or a's end nearest it), and Q the point
/// of b's segment nearest P. A solid core (Contact::solid_a) and a
/// sphere's centre: the centre's nearest point of the solid (a box
/// clamped, a cylinder clamped radially and axially, a hull's faces); and
/// a cylinder's axis: the middle of the axis' stretch within 1e-3 of its
/// radius of the least distance to the solid (golden-section search of
/// that convex distance, then bisection for the stretch's ends), and the
/// solid's point nearest it. False where the cores meet (no direction),
/// or where the axis' stretch is at its end (a cap touches, not the side).
bool closestCorePoints(const Contact& c, const Vec3& x_a, const Quat& q_a, const Vec3& x_b, const Quat& q_b,
                       Vec3& P, Vec3& Q);

/// Sets the patch of manifold `m` from its contacts at the poses a, b: the
/// patch is the convex hull of the points that overlap (separation < 0;
/// all points when none does yet). `centre_a`, `centre_b`: the mean of
/// their body-local points, where dynamic friction acts and a fresh static
/// friction anchor is set. `patch_radius`:
/// the lever arm of twisting friction, the mean distance from the centre of
/// a uniform pressure, taken as that of a disc of equal area,
/// 2/3 sqrt(A / pi) (a square: 0.752 half-sides, exactly 0.765), or a
/// quarter of the longest chord when larger (a line contact: exact); 0 for
/// one point, which holds no twist.
void describePatch(ContactManifold& m, const Contact* contacts, const BodyState& a,
                   const BodyState& b);

/// How far (a fraction of the contact margin, collide.h) a kept anchor may
/// lie off the patch: a face's anchor stays while its pressed corners come
/// and go; a rolling or rocking point contact is anchored afresh almost
/// every substep (an anchor 1.8 mm along a thin rod rocking on a wheel
/// spun the rod up about its axis).
inline constexpr double kAnchorOnPatch = 1e-3;

/// Sets the static friction anchor of manifold `m`, its patch described.
/// Kept from `previous` (the same pair's manifold of the last substep, a
/// and b either way round; nullptr for none) when that one stuck, its
/// anchor on b lies within kAnchorOnPatch x `margin` (m) of the convex hull
/// of m's points seen along n, and its anchors have slipped apart along the
/// patch by no more than `margin` (nothing moved the bodies elsewhere).
/// Otherwise the patch centre as it was at the substep's start (x_prev,
/// q_prev): friction then holds this substep's motion, as in SCA 2020,
/// sec. 3.5.
void anchorFriction(ContactManifold& m, const Contact* contacts, const ContactManifold* previous,
                    const BodyState& a, const BodyState& b, double margin);

/// Most sweeps over a manifold's normal rows, and over its friction rows,
/// in one visit; a visit stops sweeping early once no row moves more than
/// 1e-12 m.
inline constexpr int kManifoldSweeps = 8;

/// One Gauss-Seidel visit of a manifold's positional rows (SCA 2020, sec.
/// 3.5, eq. 26-27): up to kManifoldSweeps sweeps over the normal rows of
/// its points, in alternating order, then as many over the patch's static
/// friction rows. (One sweep per visit leaves a box tilted toward the
/// corner solved last, and it walks.)
///   normal:   C = (p_b - p_a) . n  (m); solved only while C < 0, with zero
///             compliance; lambda_n accumulates >= 0. Contacts found within
///             the margin (collide.h) start with C > 0 and act only if the
///             solve closes the gap. A curved pair's point (Contact::core_a;
///             a sphere or a cylinder's side on a solid too) is measured
///             again before each row: C = |Q - P| - r_a - r_b of its cores'
///             closest points, n = (Q - P) / |Q - P|.
///   friction: at the anchor (anchorFriction) a tangential row, dp =
///             p_b - p_a of the anchor's points, dp_t its part normal to
///             n, C = |dp_t|, gradient dp_t / |dp_t|; and a twist row, C =
///             n . (turn of b relative to a since the anchor), angular.
///             Kept only while |sum of tangential corrections| <= mu_s x
///             (sum of lambda_n) and |sum of twist corrections| <= mu_s x
///             (sum of lambda_n) x patch_radius; otherwise both are undone,
///             the patch is not `stuck`, and the velocity pass brakes
///             instead. A curved point's anchor is where it touches now
///             (as the paper's eq. 27), never kept: it rolls. A kept
///             anchor that passes the bound is tried again
///             afresh (this substep's motion alone); held so, the patch is
///             not `stuck` either, and the next substep anchors afresh. A
///             manifold with no pressed point is not stuck. In a
///             FrictionPool the bound grows by what the pool's other
///             manifolds leave spare (their capacity less |their
///             friction|): a post under half a plank's weight holds all of
///             its slip while the other post holds none. Its hold keeps
///             the body level (a single point's too), the twist bounded is
///             about the pool's centre (the twist row's plus the
///             friction's moment), the twist arm and the pressure centre's
///             patch are the pool's compound patch.
/// The paper holds the motion since the substep's start, a fresh anchor
/// each substep: what one substep's unconverged solve let slip stayed, and
/// a stack of three boxes crept 8 mm in 10 s at 10 x 2 (issue 28, item
/// 15). An anchor kept while the patch sticks pulls that slip back.
/// The paper keeps a friction row and bound per point; Gauss-Seidel then
/// lets the first point of a face hold the whole box, which a per-point
/// budget refuses (a box on an incline slid below the friction angle), and
/// corner rows brake a spin about n by the corners' distance (48 % too
/// fast). All points of a manifold share one material.
/// Returns whether the visit moved a body (a correction applied and kept):
/// one that moved none changed nothing, and another at the same poses
/// would do the same (World::solveDirect stops there).
/// `pool`: m's FrictionPool (nullptr for none), whose sums the visit
/// brings up to date; `group`: its SupportGroup (nullptr for none).
bool solveContactPositions(ContactManifold& m, Contact* contacts, BodyState& a, BodyState& b,
                           FrictionPool* pool = nullptr, const SupportGroup* group = nullptr);

/// The velocity pass of one manifold (SCA 2020, eq. 29-34), after the
/// velocities were read from the positions. With v = (v_b + w_b x r_b) -
/// (v_a + w_a x r_a) (for a kinematic body, the chord its point travelled
/// over the substep), v_n = n . v, v_t = v - n v_n and w_n, w_t the
/// generalized inverse masses (correction.h) along n and v_t:
///   restitution, per point: impulse n (-v_n + max(-e v~_n, 0)) / w_n,
///     with e = 0 when |v~_n| <= `rest_speed` (SCA 2020 use 2 |g| h, so
///     that resting contacts do not jitter);
///   dynamic friction, once at the patch centre: impulse
///     -v_t/|v_t| min(mu_d lambda_n / h, |v_t| / w_t), lambda_n of the
///     whole manifold (mu_d |f_n| h, f_n = lambda_n / h^2); on a patch
///     with area (or in a FrictionPool) that held at a visit this substep
///     but not at its last,
///     mu_d lambda_n less what those holds pushed against v_t
///     (friction_impulse), so that all its friction is mu_d lambda_n; in
///     a FrictionPool (`pool`) level, as its holds are: the couple of the
///     friction at the body's base goes into its supports' pressures, not
///     into a pitch (with w_t of the level motion), unless it would take
///     the pressure's centre off the pool's compound patch;
///   twisting friction: with s = n . (w_b - w_a) and w_s = n . (I_a^-1 +
///     I_b^-1) n, angular impulse -sign(s) n min(mu_d lambda_n r / h,
///     |s| / w_s), r = patch_radius.
/// The paper bounds the velocity change by h mu_d |f_n| instead of the
/// impulse, and per point; at box corners, where w_t > 1/m, that braked
/// with less than mu_d |f_n| (a box on an incline slid 6-15 % too fast),
/// and corner by corner it yawed a sliding box. At the centre of pressure
/// instead of the patch centre it braked a spinning box (the centre of
/// pressure wanders off the axis under Gauss-Seidel). Points whose normal
/// row never acted this substep (lambda_n = 0) are skipped. A curved
/// point's n is the bisector of its normals at the substep's start and
/// end, and its arms lie off its cores along that n: its velocity, read
/// from its poses, is the chord of its path round the curve, square to
/// that n (against the end's n it read as an approach, and a ball clung
/// to a log to half the centripetal speed).
void solveContactVelocities(const ContactManifold& m, const Contact* contacts, BodyState& a,
                            BodyState& b, double h, double rest_speed, const FrictionPool* pool);

/// Normal force (N) of a contact over its substep h (s): lambda_n / h^2, on b along n.
inline double contactNormalForce(const Contact& c, double h) { return c.lambda_n / (h * h); }

}  // namespace reeve
