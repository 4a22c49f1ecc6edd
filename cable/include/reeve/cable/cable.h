// Cables made of links joined by cable joints: paper sec. 3 (Alg. 1:
// rolling, attachment and pinhole links, 2D and 3D cable planes) and
// sec. 4 (Alg. 2: stored cable, hybrid links and spools, merge and split),
// open cables and closed ones (belts).
#pragma once

#include <atomic>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "reeve/cable/section.h"
#include "reeve/engine/world.h"

namespace reeve {

/// How the cable meets a body (paper sec. 3.3, 4.1).
enum class LinkType {
  Attachment,  ///< tied to a fixed body-local point
  Rolling,     ///< wraps the body's cross-section in its cable plane
  Pinhole,     ///< slides through a fixed body-local point
  Hybrid,      ///< an end on a spool: rolls while stored cable >= 0, else tied
};

/// One link as the user describes it.
/// - `point` (m, body-local): the tie point of attachments and pinholes.
/// - Rolling and hybrid links wrap `section`, a circle or convex polygon in
///   the body's cable plane: the plane z = `plane_offset` (m) of the body's
///   local frame (a cylinder's axis is local z). Without a section the
///   body shape's own cross-section in that plane is used. `orientation` +1: the cable
///   travels counter-clockwise about the plane normal (local +z) as one
///   walks along the cable, -1 clockwise (paper Fig. 3).
/// - `stored` (m): cable stored on the body at the start (Alg. 2 line 2);
///   default: the wrapped arc for interior links, 0 for cable ends. A spool
///   is a rolling or hybrid end link with stored cable.
/// - `active` false: an interior rolling link the cable does not touch yet;
///   it is split in when a span crosses its section (paper sec. 4.2),
///   wrapped on the side the span met it from: `orientation` is then
///   taken from the geometry (a span met with the centre on its left goes
///   round counter-clockwise), whatever was given. Only a span passing
///   within a section radius of the cable plane, or within the body's
///   thickness, meets it, and is wrapped where it met it (Link::depth: a
///   sphere or hull by its own section there).
/// - `mu`: friction coefficient between cable and body, on interior rolling
///   links and pinholes (beyond the paper). Unset: a rolling link never
///   slips (the paper's rolling), a pinhole is frictionless. While the
///   tensions on the two sides stay within the capstan bound T_tight /
///   T_slack <= exp(mu theta) (theta the wrap angle: stored cable / radius
///   on a circle, the turn of the cable at a pinhole) the cable sticks;
///   beyond it, it slides with the ratio on the bound until the slip stops.
///   0: always slides with equal tensions (an ideal frictionless pulley of
///   finite radius, the wrapped arc counted in the length).
struct LinkDef {
  BodyId body = 0;
  LinkType type = LinkType::Attachment;
  int orientation = 1;
  Vec3 point = Vec3::Zero();
  Section section;
  double plane_offset = 0.0;
  std::optional<double> stored;
  bool active = true;
  std::optional<double> mu;

