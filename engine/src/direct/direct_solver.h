// The direct solver (SolverKind::Direct, world.h), one class over the files
// of this folder: direct_solver.cpp (the row layout, the substep, the
// iteration), rows.cpp (each row's value and gradient at the current
// poses), active_set.cpp (the bounded rows' solve), hubs.cpp (bodies with
// many rows) and sparse_ldlt (the factorization); between its iterations
// World::solveDirect places massless bodies on their spans
// (../light_bodies.h). Each iteration takes every joint row and every
// cable path at the current poses, linearized, and solves them together
// instead of one after another:
//   (J W J^T + alpha~) dlambda = -C - alpha~ lambda,   dx = W J^T dlambda,
// J the rows' gradients (one 6-vector [linear; angular] per row and moving
// body), W each body's inverse mass and world inverse inertia, alpha~ =
// compliance / h^2 (SCA 2020 eq. 4 for all rows at once), W with the
// rows' geometric stiffness and C and dx with Newton's residual (the
// motion the bodies made against the impulses they took: newtonResidual), so
// that the iterations converge to the implicit step. Gauss-Seidel
// passes a correction one row further per sweep and stalls where light
// bodies sit between heavy ones (a light wheel between a heavy load and its
// axle, a long cable over many wheels); the joint solve does not care about
// mass ratios and chain lengths, and with the cable on rotors (body.h) the
// matrix of one cable is tridiagonal, so it costs O(rows).
//
// Unilateral rows (cables pull, limits push one way, drives are bounded)
// are handled by an active set per iteration: a row whose lambda leaves its
// bounds is fixed at the bound and the rest solved again; a slack row that
// the solution would stretch joins in. Rows that depend on others (a belt
// over two rotors: its two spans cannot be stretched apart) are dropped by
// the factorization (sparse_ldlt.h), which keeps one of them; a rigid drive
// and a limit on one coordinate, one direction twice, are settled before
// it: the touched limit wins (driveAgainstLimit). A spring drive is a
// compliant row (alpha~ on its diagonal, joint_rows::prepareCoordinate),
// not dependent on a limit. Contacts are swept Gauss-Seidel after each
// iteration, but those of a body that cables hold, resting on a static
// one (a load set down while its cables still pull), are rows here too
// (Source::Contact: normal rows, and static friction's while it holds):
// swept only, the solve and the sweep traded a correction that shrank
// 0.17 to 0.3 an iteration (DESIGN, "Forty-ninth session"). Their lambdas
// are the contacts' pressure and friction (pressContacts). Private to
// reeve_engine.
//
// A body with many rows (a tackle's block, an effector on K cables, a
// palm) would make J W J^T dense among them: K^2 values and a K^3
// factorization. Such a body, a *hub*, keeps its motion dx_h (6 values; a
// rotor's, 1) as unknowns beside the rows, in the augmented (KKT) form
// (Baraff, "Linear-time dynamics using Lagrange multipliers", 1996):
//   [ J_n W_n J_n^T + alpha~ + delta   J_h  ] [dlambda]   [-C - alpha~ lambda]
//   [ J_h^T                           -M_h  ] [dx_h   ] = [0                 ],
// n the other bodies, eliminated in closed form as before, and M_h the
// hub's mass (m, and its world inertia). The matrix is quasi-definite, so
// an LDL^T exists in any elimination order (Vanderbei 1995): one AMD order
// over rows and hub motions eliminates the rows first and each hub once,
// and the cost is linear in its rows. A rigid row whose only moving bodies
// are hubs has nothing on its diagonal but alpha~: it gets at least
// delta = kHubRegularization x the hub's row count x its hub part of
// J W J^T there, and one
// refinement step against the system without delta takes its error from
// kHubRegularization to its square. Rigid rows that are redundant through
// a hub (more cables than the effector has freedoms) share the load in
// the least-squares sense of that delta: the least norm of
// sum dlambda_k^2 delta_k, equal shares for K equal cables.
#pragma once

#include <algorithm>
#include <array>
#include <optional>
#include <utility>
#include <vector>

#include "reeve/engine/body.h"
#include "reeve/engine/path_constraint.h"
#include "../joint_row_sets.h"
#include "../line_up.h"
#include "sparse_ldlt.h"