  /// A tie point `point` (m, body-local) on `body`.
  static LinkDef attachment(BodyId body, const Vec3& point) {
    LinkDef d;
    d.body = body;
    d.point = point;
    return d;
  }
  /// A hole at `point` (m, body-local) of `body` the cable slides through.
  static LinkDef pinhole(BodyId body, const Vec3& point) {
    LinkDef d = attachment(body, point);
    d.type = LinkType::Pinhole;
    return d;
  }
  /// Wraps `body`'s own section with `orientation` (+1 ccw, -1 cw).
  static LinkDef rolling(BodyId body, int orientation) {
    LinkDef d;
    d.body = body;
    d.type = LinkType::Rolling;
    d.orientation = orientation;
    return d;
  }
  /// A spool end: rolls with `stored` m of cable (m), then is tied.
  static LinkDef hybrid(BodyId body, int orientation, double stored) {
    LinkDef d = rolling(body, orientation);
    d.type = LinkType::Hybrid;
    d.stored = stored;
    return d;
  }
};

/// A cable through `links` in order. Open cables need at least two links
/// and end in attachments, rolling links or hybrid links (spools); closed
/// cables (belts) join the last link back to the first and need at least
/// two links, none hybrid. `rest_lengths` (m), if given, has one value per
/// joint (links - 1 open, links closed) and sets the initial slack; empty
/// means taut at the start. `compliance` (m/N) is that of the whole cable
/// at its initial total length (spans plus stored cable, all of which
/// would stretch if it hung free); each free span gets the share of its
/// rest length, so strain, not span count, sets the stretch; cable stored
/// on a body does not stretch (0: inextensible).
///
/// `damping` (N s/m, >= 0; only with compliance > 0) is the whole cable's
/// at that length likewise: a dashpot beside its spring, pulling with
/// damping x its rate of stretch. Dashpots in series, a span of rest length
/// L of a cable of total length L0 gets damping x L0 / L, so the damping's
/// time, compliance x damping, is the same in every span (a material's).
///
/// `breaking_tension` (N, > 0; infinite: never): a span whose tension
/// passes it parts (beyond the paper; CableSystem::update).
struct CableDef {
  std::string name;
  std::vector<LinkDef> links;
  bool closed = false;
  double compliance = 0.0;
  double damping = 0.0;
  std::vector<double> rest_lengths;
  double breaking_tension = std::numeric_limits<double>::infinity();
};

/// Cable wound onto a link at one strain: `rest` m of rest length covering
/// rest + stretch m of the surface (elastic cables only).
struct WoundLayer {
  double rest = 0.0, stretch = 0.0;
};

/// A link in the solver. `attached` marks a hybrid link that has run out of
/// cable and acts as an attachment at `point`.
struct Link {
  BodyId body = 0;
  LinkType type = LinkType::Attachment;
  int orientation = 1;
  Vec3 point = Vec3::Zero();
  Section section;
  double plane_offset = 0.0;
  /// How the section lies along the body's axis, for a span split onto the
  /// link away from its cable plane (CableSystem::update):
  /// - Uniform: the same at every depth (a given section; a box's or
  ///   cylinder's own: a bar, a peg). Met more than a section radius from
  ///   the plane, where the span passes along the body, it is wrapped in
  ///   the plane where it met it: `plane_offset` moves there (in the link's
  ///   plane the wrap was longer than the span by the detour: energy made).
  /// - Slice: the body's own, which changes with depth (a sphere, a hull).
  ///   Met off the plane, it is wrapped in the plane where it met it, by
  ///   the body's section there: `plane_offset` and `section` move there.
  enum class Depth { Uniform, Slice };
  Depth depth = Depth::Uniform;
  double stored = 0.0;  // m of rest length
  /// An elastic cable winds on at the strain of the span it comes from and
  /// unwinds last on, first off, each layer at the strain it was wound
  /// with (the cable does not slip on the wheel). The layers (the last
  /// wound at the back) hold the top of `stored`; the rest of it lies
  /// below them unstretched. stored_stretch: their stretch, summed (m).
  std::vector<WoundLayer> layers;
  double stored_stretch = 0.0;
  /// The surface (m) the wound cable covers.
  double arc() const { return stored + stored_stretch; }
  /// Winds `rest` m of cable stretched by `stretch` m onto the top.
  void windOn(double rest, double stretch);
  /// Unwinds `arc` m (> 0) of surface from the top; returns the rest
  /// length that came off. Below the layers it is unstretched, and past
  /// the stored cable `stored` goes negative (a link run empty).
  double windOff(double arc);
  /// Takes `rest` m of rest length off the top (a span's deficit).
  void takeRest(double rest);
  /// No cable wound: stored and its layers 0.
  void unwindAll();
  bool active = true;
  bool attached = false;
  /// Friction coefficient (LinkDef::mu); infinite: never slips.
  double mu = std::numeric_limits<double>::infinity();
  /// The cable slides here in this substep: one path with its neighbours'
  /// spans (always for mu = 0; by the capstan bound for mu > 0).
  bool slipping = false;
  /// +1: sliding forward (towards the next link), the tension higher ahead;
  /// -1 backward. Sets the capstan ratio's sense while slipping.
  int slip_sense = 0;
  /// Cable that slid forward over the body's surface (or through the hole)
  /// per second (m/s) in the substep before the last update; 0 while it
  /// sticks.
  double slip_speed = 0.0;
  double slip_speed_before = 0.0;  ///< in the substep before (m/s)
  /// While inactive: the signed distance (m, + where the centre lies to
  /// the right of the span in the cable plane) of the section's centre
  /// from the span passing over it, at the last update; NaN before there
  /// is one. A span that jumps past the whole section in one substep
  /// changes its sign (the swept split); its sign before the split is the
  /// side the span met the section from, which sets `orientation` there.
  double side = std::numeric_limits<double>::quiet_NaN();
  /// While a hybrid is tied: the bearing (rad, in its cable plane, about
  /// its section's centre, in the body's frame) of its span's other end at
  /// the last update; NaN before there is one. Less the body's turn, its
  /// change is the tie point's travel round the section relative to the
  /// span, whose sense says which tangent point the tie point passed when
  /// it is hidden (CableSystem::switchHybrids).
  double tie_bearing = std::numeric_limits<double>::quiet_NaN();

  /// True when the cable wraps the body's section here (rolling, or a
  /// hybrid that still has cable).
  bool rolls() const {
    return type == LinkType::Rolling || (type == LinkType::Hybrid && !attached);
  }
  /// True when the cable passes this link within one path (a pinhole or
  /// rolling link it slides over) rather than being held by it.
  bool slides() const { return active && slipping; }
};

/// The span leaving link j and arriving at the next active link `to`, with
/// body-local anchors (tangent points on rolling links, tie points
/// otherwise) and the cable it holds (rest length). Spans joined through
/// pinholes form a run that the World solves as one path constraint, so
/// they share one tension (times `weight`, the capstan ratio of friction
/// links slipping between it and the run's tightest span, which has 1);
/// `path` is this span's path when it starts a run, `run` the joint whose
/// path carries it. Disabled while link j is inactive, and for good once
/// `parted`: the cable broke here, or a free end ran off a link the span
/// left from (its cable went to the links either side as loose cable,
/// stored there: `tail_a` (m) to link j, `tail_b` to link `to`).
struct CableJoint {
  int to = 0;
  Vec3 local_a = Vec3::Zero();
  Vec3 local_b = Vec3::Zero();
  double rest_length = 0.0;  // m
  PathId path = 0;
  int run = 0;
  double weight = 1.0;
  bool parted = false;
  double tail_a = 0.0, tail_b = 0.0;  // m
  /// The span ran out: a wheel at an end wound more cable than it held
  /// (SpanRunsOut), and it has not held cable since.
  bool ran_out = false;
  /// The span ran out between a wheel and a tie point, which jammed there
  /// (CableSystem::jam): no row; a ball joint holds the tie point on the rim.
  bool jammed = false;
};

/// A link switch, merge or split (paper Alg. 2), or a break, for logs.
/// Break: the span leaving `link` parted at `tension` (N). RunsOff: a free
/// end (after a break) left `link`, which could not hold it: a pinhole or
/// a wrap it slides over, or a wheel whose stored cable ran out; the span
/// beyond goes slack for good. SpanRunsOut: the span leaving `link` ran out
/// of cable, a wheel at its end winding more than it held (a tie point
/// reached the wheel's rim, or two wheels met; issue 28, item 9). A tie
/// point at the rim jams there (CableJoint::jammed: a ball joint to the
/// wheel); otherwise the wheel slips on the cable.
struct CableEvent {
  enum class Kind { HybridRunsOut, HybridRollsAgain, Merge, Split, Break, RunsOff, SpanRunsOut };
  Kind kind;
  double time_s;  // end of the substep in which it happened; a break: of the solve that overloaded it
  int cable;
  int link;
  int orientation;  // the link's orientation after the event
  double tension = 0.0;  // N, breaks only
};

/// Name of an event kind ("hybrid_runs_out", "hybrid_rolls_again", "merge",
/// "split", "break", "runs_off", "span_runs_out").
const char* eventName(CableEvent::Kind kind);

/// A command to a winch from simulated time `from_s` (s) on: speed mode
/// (`speed`, m/s of cable; > 0 hauls in, < 0 pays out) or, with
/// `target_stored` (m, >= 0), length mode: towards that much stored cable
/// at the winch's max_speed, then hold.
struct WinchCommand {
  double from_s = 0.0;
  double speed = 0.0;
  std::optional<double> target_stored;
};

/// A winch at an end of an open cable (beyond the paper). The end link is
/// an attachment the winch reels cable into and pays it out of, keeping
/// what it holds as that link's stored cable. It follows `speed` and
/// `target_stored` (a WinchCommand's), and then each of `schedule`'s
/// commands from its time on (at the first substep starting within half
/// a substep of it; times increasing). Either way at most `max_speed` and
/// with a pull of at most `max_pull` (N): asked for more, the winch stalls
/// and pays out under the load, which then moves as that force says.
struct WinchDef {
  bool at_start = false;  ///< the winch is at the first link; false: the last
  double speed = 0.0;     ///< m/s
  double max_speed = std::numeric_limits<double>::infinity();  ///< m/s, > 0
  double max_pull = std::numeric_limits<double>::infinity();   ///< N, > 0
  std::optional<double> target_stored;                          ///< m, >= 0
  std::vector<WinchCommand> schedule;
};

/// Cables joined into one length constraint (beyond the paper: MuJoCo's
/// spatial tendon branches, `<pulley divisor>`, an ideal floating pulley
/// block): sum_b L_b / divisor_b <= sum_b R_b / divisor_b over the cables'
/// path lengths L_b and rest lengths R_b, cable b pulling with
/// T / divisor_b. Divisor 2 on two cables hung from a third: the third
/// lifts twice what each of them does, and takes in half what they pay
/// out together. Each cable is one run at all times: open, tied at both
/// ends (attachments), sliding over every link between (pinholes, and
/// rolling links with mu 0), without a winch or a breaking tension, in
/// no other junction, and touching a moving body.
struct JunctionDef {
  std::string name;
  std::vector<int> cables;
  std::vector<double> divisors;  ///< one per cable, > 0 and finite
};

/// A junction in the solver: its cables, each one's scale (1 / divisor),
/// and the path constraint of all their points (PathConstraint::scales).
/// The cable moves between its cables as they move, each cable keeping
/// equal strain (their rest lengths in proportion to their lengths): each
/// cable's total length changes so, sum_b total_b / divisor_b not.
struct Junction {
  std::string name;
  std::vector<int> cables;
  std::vector<double> scales;
  PathId path = 0;
  double total_length = 0.0;  ///< m: sum_b scale_b x total length_b, as made or set
  int cables_last = -1;       ///< the highest of `cables`: the last to update in a substep
};

struct Cable {
  std::string name;
  /// The junction it is a branch of (an index into junctions()), or -1.
  int junction = -1;
  double junction_scale = 1.0;  ///< 1 / its divisor there
  bool closed = false;
  double compliance_per_m = 0.0;  // 1/N: span compliance = this x rest length
  double damping_times_m = 0.0;   // N s: span damping (N s/m) = this / rest length
  double total_length = 0.0;      // m: rest lengths plus stored cable, as made or set
  std::vector<Link> links;
  std::vector<CableJoint> joints;  // joints[j] leaves links[j]
  std::optional<WinchDef> winch;
  // m the winch reeled in before the last solve, whose pull (known once
  // that solve is done) times it is the winch's work (winchWork).
  double reeled = 0.0;
  // m of cable the winch fed into its span in the last update (paid out,
  // or negative reeled in, stretched by the last pull): PathConstraint::fed
  // of the span's run.
  double fed = 0.0;
  /// The rest lengths CableDef::rest_lengths gave (m, per joint), kept only
  /// where spans joined through a frictionless pinhole or wrap share one
  /// rest length in proportion to their lengths and so read otherwise at
  /// load (issue 28, item 10: a scene warning says so); else empty.
  std::vector<double> given_rest_lengths;
  double breaking_tension = std::numeric_limits<double>::infinity();  // N
  bool broken = false;  // a span has parted
};

/// A break of the cable bookkeeping's invariants, or a rigid run held
/// stretched (CableSystem::firstBreach).
struct CableBreach {
  double time_s = 0.0;        ///< the update's time stamp (s)
  std::string what;           ///< invariantViolation()'s message
  int cable = -1;             ///< the cable whose bookkeeping broke
  /// Its rolling end link (of an open cable) paid out more cable than it
  /// stored: the scene's spool ran out, not the solver (a hybrid link
  /// would have tied the cable there, Alg. 2 l. 12-13).
  bool spool_ran_out = false;
  /// A rigid run through bodies that no constraint moves (static, or
  /// kinematic: moved by their schedules), with no friction link at its
  /// ends that could let it slip, was stretched further than it was when
  /// it came to be so held (where the cable has no breaking tension; one
  /// with parts there instead): nothing can pull it in, and a rigid cable
  /// does not stretch (a kinematic drum hauling over a wheel fixed in the world,
  /// which holds the cable without slipping). Left alone, the stretch came
  /// back as a yank the moment a moving body joined the run (a merge): 45
  /// kJ in a frame. `stretch`: its length less its rest length then (m).
  bool held_stretched = false;
  double stretch = 0.0;
  BodyId fastest = -1;        ///< the rolling body that turned furthest in that update
  double fastest_turn = 0.0;  ///< its turn in that update (rad, signed)
  /// The rolling body that moved furthest since the update before, for its
  /// size: its move (m) and its size for the tangents (m: the radius of a
  /// circle as long round as its smallest cable section). A wheel carried
  /// further than its own size in one substep (18,000 g on a pendulum)
  /// leaves the tangents nothing to follow, as one turned past half a turn.
  BodyId farthest = -1;
  double farthest_move = 0.0;
  double farthest_radius = 0.0;
};

/// All cables of a World. Registers a substep hook on construction that
/// runs the cable update before each position solve, so it must outlive
/// the World's stepping and is neither copied nor moved.
class CableSystem {
 public:
  explicit CableSystem(World& world);
  CableSystem(const CableSystem&) = delete;
  CableSystem& operator=(const CableSystem&) = delete;