namespace reeve {

class World;
struct Island;
struct Contact;
struct ContactManifold;

namespace direct {
/// A row lists the bodies it moves and the kinematic ones it pushes on: a
/// kinematic body's entries weigh nothing (W = 0) and couple no rows, but
/// record the impulse it took (the work it does: World::addKinematicWork).
inline bool listed(const BodyState& body) { return body.moves() || body.kinematic; }
/// The tolerance (m, or rad) the direct solve meets its rows to in a
/// substep of `h` s: SolverSettings::tolerance, met at h = 1/600 s, times
/// (h / (1/600 s))^2 below that. A residual C left in a substep is a force
/// error of about C m / h^2 (4e-5 N per kg at 1/600 s); unscaled, at
/// 10,000 substeps of a 60 Hz frame a 1:100 Atwood machine's solve
/// stopped before it started and reported no tension.
inline double substepTolerance(double tolerance, double h) {
  constexpr double kToleranceStep = 1.0 / 600.0;  // s
  const double scale = h < kToleranceStep ? (h / kToleranceStep) * (h / kToleranceStep) : 1.0;
  return tolerance * scale;
}
}  // namespace direct

class DirectSolver {
 public:
  /// Starts a substep of `h` s on the rows of `island`'s constraints (after
  /// the joints' prepare functions): rebuilds the row layout if they
  /// changed since the last substep, clears the lambdas, sets
  /// what stays put over the substep. `again`: the substep's solve done
  /// again (World::ResolveCheck), which starts from the first one's active
  /// set, not from what the first one ended with. Returns true where the
  /// layout was built again only because a resting contact joined or left
  /// it (its rows are the layout's last: describeContacts), which
  /// allocates, as a cable event's layout does.
  bool prepare(World& world, const Island& island, double h, bool again);
  /// One iteration: linearize, solve, move the bodies. Returns false, and
  /// moves nothing, when every row is already met to the settings'
  /// tolerance: the iterations left would do nothing either, unless
  /// something else (a contact) moves a body.
  bool iterate(World& world, double h);
  /// Adds what the contact rows' lambdas gained since the last call to
  /// their contacts' lambda_n (kg m), the pressure the contact sweep's
  /// friction bounds, pools and the velocity pass read, and the friction
  /// rows' to their manifolds' friction_impulse and twist_impulse, which
  /// the sweep bounds. `contacts`, `manifolds`: the World's, this
  /// substep's.
  void pressContacts(std::vector<Contact>& contacts, std::vector<ContactManifold>& manifolds);

 private:
  enum class Source : unsigned char { Hinge, Prismatic, Spherical, Fixed, Distance, Path, Contact };
  struct Entry {  // one moving body of one row
    int body = 0;  // index into bodies_
    int row = 0;
    Vec3 lin = Vec3::Zero(), ang = Vec3::Zero();    // dC / d(position, rotation)
    Vec3 wlin = Vec3::Zero(), wang = Vec3::Zero();  // W times those
    // A rotor turns about its axle u alone: its entries keep only u . K . u
    // = (u . g)(u . r) - g . r of their curvature (curvature_), the only
    // part newtonStep reads.
    double axial = 0.0;
    bool flat = false;  // curvature and axial are 0 (flatten): no stiffness to add
    // wlin and wang are W J for this gradient. evaluate() leaves them for
    // shiftValues(), and only an iteration that solves weighs (W~ is known
    // there): one that stops on its residual weighs nothing.
    bool weighed = false;
  };
  struct Row {
    Source source;
    int index;        // of the joint, distance or path
    int first_entry;  // entries_[first_entry, first_entry + entry_count)
    int entry_count;
    int position;     // in the factorization's elimination order
    int diagonal;     // index of its diagonal value in the factorization
    int slots_begin;  // off-diagonal slots_: [slots_begin, slots_end)
    int slots_end;
  };
  struct Pair {  // a term J_e1 W J_e2^T of the matrix
    int e1, e2, slot;
  };
  struct Slot {  // an off-diagonal value and the row on its other side
    int value, other_row;
  };