  /// Adds a cable at the World's current poses: tangent points, initial
  /// rest lengths (taut unless given) and stored cable. Throws
  /// std::invalid_argument, leaving the World untouched, for a definition
  /// that cannot be built (too few links, unknown body, orientation not
  /// +-1, a rolling link without a section, a pinhole or hybrid where it
  /// cannot be, wrong rest_lengths size, negative values, no tangent
  /// between adjacent links).
  int addCable(const CableDef& def);

  /// One substep of bookkeeping from the current poses: first breaks (a
  /// span the last solve pulled past the breaking tension parts, beyond
  /// the paper), the winch's reeling, then tangent points,
  /// rest lengths and stored cable (Alg. 1 l. 2-7, Alg. 2 l. 8-9), pinhole
  /// sliding (Alg. 1 l. 8-16), hybrid switches (Alg. 2 l. 11-22), merges and
  /// splits (Alg. 2 l. 23-28). `time_s` stamps the events. `h` (s) is the
  /// substep the World just integrated: each body turned by h omega then,
  /// and by its last solve's turn (BodyState::solve_turn), however many
  /// turns that is, and the cable it pays out counts them all. With h = 0
  /// (an update between steps) only the last solve's turn is counted; a
  /// body turned by hand must have turned less than half a turn about its
  /// cable plane's normal since the last update. Within a step the World
  /// runs it in parts (World::IslandHook): beginUpdate, updateIsland for
  /// what is on no island and then for each island (side by side on the
  /// World's threads), endUpdate.
  void update(double time_s = 0.0, double h = 0.0);

  /// Joins cables into one length constraint (JunctionDef). Throws
  /// std::invalid_argument, leaving the system untouched, for fewer than
  /// two cables, an unknown or repeated cable, a divisor not > 0 and
  /// finite, or a cable that cannot be a branch (JunctionDef). Returns its
  /// index.
  int addJunction(const JunctionDef& def);
  /// Why cable c cannot be a junction's branch (JunctionDef: "is closed",
  /// "has a winch", ...), or "" if it can.
  std::string branchProblem(int c) const;

  const std::vector<Cable>& cables() const { return cables_; }
  const std::vector<Junction>& junctions() const { return junctions_; }
  const World& world() const { return world_; }
  /// Events since the last takeEvents().
  std::vector<CableEvent> takeEvents();

  /// Tension (N), rest length (m) and current length (m) of joint j of
  /// cable c; all 0 for a disabled joint.
  double tension(int c, int j) const;
  double restLength(int c, int j) const;
  double length(int c, int j) const;
  /// Rest length (m) of joint j and cable stored (m) on link k of cable c
  /// as of the poses now: what the last update left plus what the next
  /// will pay in or out for the turn the last solve made (Alg. 1 l. 4-5),
  /// so that a frame's output agrees with its poses (issue 28, item 11:
  /// they lagged a substep). restLength() and Link::stored are the
  /// bookkeeping's own, as of the last update.
  double restLengthNow(int c, int j) const;
  double storedNow(int c, int k) const;
  /// Length (m) of joint j of cable c between the tangent points of the
  /// poses now (the next update's), to compare with restLengthNow: length()
  /// measures between the last update's anchors, which a wheel a solve
  /// turned by radians has carried round its rim.
  double lengthNow(int c, int j) const;
  /// Whether joint j of cable c currently exists (its link is active, it
  /// has not parted, and it is not jammed: CableJoint::jammed).
  bool jointEnabled(int c, int j) const;
  /// Slip speed (m/s) of link k of cable c: cable sliding forward (towards
  /// link k + 1) over the body or through the hole, measured as the last
  /// substep started, over the one before it (the update runs before the
  /// solve); 0 where it sticks or rolls.
  double slipSpeed(int c, int k) const { return cables_[c].links[k].slip_speed; }
  /// World positions (m) of the tangent points of joint j of cable c;
  /// meaningless while the joint is disabled (see jointEnabled()).
  Vec3 startPoint(int c, int j) const;
  Vec3 endPoint(int c, int j) const;
  /// Rest lengths plus stored cable of cable c (m): conserved by update().
  double totalLength(int c) const;
  /// The bookkeeping's invariants after an update, or what breaks them: no
  /// active span's rest length and no rolling link's stored cable below 0
  /// (a spool's cable running out and a link emptying are events that end
  /// there, Alg. 2), and each cable's total length what it was made with
  /// or set to (setRestLength); a junction's cables trade theirs, keeping
  /// the junction's (Junction::total_length). Rounding is allowed 1e-9 of
  /// the total.
  std::optional<std::string> invariantViolation() const;
  /// The first update() after which invariantViolation() held something
  /// (checked after every update, in every build), or nothing. Reachable
  /// from a scene, not only from a bug: before issue 29, a load hauled
  /// into the last wheel of hilbert3 run past its duration (dragged on
  /// through the wheels; it jams now) and a direct solve that had to turn
  /// a wheel radians (its span ends then swung round the rim). Runners
  /// stop there, as at World::firstNonFinite().
  const std::optional<CableBreach>& firstBreach() const { return breach_; }
  /// Sets the rest length (m, >= 0) of joint j of cable c: a winch paying
  /// out or hauling in cable, or slack given after set-up.
  void setRestLength(int c, int j, double rest_length_m);
  /// Puts a winch on cable c, or changes its command (a controller may
  /// call this between steps). Throws std::invalid_argument for a closed
  /// cable, an end link that is not an attachment, or values out of range
  /// (max_speed, max_pull > 0; |speed| <= max_speed; target_stored >= 0;
  /// all but the maxima finite; schedule times finite and increasing).
  void setWinch(int c, const WinchDef& winch);
  /// The pull (N) of cable c's winch over the last substep: the tension of
  /// the span it reels; 0 without a winch.
  double winchPull(int c) const;
  /// Work (J) the winches put into the machine since the system was made
  /// (issue 28's energy ledger): per substep, the cable reeled in before
  /// the solve (as stretched by that pull: rest length x (1 + strain))
  /// times the pull that solve held it with (negative paying out under
  /// load: a winch braking).
  double winchWork() const;
  /// Work (J) cable friction took out since the system was made (the
  /// energy ledger): per substep, at each slipping friction link, the cable
  /// that slid over it times the tension it gained across it, as the last
  /// solve left them, where that is a loss (friction that pushed the slip
  /// along is not credited: the ledger shows its energy as created). The
  /// last solve's is counted too, which the next update will book. Under
  /// the start projection (World::ledgerLag) it holds half of the last
  /// substep's share: its slip read at the substep's start.
  double frictionLoss() const;
  /// Elastic energy (J) of the stretched cable wound on the links (the
  /// energy ledger): stored_stretch^2 / (2 compliance_per_m x stored) per
  /// link. Spans' elastic energy is the World's (their path constraints).
  double storedElasticEnergy() const;