  /// Writes the layout of the island's rows to `signature`: for each row
  /// its source, index and moving bodies. Unchanged signature, unchanged
  /// layout. Returns where its contact rows begin in it.
  std::size_t describe(World& world, const Island& island, std::vector<int>& signature) const;
  /// describe()'s contact rows, after the rest (Source::Contact).
  void describeContacts(const World& world, const Island& island, std::vector<int>& signature) const;
  void build(World& world);
  /// Fills C, bounds, activity and the entries' gradients of every row.
  void evaluate(World& world, double h);
  /// Projection::Start (world.h): the entries' gradients at the substep's
  /// start poses, into start_; each iteration then moves the bodies along
  /// them, with C at the poses solved (SHAKE): the iteration
  ///   (G_n W G_n^T + alpha~) dlambda = -C(x) - alpha~ lambda,  dx = W G_n^T dlambda
  /// converges to x = x~ + W G_n^T lambda with C(x) + alpha~ lambda = 0.
  void linearizeAtStart(World& world, double h);
  /// Where the substep's iterations start: each body at the prediction x~
  /// (integrate()), lifted by what held it up against gravity in the last
  /// substep (start_x_, at most g h^2), into moved_x_ and its pose.
  /// `rebuilt`: the layout is new this substep.
  void startPoint(const World& world, double h, bool again, bool rebuilt);
  /// Row r is a joint's one-sided row (a limit, a one-sided slide) that
  /// pushed in the last substep.
  bool pushedAsStop(int r) const;
  /// The lift (start_x_, start_phi_) moves some pushedAsStop row's C by
  /// more than `tolerance` (m or rad), along its last gradient.
  bool liftMovesStops(double tolerance) const;
  /// Which rows take their start gradient (use_start_), at the first
  /// iteration of a substep.
  void chooseStartRows();
  void evaluateBodies();
  /// The entry's W J from its gradient (and weighed set).
  void weigh(Entry& e) const;
  /// Sets (or, `add`, adds to) entry e's curvature for a point at arm r
  /// whose dC/dp is g: its axial part on a rotor, else the whole.
  void curve(int e, const Vec3& g, const Vec3& r, bool add);
  /// curve() for a path's end point p: at a rolling end the circle's centre
  /// turns with the body but its lever only off the axle (the solve turns
  /// the lever back by its turn about the axle, solvePoint), so the lever's
  /// curvature is taken off the axle, and a rotor keeps the centre's alone.
  void curveEnd(int e, const Vec3& g, const SolvePoint& p, bool add);
  /// Sets entry e's curvature to 0 (a row whose gradient does not turn
  /// with the body: an angular joint row), once.
  void flatten(int e) {
    if (entries_[e].flat) return;
    curvature_[e].setZero();
    entries_[e].axial = 0.0;
    entries_[e].flat = true;
  }
  /// Every free row meets its equation C + alpha~ lambda = 0 to within
  /// `tolerance` (m or rad), or is held at a bound it presses against.
  bool converged(double tolerance) const;
  /// Row r at `value` (its C, m or rad): a one-sided row past its side by
  /// more than `tolerance`.
  bool violated(int r, double value, double tolerance) const;
  /// Row r at `value`: its residual value + alpha~ lambda within
  /// `tolerance`, or held at a bound it presses against.
  bool met(int r, double value, double tolerance) const;
  /// A path's or distance constraint's row in a substep of `h` s: C, alpha~
  /// (both damped, when it is, and in the set) and its state.
  void evaluatePath(const World& world, int row, double h);
  /// The length (in C_) and gradients of a two-point path, and of a longer
  /// one (a run through pinholes or sliding wraps). Weighted paths (cable
  /// friction) are not rows: their forces are not along their length's
  /// gradient, which the symmetric system assumes (World::solvePositions).
  /// Scaled ones are (`scales`: PathConstraint::scales, or null).
  void evaluateSpan(const World& world, int row, const PathPoint& p0, const PathPoint& p1);
  void evaluateRun(const World& world, int row, const PathPoint* points, std::size_t count, const double* scales);
  /// Whether a span end keeps its row linear in the solve's motion: on a
  /// body the solve does not move, or rolling on a rotor about
  /// its axle from a circle centred on it. Such an end stays where it is
  /// as the rotor turns and pays out cable at a fixed rate per radian
  /// (SolvePoint::perRadian), so its gradient is constant and C changes by
  /// exactly J dphi (predictSpan).
  bool linearEnd(const PathPoint& point) const;
  /// A linear span's length (linearEnd at both ends) after the solve's
  /// turns since it was last evaluated: length + J dphi, its gradient
  /// unchanged.
  void predictSpan(int row);
  /// Whether a linear span keeps its last substep's first evaluation at
  /// this substep's first: its points lie where they lay then (the same
  /// PathConstraint::placement), and the bodies it moves stand where they
  /// stood with their axles as they were (BodyFrame::still). Its length
  /// and gradient are then the same, and the solve's turns are 0.
  bool keepsSpan(const PathConstraint& path, int row) const;
  /// A path point as this solve has it (path_constraint.h: solvePoint), on
  /// the body with index `slot` in bodies_ (-1: a body that does not move).
  SolvePoint endPoint(const World& world, const PathPoint& point, int slot);
  /// The rotation of the body with index `slot` in bodies_ this iteration.
  const Mat3& rotation(int slot);
  /// Returns the number of rows the joint has.
  int evaluateJoint(World& world, int first_row, double h);
  /// A manifold's rows from `first_row`: its normal rows, one a point, C =
  /// (p_b - p_a) . n (m, the contact sweep's: solveContactPositions),
  /// pushing only (lambda >= 0), rigid; then its static friction's
  /// (frictionRows). Returns the number of rows.
  int evaluateContacts(const World& world, int first_row);
  /// The number of static friction rows of a manifold whose first contact
  /// is `c`: two along the patch at its anchor (ContactManifold::anchor_a,
  /// anchor_b), C = (p_b - p_a) . t, and one about n where the patch has a
  /// radius, C = the turn of b relative to a since the anchor. None
  /// without friction (mu_s = 0), nor in a FrictionPool or SupportGroup,
  /// whose fellows share a bound that the sweep keeps (contact.h).
  static int frictionRows(const ContactManifold& m, const Contact& c);
  /// The states of a coordinate's drive and limit rows, which share their
  /// direction, when a limit is touched and the drive is rigid;
  /// `first_clamped` is the row of the joint's first clamped row.
  void driveAgainstLimit(int first_clamped, const joint_rows::JointRowSet& set);
  /// Rows that ended the last iteration (or substep) at a force or torque
  /// cap (a capped drive, a winch's pull) start this one held at it.
  void warmStartCaps();
  /// Solves the active set; leaves dlambda_ and the bodies' dx, dphi.
  /// `tolerance` (m or rad): what counts as a met row.
  void solveActiveSet(double tolerance);
  /// Factors the assembled matrix, solves for x_ and sets dlambda_ and the
  /// bodies' motion, keeping rows wrongly dropped as dependent; then, where
  /// a hub's rows were regularized, refinement steps. Returns true when a
  /// row truly dependent and unmet made a one-sided row let go
  /// (releaseAlongDependency): the active set changed.
  bool factorAndSolve(double tolerance);
  /// Row r, dropped as dependent and left `residual` (m or rad) unmet: fixes
  /// at 0 the first free one-sided row its dependency brings to its bound.
  bool releaseAlongDependency(int r, double residual);
  /// The most the residual C + J dx + alpha~ lambda of a row held at a
  /// bound (fixed or off, lambda at lo or hi) asks to come off it, beyond
  /// `tolerance` (m or rad), or 0; with `free_them`, the fixed ones so
  /// violated are made free.
  double heldViolation(double tolerance, bool free_them);
  /// Puts back the settled solve held_ keeps.
  void restoreHeld();
  /// dlambda_ and the hubs' motion from the solution in x_.
  void readSolution();
  /// Row r's value C + J (dx, dphi) once the bodies make the motion solved
  /// (m or rad, linearized).
  double predictedValue(int r) const;
  /// The free rows' residual of the system without the hubs' delta, in
  /// x_ (0 for the other unknowns), solved with the last factor and added.
  /// Returns the largest residual (m or rad) it corrected.
  double refine();
  /// The hubs' part of the matrix in full_ (couplings J_h, masses -M_h)
  /// and each row's delta.
  void assembleHubs();
  struct Hub;
  /// Redistributes the dlambda of the hub's free rigid cables that move it
  /// alone (its cable leaves) to the least sum of length x dlambda^2 with
  /// the same wrench on it: the limit of equal elastic cables.
  void leastNormLeaves(const Hub& hub);
  void bodyMotion();
  /// A hub's mass matrix entry (i, j) (kg or kg m^2, world) and the entry's
  /// gradient along the hub's dof `dof` (0-2 linear, 3-5 angular; a rotor's
  /// 0 is its axle).
  double hubMass(int hub, int i, int j) const;
  double hubGradient(const Entry& e, int dof) const;