 private:
  /// update()'s parts. beginUpdate: the cables and rolling bodies sorted
  /// by the World's islands. updateIsland: the turns of island `island`'s
  /// rolling bodies and its cables' updates (-1: those on no island).
  /// endUpdate: what the cables' updates give the whole, in cable order
  /// (events, friction, winch work, jams), and the invariants' check.
  void beginUpdate(double h);
  /// `substep`: its index in the step (0 for an update by hand). Returns
  /// whether it left news for endUpdate.
  bool updateIsland(int island, double time_s, double h, int substep);
  void endUpdate(double time_s);
  /// turn_[b]: how far (rad, unwrapped) each rolling body b of island
  /// `island` turned about its cable plane's normal (local z) since the
  /// last update.
  void measureTurns(int island, double h, int substep);
  /// Whether joint j keeps the tangent points of the last update
  /// (FixedSpan: world points a, b): its links roll on circles about axles
  /// that stay put, and both bodies stayed in place since.
  bool keepsTangents(const Cable& cable, int c, int j) const;
  /// Body b's turn (rad, unwrapped) about its cable plane's normal since
  /// the last update, counting `spin` (rad) as known whole turns.
  double turnSinceUpdate(BodyId b, double spin) const;
  /// Cable (m) joint j's two ends would pay into its span for the turns
  /// since the last update: {leaving end, arriving end} (0 for ends that
  /// do not roll); nullopt without tangents.
  std::optional<std::pair<double, double>> pendingPayOut(const Cable& cable, int j) const;
  void updateJoint(Cable& cable, int c, int j, double time_s);
  /// Span j of cable c ran out: a tie point drawn into its wheel jams
  /// there (cable_jam.cpp). Returns whether it jammed; its ball joint is
  /// added after the cables' updates (addJamJoints).
  bool jam(Cable& cable, int c, int j);
  /// A split put a tie point that a jam's ball holds on wheel `mid`'s rim
  /// (carried past its tangent point and back) at either end of the new
  /// spans: the span between them jams again (cable_jam.cpp).
  void rejamSplit(Cable& cable, int c, int j, int mid);
  /// Span j of cable c joins a tie point and a pinhole: where the tie
  /// point has reached the hole (or passed it within the substep), it
  /// jams there likewise, and the pinhole holds the cable from then on.
  bool jamAtPinhole(Cable& cable, int c, int j, double time_s);
  /// The ball joints of this update's jams, in cable order; a span whose
  /// joint the World refuses does not jam.
  void addJamJoints(double time_s);
  /// One cable's part of update(): what it gives the whole goes to
  /// updates_[c], as islands' cables update side by side (updateIsland).
  bool updateCable(int c, double time_s, double h);  // whether it left news (CableUpdate::news_at)
  /// The winch's substep (WinchDef) of `h` (s) starting at `start_s`: what
  /// it paid out stalled in the last solve, then what it reels in this one.
  void reel(Cable& cable, double start_s, double h);
  /// The winch's link and the joint of the span it reels.
  std::pair<int, int> winchSpan(const Cable& cable) const;
  /// Where cable's winch is stalled (the last solve held its run at
  /// max_pull), what it pays out at its next update for a run now `length`
  /// m long after a substep of `h` s: the stretch past the compliance's at
  /// that pull, at most what the drum holds (reel()). Nothing where it is
  /// not stalled. winchWork() counts it before that update books it.
  std::optional<double> stallSlip(const Cable& cable, double length, double h) const;
  void switchHybrids(Cable& cable, int c, double time_s, double h);
  /// How far (rad, unwrapped, + counter-clockwise in the cable plane) the
  /// tie point of hybrid link k (of span j) went round its section relative
  /// to the span over this substep's integration of `h` s: from where the
  /// last solve left both bodies to now (switchHybrids).
  double travelSinceSolve(const Cable& cable, int k, int j, double h) const;
  /// Whether hybrid link k's spool (of span j) is so light beside the body
  /// at the span's other end that its spin is the load's, which the catch
  /// at the tie point's line-up ends, not its own, which winds the cable
  /// on: its rim's mass I / r^2 (r of a circle of the section's perimeter)
  /// under kSpunByItsLoad of that body's. Measured on a yo-yo of 1 kg on a
  /// spool of 3 cm, 4 m of cable: winding on by the integration's travel
  /// (switchHybrids), a 2 g spool (rim 1e-3 of its load) made 28.7 J in a
  /// frame under Gauss-Seidel at 1 x 1 and 1.9 J under the direct solver
  /// hinged to a cart; rims of 1e-2 and 0.1 ran as without it, and
  /// hybrid.json's (1) needs it (DESIGN, "Fifty-ninth session").
  bool spunByItsLoad(const Cable& cable, int k, int j) const;
  static constexpr double kSpunByItsLoad = 0.1;
  /// Breaking (cable_break.cpp): parts the span the last solve pulled
  /// hardest past the cable's breaking tension (its lambda over `h`), then
  /// lets free ends run off what cannot hold them (releaseFreeEnds).
  void breakOverloaded(Cable& cable, int c, double time_s, double h);
  /// Parts span j: its rest length goes to its two links as loose cable,
  /// `share_a` of it to link j.
  void part(Cable& cable, int j, double share_a);
  /// A free end holds at an attachment, a hybrid end and a no-slip wheel
  /// that still stores cable; through anything else it runs off, parting
  /// the span beyond, until something holds.
  void releaseFreeEnds(Cable& cable, int c, double time_s);
  void mergeEmptyLinks(Cable& cable, int c, double time_s);
  void splitAtCrossedLinks(Cable& cable, int c, double time_s);
  /// Room in updates_[c] for the largest section of a link of cable `c`
  /// met off its plane (Link::Depth::Slice).
  void reserveSlice(int c);
  /// Runs (spans joined through sliding links), each substep: share out
  /// each run's rest length as the last solve left it and measure the slip
  /// of each sliding link over the last `h` s (settleRuns, before the
  /// substep's turns are paid out), switch friction links between sticking
  /// and slipping (switchSlips), and rebuild the runs' path constraints
  /// (buildRuns). syncRuns: the first and last, between steps. settleRuns
  /// takes the spans' lengths at the poses `now` or as the last solve left
  /// them (before this substep's integration), and returns the work
  /// friction took out (J); it writes the rest lengths and slips into
  /// `settle` (`cable` itself, a copy, or nullptr to measure only).
  void syncRuns(Cable& cable);
  double settleRuns(const Cable& cable, double h, bool now, Cable* settle) const;
  void switchSlips(Cable& cable, double h);
  /// Tension (N) of span j in the last solve of a substep of h s: its
  /// run's lambda over h^2 times its weight.
  double solvedTension(const Cable& cable, int j, double h) const;
  /// Whether sticking friction link k slips now, at the last solve's
  /// tensions (then set slipping, with its sense).
  bool startsSlipping(Cable& cable, int k, double h) const;
  /// The World's ResolveCheck: switches the friction links the solve just
  /// done carried past their bound or slid backwards; true if any.
  bool recheckSlips(double h);
  void buildRuns(Cable& cable);
  /// The junction's path from its cables' runs (built, then disabled), its
  /// rest length shared among them at equal strain (cable_junction.cpp):
  /// after a branch's runs are built between steps (syncRuns), and in a
  /// substep's update after its last branch's.
  void buildJunction(Junction& junction);
  /// The path carrying span j's tension, and the span's share of it.
  PathId tensionPath(const Cable& cable, int j) const;
  /// Rest length (m) of `arc` m of cable (along the surface) winding onto
  /// link k (> 0) from span j, or off it (< 0) into span j: on at span j's
  /// strain as the last solve left it, off at the strain the link's cable
  /// was wound with (Link::windOff). `arc` itself for an inextensible cable.
  double restOfArc(const Cable& cable, int k, int j, double arc) const;
  /// Winds `arc` m (as restOfArc) onto link k from span j, or off it into
  /// span j: moves the rest length between them and the stretch onto or
  /// off the link. Returns the rest length the span lost (< 0: gained).
  /// windLink: the link's side only.
  double wind(Cable& cable, int k, int j, double arc);
  double windLink(Cable& cable, int k, int j, double arc);
  /// Wrap angle (rad) of the cable at active link k: around a rolling
  /// link's section, through a pinhole.
  double wrapAngle(const Cable& cable, int k) const;
  /// invariantViolation() with the cable and whether a spool ran out; time
  /// and turns are left to update(). cableBreach: cable c's alone.
  std::optional<CableBreach> findBreach() const;
  std::optional<CableBreach> cableBreach(int c) const;
  /// After buildRuns: a rigid run that no body can pull in, stretched
  /// further since it was held, parts if the cable has a breaking tension
  /// (a Break event at time_s) and is recorded in updates_[c].held if not
  /// (CableBreach::held_stretched). `switched`: the runs changed in this
  /// update (an event), so each held run's stretch is measured afresh.
  void watchHeldRuns(Cable& cable, int c, double time_s, bool switched);
  /// Current length (m) and world end points of joint j's straight span.
  double spanLength(const Cable& cable, int j) const;
  Vec3 startPointOf(const Cable& cable, int j) const;
  Vec3 endPointOf(const Cable& cable, int j) const;