  std::vector<int> signature_, scratch_;
  std::size_t contacts_begin_ = 0;  // where signature_'s contact rows begin
  // describe()'s: the bodies the cables listed before the contacts move, sorted.
  mutable std::vector<BodyId> row_bodies_;
  // describe()'s: a path's (listed body, point) pairs, sorted by body to
  // find each body's first point, then by point.
  mutable std::vector<std::pair<BodyId, int>> path_bodies_;
  // The island's manifolds (Island::manifolds, this substep): a contact
  // row's index is its manifold's place in them.
  const std::vector<int>* manifolds_ = nullptr;
  // Per contact row: its contact (World::contacts()) this iteration, or a
  // friction row's manifold (World::contactManifolds()); the lambda
  // pressContacts() last added there; a friction row's direction, world
  // (t, or the n it twists about); and its kind.
  enum class ContactRow : unsigned char { Normal, Slip, Twist };
  std::vector<int> contact_rows_, contact_of_;
  std::vector<double> contact_written_;
  std::vector<Vec3> contact_dir_;
  std::vector<ContactRow> contact_kind_;
  struct RunScratch {  // evaluateRun's, per point of the path
    std::vector<Vec3> arm, pos;
    std::vector<Vec3> u;  // segment i's unit direction times its scale
    std::vector<int> entry;
    // Per slot: the row's entry on that body while a run is evaluated, else
    // -1 (sized with the layout): a point's entry in O(1), not a search of
    // the row's entries (a rope through 1024 beads' holes spent 82 % of its
    // step there).
    std::vector<int> slot_entry;
    std::vector<int> fixed;  // per entry of the row: its fixed end's index, or -1
  } run_;
  joint_rows::JointRowSet joint_set_;  // evaluateJoint's, joint after joint
  std::vector<Row> rows_;
  std::vector<Entry> entries_;
  // Per entry, d2C / d(rotation)^2 (m): the sum over the row's points on
  // the body of sym(g r^T) - (g . r) I, g the point's dC/dp and r its arm
  // (a rotor's: Entry::axial). Beside the entries, not in them: the loops
  // over entries (the assembly, the motion) read 120 bytes an entry, not
  // 192, and a rotor's entry never reads it.
  std::vector<Mat3> curvature_;
  // Per entry, a span end's 1 / length: d2C / dp^2 = (I - u u^T) / length
  // across the span (u its direction), the second order of C as the end
  // moves sideways; 0 for the other rows' entries (a joint's rows are
  // linear in the motion; a run's points are left out).
  std::vector<double> bend_;
  // A span's fixed point on a moving body, or a run's fixed points on one
  // body taken together, as evaluated: the sums over its points (world arm
  // r from the body's centre of mass, `toward` minus the point's gradient,
  // a span's unit direction away from it) that give the body's TurnModel
  // about any axis (line_up.h).
  struct FixedEnd {
    int body;                      // index into bodies_
    int row, entry;                // its row and its body's entry in that row
    double reach = 0.0;            // the longest arm (m)
    Vec3 moment = Vec3::Zero();    // sum of toward x r: l1 = e . moment
    double along = 0.0;            // sum of toward . r
    Mat3 outer = Mat3::Zero();     // sum of toward r^T: l2 = along - e . outer e
    void add(const Vec3& arm, const Vec3& toward) {
      reach = std::max(reach, arm.norm());
      moment += toward.cross(arm);
      along += toward.dot(arm);
      outer += toward * arm.transpose();
    }
    TurnModel model(const Vec3& e) const { return {e.dot(moment), along - e.dot(outer * e)}; }
  };
  std::vector<FixedEnd> fixed_ends_;  // the last evaluate()'s (evaluateSpan, evaluateRun)
  struct FixedSpan {  // a span between two fixed points, as evaluated (stiffenMoves)
    int body0, body1;  // indices into bodies_, -1 for a body the solve does not move
    Vec3 arm0, arm1;   // world, from each body's centre of mass
    Vec3 d;            // p_1 - p_0 (m)
  };
  std::vector<FixedSpan> fixed_spans_;  // the last evaluate()'s (evaluateSpan)
  struct StoredEnd {  // a span's rolling end with a store (PathPoint::roll_store), as evaluated
    int body;          // index into bodies_
    int row, entry;    // its row and its body's entry in that row
    Vec3 pays;         // world unit axle, in the sense a turn pays out
    double left;       // the turn (rad) in that sense that pays out the rest of its store
  };
  std::vector<StoredEnd> stored_ends_;  // the last evaluate()'s (evaluateSpan)
  struct StiffenedMove {  // a body whose translation stiffenMoves() scaled, and its W before
    int body;
    double inv_mass;
    Mat3 inv_mass_x;
  };
  std::vector<StiffenedMove> stiffened_moves_;
  struct Stiffened {  // a body whose turn stiffenTurns() scaled, and its W before
    int body;
    Mat3 inv_inertia;
    double inv_axial;
  };
  std::vector<Stiffened> stiffened_turns_;
  struct Secant {  // an entry whose fixed end stiffenTurns() gave its turn's secant, and its gradient before
    int entry;
    Vec3 ang;
  };
  std::vector<Secant> secants_;
  std::vector<int> secant_of_;  // per entry: its index in secants_, or -1
  /// The turn (rad) the step (dphi_ + shift_phi_, times `omega`) gives
  /// fixed end `f`'s body, and in `most` the most it may be (line_up.h;
  /// the turn itself below trustedStepTurn() in a substep of `h` s).
  double turnPast(const FixedEnd& f, double omega, double h, double& most) const;
  /// The turn (rad) the step gives stored end `f`'s body in the sense that
  /// pays out (negative: winds on).
  double storeTurn(const StoredEnd& f, double omega) const {
    return f.pays.dot(omega * (dphi_[f.body] + shift_phi_[f.body]));
  }
  /// Where the step turns a stored end past its store, gives the end's
  /// gradient in its row the turn's secant share: r a radian for the
  /// store's turn, then r sin(past) as the point where the cable ends
  /// turns on with the body (solvePoint's tie), most at its line-up a
  /// quarter turn on; past that, its body's turn is scaled to stop there
  /// (stiffenTurns' rule). With one iteration a substep the step itself
  /// is what the bodies keep: modelled as all rolling, a 2 kg spool paid
  /// 4.5 cm out past its store under 100 kg and the next substep yanked
  /// it back (174 J at 1 x 1).
  bool stiffenStores(double omega);
  /// Scales the turn of `body`, whose end's entry `own` in row `r` the step
  /// turns by `angle` (rad), so that the row alone turns it at most `most`
  /// (stiffenTurns, stiffenStores).
  void stopTurn(int body, int r, const Entry& own, double most, double angle);
  /// Entry `entry`'s gradient as its row's model had it, kept the first
  /// time a round gives it a secant (restoreTurns puts it back); none where
  /// the turn keeps to its model: not `past` its line-up and its secant
  /// within `slack` of 1 (stiffenTurns, stiffenStores).
  std::optional<Vec3> modelGradient(int entry, double secant, bool past, double slack);
  /// weigh()s every entry of a body whose turn a round scaled.
  void reweighStiffened();
  /// Where the step turns a fixed end's body by more than trustedStepTurn()
  /// in a substep of `h` (s), gives the end's gradient in its row the
  /// turn's secant share (turnSecant: what the turn gains of its length,
  /// not what the tangent promised), and scales the angular W of a body whose step turns the end
  /// past its line-up, as Gauss-Seidel's visit does (path_constraint.cpp):
  /// the end's row then turns it at most to there, the rest of its
  /// correction going to the row's other bodies. Returns whether any
  /// changed; restoreTurns() puts the gradients and W back.
  bool stiffenTurns(double omega, double h);
  void scaleTurn(int body, double scale);
  void restoreTurns();
  /// Stiffens the translation of the body that the step (dx_ + shift_x_,
  /// times `omega`) moves the more of a span's two fixed ends, where it
  /// moves them past their closest approach, by the share of the step
  /// that reaches it; returns whether any changed. restoreMoves() puts W
  /// back.
  bool stiffenMoves(double omega);
  void restoreMoves();
  /// The step's motion (m) of the point at world arm `arm` on body slot
  /// `body` (none for -1), its turn to first order.
  Vec3 pointStep(int body, const Vec3& arm, double omega) const;
  /// The share (0, 1] of the step that turns no fixed end past its line-up
  /// (turnPast, in a substep of `h` s).
  double lineUpShare(double omega, double h) const;
  std::vector<Entry> start_;      // entries_ at the substep's start (linearizeAtStart); empty: Projection::End
  std::vector<Mat3> start_curvature_;  // ... and their curvature_
  bool at_start_ = false;         // evaluating at the start poses
  bool first_iteration_ = false;  // the substep's first iterate() is next
  std::vector<char> use_start_;   // per row: moves along start_ (chooseStartRows)
  std::vector<Pair> pairs_;
  std::vector<Slot> slots_;  // other_row >= rows_.size(): a hub's unknown
  struct Hub {
    int body;   // index into bodies_
    int dofs;   // 6, or 1 for a rotor
    int first;  // its first unknown (rows_.size() + ...)
    int first_leaf, leaves;  // rows that move it alone: leaf_entries_
  };
  struct Coupling {  // J_h: the entry's gradient along a hub's dof
    int entry, hub, dof, slot;
  };
  struct MassSlot {  // -M_h(i, j), i <= j
    int hub, i, j, slot;
  };
  std::vector<Hub> hubs_;
  std::vector<int> hub_of_;  // per index into bodies_: its hub, or -1
  std::vector<Coupling> couplings_;
  std::vector<MassSlot> mass_slots_;
  std::vector<int> position_;      // per unknown (rows, then hubs' dofs): in the elimination order
  std::vector<double> hub_motion_;  // per hub dof: the solve's dx_h
  std::vector<double> delta_;       // per row: its regularization (0 off hubs)
  std::vector<double> length_;      // per path or distance row: its length (m)
  // Per row, from a span's last evaluation in full at a substep's start
  // (Projection::End): both its ends linear (linearEnd), its path's
  // placement then (0: none to keep) and its length then (m).
  std::vector<char> linear_;
  std::vector<long long> placed_;
  std::vector<double> placed_length_;
  bool evaluated_ = false;  // this substep's first evaluation ran (in full)
  std::vector<int> leaf_entries_;   // per hub, from first_leaf: its leaves' entries
  std::vector<Mat3> hub_inertia_;   // per hub: world inertia this iteration
  std::vector<BodyId> bodies_;    // moving bodies in some row
  // Each world body's index in bodies_ (-1: none), read by slotOf(): a
  // window of world ids from body_base_ where the island's ids lie close
  // together, as a scene's machines usually do, else the (id, index)
  // pairs sorted by id. One slot per world body in each island was
  // islands x bodies: 200 MB for 4096 Atwood machines, and the time a
  // machine took grew with their number.
  BodyId body_base_ = 0;
  std::vector<int> body_index_;
  std::vector<std::pair<BodyId, int>> body_ids_;
  int slotOf(BodyId id) const;
  SparseLdlt ldlt_;
  // Per row: value, compliance term, bounds, accumulated and new lambda,
  // its state in the active set, where its lambda is mirrored, and for
  // joint rows the 6-D direction and the joint's impulse accumulators.
  enum class State : unsigned char { Free, Fixed, Off };
  std::vector<double> C_, alpha_, lo_, hi_, lambda_, dlambda_;
  std::vector<double> x_, rhs_;  // right-hand side, then solution, in elimination order (every unknown)
  std::vector<char> keep_;        // per position: a row not to drop (factorAndSolve)
  // The row this pass let go along a dependency (releaseAlongDependency),
  // or -1; and whether this solve may still let one go (not once a release
  // had to be undone: solveActiveSet).
  int released_ = -1;
  bool may_release_ = true;
  std::vector<State> state_;
  std::vector<char> pulled_;  // per row: its lambda was < 0 when the last substep ended
  // Per row: +1 (-1) when its lambda ended the last iteration at a finite,
  // non-zero upper (lower) bound, else 0 (warmStartCaps); and whether this
  // solve started it held there.
  std::vector<signed char> at_cap_, at_cap_start_;  // ... and as this substep started
  std::vector<char> warm_;
  bool settled_ = false;  // the last solveActiveSet ended with no change, not out of passes
  // The settled solve whose held rows that ask to come off their bound
  // are being solved again free (solveActiveSet), and the most one asked.
  struct HeldSolve {
    std::vector<double> dlambda, hub_motion;
    std::vector<State> state;
    double violation = 0.0;
  } held_;
  std::vector<int> drive_of_;  // per limit row: the row of its coordinate's drive, or -1
  std::vector<double*> mirror_;
  std::vector<Eigen::Matrix<double, 6, 1>> dir_;  // joint_rows::Vec6
  std::vector<Vec3*> linear_a_, angular_a_;
  std::vector<double> full_;  // the assembled matrix values
  // Per body: its rotation and W this iteration (a rotor's world axle and
  // 1 / I about it instead of the inverse inertia), and its motion.
  struct BodyFrame {
    BodyState* state = nullptr;  // set by prepare()
    Mat3 R = Mat3::Identity(), inv_inertia = Mat3::Zero();
    bool rotated = false;  // R is this iteration's (a rotor's is taken when read: rotation())
    Vec3 axle = Vec3::Zero();
    double inv_mass = 0.0, inv_axial = 0.0;
    // (m I + |K_x|)^-1 where the spans' sideways stiffness is kept
    // (newtonStep); W is inv_mass otherwise.
    Mat3 inv_mass_x = Mat3::Zero();
    bool stiff_x = false;
    double axial_inv0 = 0.0, axial_inertia = 0.0;  // a rotor's 1 / I_u and I_u, as the substep starts
    // The body's solve_turn when last evaluated, and its turn since then.
    Vec3 evaluated_turn = Vec3::Zero(), turned = Vec3::Zero();
    // Its position and axle at the last substep's first evaluation, and
    // whether this one's are the same (the axle to 1e-15: it turned about
    // it): keepsSpan.
    Vec3 placed_x = Vec3::Zero(), placed_axle = Vec3::Zero();
    bool still = false;
    double turn_scale = 1.0;  // a hub's angular W scaled by stiffenTurns(), its inertia divided
  };
  std::vector<BodyFrame> frames_;
  std::vector<Vec3> dx_, dphi_;
  // Per body: what this solve moved it in the substep so far, and the
  // motion dx0 = -W~ g of Newton's residual (newtonStep).
  std::vector<Vec3> moved_x_, moved_phi_, shift_x_, shift_phi_;
  std::vector<double> last_lambda_;  // per row: lambda as the last substep ended
  bool first_solve_ = false;          // this iteration is the substep's first
  bool lifted_ = false;               // startPoint moved a body: Newton's residual is not 0 at the first solve
  double last_h_ = 0.0;               // the last substep's h (s); 0: none yet
  std::vector<Vec3> start_x_;         // per body: where startPoint put it from x~ this substep (m)
  std::vector<Vec3> start_phi_;       // ... and turned it from q~ (rad)
  std::vector<Vec3> last_a_, last_alpha_;  // per body: the rows' acceleration in the substep before (m/s^2, rad/s^2)
  bool last_lifted_ = false;               // ... which startPoint lifted (else last_a_ says nothing)
  std::vector<Mat3> stiffness_;  // per body: sum of lambda d2C/dtheta^2 this iteration
  std::vector<Mat3> lateral_stiffness_;  // per body: sum of |lambda| d2C/dx^2 of its span ends (bend_)
  std::vector<char> jointed_;  // per body: in a joint's rows (no lateral_stiffness_ then)
  std::vector<Mat3> world_inertia_;  // per body but rotors: its world inertia this iteration (newtonResidual)
  std::vector<double> axial_stiffness_;  // per rotor: u . stiffness_ . u (Entry::axial)
  double shift_size_ = 0.0;      // the largest |dx0|, |dphi0| (m, rad) of newtonStep
  bool stiffened_ = false;       // newtonStep added |K| to some body's W
  double last_step_ = 0.0;       // the last step's largest |dx|, |dphi| (m, rad), as solved; 0: none
  double last_rho_ = 0.0;        // the last measured ratio of a plain step's size to the one before; 0: none
  bool extrapolated_ = false;    // the last step was scaled (extrapolation())
  bool touching_ = false;        // the island has contacts (swept between its iterations)
  bool contacts_in_rows_ = false;  // every manifold of the island is rows of this solve, and no path is weighted
  bool moves_alone_ = false;     // nothing but this solver moves the island's bodies between its iterations
  bool plain_solve_ = false;     // the last iteration was the substep's first, solved with every plain W
  bool met_ = false;             // the last solve met every row (metAsSolved) or stalled: the next one ends the substep
  bool damped_ = false;          // the last evaluation damped a row (evaluatePath): metAsSolved does not predict it
  double moved_size_ = 0.0;      // the largest |moved_x_|, |moved_phi_| (m, rad) as newtonResidual last found them
  std::vector<char> reweigh_;    // per body: its W changed in newtonStep
  /// Newton's residual g = M (x - x~) - J^T lambda per body (into
  /// shift_x_, shift_phi_) and the rows' geometric stiffness K (DESIGN
  /// "Newton's residual and geometric stiffness"); sets moved_size_.
  /// Returns a bound on |dx0| = |W~ g| (m or rad) that holds for any W~ <=
  /// W: 0 at the substep's first solve (g = 0), else where `bounded` the
  /// bound (infinite where g is not finite), else infinity.
  double newtonResidual(bool bounded);
  /// Each body's W~ = (M + |K|)^-1 in frames_ (reweigh_: where it changed)
  /// and its motion dx0 = -W~ g, in place of g; sets shift_size_.
  void newtonStep();
  /// The substep's first iteration, for body i (frame f) with the last
  /// substep's K: W~ = (I + |K|)^-1 where an eigenvalue of K exceeds the
  /// inertia along its eigenvector (those kept), else the plain W.
  void warmStiffness(BodyFrame& f, const Mat3& K, std::size_t i);
  /// Body i's translation W~ = (m I + |K_x|)^-1 from its spans' sideways
  /// stiffness (lateral_stiffness_: the last substep's in the first
  /// iteration), the eigenvalues above its mass kept, else the plain W.
  void stiffenLateral(BodyFrame& f, std::size_t i);
  /// Whether every row's gradient stays as it is while the bodies move:
  /// spans linear in the solve's turns (linear_) and a rotor's hinge rows.
  bool linearRows(const World& world) const;
  /// Aitken's extrapolation of the step solveActiveSet left (dx_ + shift_x_,
  /// dphi_ + shift_phi_, dlambda_): scales dlambda_ and returns the factor
  /// omega >= 1 for the bodies' step (1: a plain step).
  double extrapolation();
  /// After a plain solve of linear rows (plain_solve_), with nothing but
  /// this solver to move the bodies before the next iteration: whether
  /// every row is met at C + J dx, its value once the bodies made the motion
  /// solved, which is what the next evaluation would find (to rounding).
  /// Stricter than converged() on that evaluation: a row counts as met only
  /// within `tolerance` or held at a bound it presses against, and no
  /// one-sided row violated, so the next iteration is skipped only where it
  /// would end the substep anyway.
  bool metAsSolved(double tolerance) const;
  /// For an iteration that solves: the entries weighed with W~, and C_ +=
  /// J dx0, the rows as the residual's motion leaves them.
  void shiftValues();
};

inline int DirectSolver::slotOf(BodyId id) const {
  if (!body_ids_.empty()) {
    const auto it = std::lower_bound(body_ids_.begin(), body_ids_.end(), std::pair{id, -1});
    return it != body_ids_.end() && it->first == id ? it->second : -1;
  }
  // kWorldBody and ids below the window wrap to above it.
  const auto k = static_cast<std::size_t>(static_cast<unsigned>(id - body_base_));
  return k < body_index_.size() ? body_index_[k] : -1;
}

}  // namespace reeve