  World& world_;
  std::vector<Cable> cables_;
  std::vector<Junction> junctions_;
  std::vector<CableEvent> events_;
  // What one cable's update gives the whole, kept apart while the cables
  // update on the World's threads: its events and jams added in cable
  // order after them, its work and losses summed per cable and then in
  // cable order when asked for. The same bits on any number of threads.
  struct JamRequest {
    int joint;            // the span that ran out
    BodyId wheel, tie;    // the ball joint's bodies (the wheel or the pinhole's)
    Vec3 tie_point;       // m, world: its anchor
    int pinhole = -1;     // a pinhole's link, which holds the cable now, and its mu before
    double pinhole_mu = 0.0;
  };
  // A span's tangent points in the world as an update left them, where both
  // its links roll on circles about axles that stay put (steady_): the next
  // update keeps them if its bodies only turned about those axles since
  // (updateJoint). `update`: its cable's update count then (CableUpdate::
  // count), -1 for none; `found`: the
  // update that found them afresh (kept since), the span's path's
  // PathConstraint::placement; `to` and `sides` (the links'
  // orientations): the span they were found for.
  struct FixedSpan {
    Vec3 a = Vec3::Zero(), b = Vec3::Zero();
    long long update = -1, found = 0;
    int to = -1, sides = 0;
  };
  struct CableUpdate {
    // Its updates so far: every update updates every cable, so each
    // cable's count is the same as one for the system would be, and an
    // island stepping its substeps on its own (World::IslandHook::
    // whole_steps) counts its cables' alone.
    long long count = 0;
    // The end (s) of the update that left its news (events, jams, a
    // breach) for endUpdate: that substep's endUpdate takes them, not an
    // earlier one's.
    double news_at = 0.0;
    std::vector<FixedSpan> fixed;  // per joint
    // Per joint starting a held run (watchHeldRuns): the least its run was
    // stretched since it was held (m, length less rest length; negative:
    // slack); NaN where none is held.
    std::vector<double> held_least;
    std::optional<CableBreach> held;  // the first held run stretched further (sticky)
    std::vector<CableEvent> events;
    double friction_loss = 0.0;  // J, since the system was made: its part of frictionLoss()
    double winch_work = 0.0;     // J, this substep's
    double winch_total = 0.0;    // J, since the system was made: its part of winchWork()
    std::vector<JamRequest> jams;
    bool breached = false;  // its invariants broken after it (cableBreach)
    // A sphere's or hull's section where a span met it off its link's
    // plane (splitAtCrossedLinks), built here with room reserved
    // (reserveSlice) so that testing one every substep takes no heap.
    Section slice;
    std::vector<Vec2> slice_points;
  };
  std::vector<CableUpdate> updates_;  // per cable
  std::vector<std::pair<BodyId, BodyId>> jams_;  // (wheel, tie point's body) held by a ball joint
  std::vector<BodyId> rolling_bodies_;  // bodies with a rolling or hybrid link
  std::vector<Quat> last_q_;            // per body: orientation at the last update
  std::vector<double> turn_;            // per body, rad (measureTurns)
  std::vector<Vec3> last_x_;            // per body: position at the last update
  std::vector<double> move_;            // per body, m since the last update (measureTurns)
  // Per body: its cable plane's circles stay where they are as it turns (a
  // static body, or a rotor whose axle is its local z); and it did, since
  // the last update (measureTurns: it kept its position and turned about
  // that axle alone).
  std::vector<char> steady_, in_place_;
  // The last update was by hand, after the solve: the next one's first
  // substep does not count that solve's turn again (measureTurns).
  bool solve_turn_counted_ = false;
  // beginUpdate's sort: cable indices and rolling bodies by island (-1
  // first), island i's from *_begin_[i + 1] to *_begin_[i + 2].
  std::vector<int> cables_by_island_, cable_begin_;
  std::vector<BodyId> rolling_by_island_;
  std::vector<int> rolling_begin_;
  int grouped_for_ = -1;  // World::islandsBuilt() when sorted
  std::optional<CableBreach> breach_;   // firstBreach()
  std::atomic<bool> news_{false};       // a cable's update has an event, a jam or a breach for endUpdate
  bool poses_predicted_ = false;        // within a substep's update: the last solve's poses are x_prev, q_prev
  bool rechecks_slips_ = false;         // recheckSlips is the World's ResolveCheck
  Cable settled_;                       // recheckSlips' copy, kept for its storage
};

}  // namespace reeve
