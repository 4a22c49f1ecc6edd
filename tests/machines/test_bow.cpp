// scenes/bow.json, the paper's compound bow (Fig. 19): limbs of spring
// hinges, eccentric cams at their tips, a string from cam to cam through a
// nock and two buss cables, an arrow on a rail. Checked against mechanics
// computed from the state, not from the solver's forces: along a slow draw
// the drive's force is the derivative of the stored energy (virtual work)
// and what statics of the cams and limbs give from their moment arms and
// spring torques, so the let-off is the cams'; released, the energy is
// conserved until the arrow leaves the string, and the arrow's speed is
// what the energy left in the bow leaves for it.
#include <gtest/gtest.h>

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "reeve/cable/cable.h"
#include "scene_fixture.h"

namespace reeve::test_bow {
namespace {

struct Budget {
  int substeps, iterations;
};
constexpr Budget kScene{300, 2};  // the scene's
constexpr Budget kPaper{10, 10};  // the paper's (Fig. 19: 10 substeps of 10 iterations)

// z of a planar cross product: the moment about +z of F at arm r.
double moment(const Vec3& r, const Vec3& F) { return r.x() * F.y() - r.y() * F.x(); }

struct Bow {
  Scene s;
  BodyId arrow, nock, cam[2];
  PrismaticId rail = -1, nock_joint = -1;  // the arrow's rail; the nock on the arrow
  HingeId cam_hinge[2] = {-1, -1};
  std::vector<HingeId> limb[2];  // each limb's spring hinges, from the riser out
  int string = -1, buss[2] = {-1, -1};
  double brace_energy = 0.0;  // springs and gravity at load (J)
  double full_draw = 0.0;     // m, the rail's stop

  explicit Bow(Budget b) : s(test::scene("bow")) {
    s.world->settings().substeps = b.substeps;
    s.world->settings().iterations = b.iterations;
    World& w = *s.world;
    arrow = test::body(s, "arrow");
    nock = test::body(s, "nock");
    const char* side[2] = {"top", "bottom"};
    for (int k = 0; k < 2; ++k) {
      cam[k] = test::body(s, std::string(side[k]) + "_cam");
      for (int i = 0; i < 3; ++i) {
        const BodyId segment = test::body(s, std::string(side[k]) + "_limb" + std::to_string(i));
        for (HingeId h = 0; h < static_cast<int>(w.hinges().size()); ++h)
          if (w.hinge(h).a == segment) limb[k].push_back(h);
      }
      for (HingeId h = 0; h < static_cast<int>(w.hinges().size()); ++h)
        if (w.hinge(h).a == cam[k]) cam_hinge[k] = h;
    }
    for (PrismaticId p = 0; p < static_cast<int>(w.prismatics().size()); ++p) {
      if (w.prismatic(p).a == arrow) rail = p;
      if (w.prismatic(p).a == nock) nock_joint = p;
    }
    const auto& all = s.cables->cables();
    for (int c = 0; c < static_cast<int>(all.size()); ++c) {
      if (all[c].name == "string") string = c;
      if (all[c].name == "buss_top") buss[0] = c;
      if (all[c].name == "buss_bottom") buss[1] = c;
    }
    // The file's demonstration draws from t = 0 to the rail's stop at full
    // draw and lets go at 2 s; the tests draw as they need and hold the
    // arrow with the drive alone.
    w.prismatic(rail).drive = PrismaticDrive{PrismaticDrive::Mode::Velocity, 0.0, 0.0};
    full_draw = w.prismatic(rail).limit.upper;
    w.prismatic(rail).limit.enabled = false;
    brace_energy = springEnergy() + gravityEnergy();
  }

  World& w() { return *s.world; }
  const World& w() const { return *s.world; }
  Vec3 gravity() const { return w().settings().gravity; }
  double h() const { return 1.0 / s.frame_rate_hz / w().settings().substeps; }

  // -- energy (J), from the state alone --
  // Sum of 1/2 k (theta - target)^2 over the spring hinges (angles from the
  // bodies' orientations).
  double springEnergy() const {
    double e = 0.0;
    for (const HingeJoint& j : w().hinges())
      if (j.drive.stiffness > 0.0) {
        const double d = wrapAngle(hingeAngle(j, w().body(j.a).q, w().body(j.b).q) - j.drive.target);
        e += 0.5 * j.drive.stiffness * d * d;
      }
    return e;
  }
  double gravityEnergy() const {
    double e = 0.0;
    for (BodyId b = 0; b < w().bodyCount(); ++b) e -= w().bodyMass(b) * gravity().dot(w().body(b).x);
    return e;
  }
  double kinetic(BodyId b) const {
    const BodyState& x = w().body(b);
    const Vec3 omega = x.q.conjugate() * x.omega;  // body axes
    return 0.5 * w().bodyMass(b) * x.v.squaredNorm() + 0.5 * omega.dot(x.inertia * omega);
  }
  double kineticEnergy() const {
    double e = 0.0;
    for (BodyId b = 0; b < w().bodyCount(); ++b)
      if (w().bodyMass(b) > 0.0) e += kinetic(b);
    return e;
  }
  double energy() const { return springEnergy() + gravityEnergy() + kineticEnergy(); }
  // Power (W) the springs' damping takes: sum of c (d theta / dt)^2.
  double dampingPower() const {
    double p = 0.0;
    for (const HingeJoint& j : w().hinges())
      if (j.drive.damping > 0.0) {
        const double rate = (w().body(j.a).omega - w().body(j.b).omega).z();
        p += j.drive.damping * rate * rate;
      }
    return p;
  }

  // -- the draw --
  double drawn() const { return w().prismaticSlide(rail); }          // m behind brace
  double drawForce() const { return w().prismaticDriveForce(rail); }  // N, on the arrow, backwards (+x)
  void drive(double speed) { w().prismatic(rail).drive = PrismaticDrive{PrismaticDrive::Mode::Velocity, speed, 0.0}; }
  void holdAt(double x) { w().prismatic(rail).drive = PrismaticDrive{PrismaticDrive::Mode::Position, x, 0.0}; }
  void frame() { test::frame(s); }
  bool finite() const { return !w().firstNonFiniteBody(); }
  double largestTension() const {
    double t = 0.0;
    for (int c = 0; c < static_cast<int>(s.cables->cables().size()); ++c)
      for (int j = 0; j < static_cast<int>(s.cables->cables()[c].joints.size()); ++j)
        t = std::max(t, s.cables->tension(c, j));
    return t;
  }

  // -- statics from the moment arms --
  // Unit vector along joint j of cable c from its start to its end.
  Vec3 along(int c, int j) const {
    return (s.cables->endPoint(c, j) - s.cables->startPoint(c, j)).normalized();
  }
  Vec3 axle(int k) const { return w().worldPoint(cam[k], w().hinge(cam_hinge[k]).frame.anchor_a); }
  // Where the string leaves cam k and the unit vector it pulls the cam along.
  Vec3 stringPoint(int k) const { return k == 0 ? s.cables->startPoint(string, 0) : s.cables->endPoint(string, 1); }
  Vec3 stringPull(int k) const { return k == 0 ? along(string, 0) : Vec3(-along(string, 1)); }
  // Moment arms (m) about cam k's axle of the string and of its own buss cable.
  double stringArm(int k) const { return std::abs(moment(stringPoint(k) - axle(k), stringPull(k))); }
  double bussArm(int k) const {
    return std::abs(moment(s.cables->startPoint(buss[k], 0) - axle(k), along(buss[k], 0)));
  }

  // The draw force that statics gives, from the geometry and the spring
  // torques alone. Unknowns: the string's tension T and the buss cables'
  // B_0 (top), B_1. Each cam turns freely on its axle: the moments about it
  // of the string, its own buss cable and its weight balance. Each spring
  // hinge holds what lies beyond it (segments, cam, the cables pulling on
  // them, their weights) with its torque -k (theta - target) - c dtheta/dt.
  // Eight equations (two cams, six hinges), three unknowns, least squares;
  // the nock then needs the drive to hold -T (u_top + u_bottom) . x, u the
  // string's directions from the nock. `residual` (N m) receives the
  // largest equation's misfit.
  double staticDrawForce(double* residual = nullptr) const {
    Eigen::Matrix<double, 8, 3> A = Eigen::Matrix<double, 8, 3>::Zero();
    Eigen::Matrix<double, 8, 1> rhs = Eigen::Matrix<double, 8, 1>::Zero();
    const Vec3 g = gravity();
    int row = 0;
    for (int k = 0; k < 2; ++k) {
      const int other = 1 - k;
      // Cable forces on limb k and its cam: point, unit direction, unknown.
      struct Pull {
        Vec3 at, dir;
        int unknown;
      };
      const Pull pulls[3] = {{stringPoint(k), stringPull(k), 0},
                             {s.cables->startPoint(buss[k], 0), along(buss[k], 0), 1 + k},
                             {s.cables->endPoint(buss[other], 0), -along(buss[other], 0), 1 + other}};
      // The cam about its axle: the string and its own buss cable.
      const Vec3 a = axle(k);
      for (int p = 0; p < 2; ++p) A(row, pulls[p].unknown) += moment(pulls[p].at - a, pulls[p].dir);
      rhs(row++) = -moment(w().body(cam[k]).x - a, w().bodyMass(cam[k]) * g);
      // Each spring hinge: all three pulls act beyond it.
      for (std::size_t i = 0; i < limb[k].size(); ++i) {
        const HingeJoint& j = w().hinge(limb[k][i]);
        const Vec3 H = w().worldPoint(j.a, j.frame.anchor_a);
        const double theta = hingeAngle(j, w().body(j.a).q, w().body(j.b).q);
        const double rate = (w().body(j.a).omega - w().body(j.b).omega).z();
        const double spring = -j.drive.stiffness * wrapAngle(theta - j.drive.target) - j.drive.damping * rate;
        for (const Pull& p : pulls) A(row, p.unknown) += moment(p.at - H, p.dir);
        double weights = moment(w().body(cam[k]).x - H, w().bodyMass(cam[k]) * g);
        for (std::size_t m = i; m < limb[k].size(); ++m) {
          const BodyId seg = w().hinge(limb[k][m]).a;
          weights += moment(w().body(seg).x - H, w().bodyMass(seg) * g);
        }
        rhs(row++) = -spring - weights;
      }
    }
    const Eigen::Vector3d T = A.colPivHouseholderQr().solve(rhs);
    if (residual) *residual = (A * T - rhs).cwiseAbs().maxCoeff();
    const Vec3 n = w().body(nock).x;
    const Vec3 u_top = (stringPoint(0) - n).normalized(), u_bottom = (stringPoint(1) - n).normalized();
    return -T(0) * (u_top + u_bottom).x();
  }
};

// One sample of a slow draw.
struct Sample {
  double x, force, statics, energy, kinetic, damped;  // m, N, N, J, J, J dissipated so far
};

// Draws the arrow from brace to `to` m at `speed` m/s (reached over the
// first 0.1 s), sampling every frame, then holds it at `to`.
std::vector<Sample> slowDraw(Bow& bow, double to, double speed) {
  std::vector<Sample> samples;
  const double dt = 1.0 / bow.s.frame_rate_hz;
  double damped = 0.0, t = 0.0;
  while (bow.drawn() + speed * dt < to) {
    bow.drive(speed * std::min(1.0, (t + dt) / 0.1));
    const double before = bow.dampingPower();
    bow.frame();
    t += dt;
    damped += 0.5 * (before + bow.dampingPower()) * dt;
    samples.push_back({bow.drawn(), bow.drawForce(), bow.staticDrawForce(), bow.springEnergy() + bow.gravityEnergy(),
                       bow.kineticEnergy(), damped});
  }
  bow.holdAt(to);
  return samples;
}

TEST(Bow, BracedItIsAtRest) {
  // The springs' targets are set so that the braced bow is in equilibrium:
  // left alone, nothing moves.
  Bow bow(kScene);
  std::vector<Vec3> start;
  for (BodyId b = 0; b < bow.w().bodyCount(); ++b) start.push_back(bow.w().body(b).x);
  for (int f = 0; f < 30; ++f) bow.frame();
  double moved = 0.0;
  for (BodyId b = 0; b < bow.w().bodyCount(); ++b) moved = std::max(moved, (bow.w().body(b).x - start[b]).norm());
  std::printf("[ measured ] braced, 0.5 s: largest move %.2e m, kinetic energy %.2e J, string %.1f N, buss cables "
              "%.1f and %.1f N\n",
              moved, bow.kineticEnergy(), bow.s.cables->tension(bow.string, 0), bow.s.cables->tension(bow.buss[0], 0),
              bow.s.cables->tension(bow.buss[1], 0));
  EXPECT_LT(moved, 1e-7);
  EXPECT_LT(bow.kineticEnergy(), 1e-9);
  // The statics of the cams and limbs give the same: no force on the nock.
  double residual = 0.0;
  EXPECT_NEAR(bow.staticDrawForce(&residual), 0.0, 1e-3);
  EXPECT_LT(residual, 1e-3);
}

TEST(Bow, DrawnSlowlyTheForceIsTheDerivativeOfTheStoredEnergy) {
  // Virtual work: F dx = dE + dK + dW_damping, E = sum 1/2 k (theta -
  // target)^2 + sum m g y from the hinge angles and positions, K the
  // kinetic energy, W the springs' damping; the force is compared with the
  // central difference of the rest over the neighbouring frames (5 mm
  // apart) wherever it is above a tenth of its peak.
  for (const Budget b : {kScene, kPaper}) {
    SCOPED_TRACE(testing::Message() << b.substeps << " x " << b.iterations);
    Bow bow(b);
    const std::vector<Sample> draw = slowDraw(bow, bow.full_draw, 0.3);
    double peak = 0.0;
    for (const Sample& d : draw) peak = std::max(peak, d.force);
    double worst = 0.0, worst_at = 0.0, damped_share = 0.0;
    for (std::size_t i = 1; i + 1 < draw.size(); ++i) {
      const Sample &p = draw[i - 1], &n = draw[i + 1];
      if (draw[i].force < 0.1 * peak) continue;
      const double work = (n.energy - p.energy) + (n.kinetic - p.kinetic) + (n.damped - p.damped);
      const double derivative = work / (n.x - p.x);
      const double error = std::abs(draw[i].force - derivative) / draw[i].force;
      damped_share = std::max(damped_share, (n.damped - p.damped) / work);
      if (error > worst) worst = error, worst_at = draw[i].x;
    }
    std::printf("[ measured ] %d x %d: draw force vs d(stored energy)/dx over %zu frames: worst %.2e at %.3f m "
                "(peak %.1f N; damping's share of the work at most %.1e)\n",
                b.substeps, b.iterations, draw.size(), worst, worst_at, peak, damped_share);
    EXPECT_LT(worst, 0.01);
    EXPECT_TRUE(bow.finite());
  }
}

TEST(Bow, TheDrawForcePeaksAndLetsOffAsTheCamsMomentArmsGive) {
  // Statics from the geometry (where each cable leaves each cam, the cams'
  // axles, the hinges) and the spring torques alone (Bow::staticDrawForce)
  // against the drive's force along the draw; then the let-off, 1 -
  // holding force / peak force, against the one statics gives. The cams
  // cause it: as a cam turns, its centre swings towards the string, whose
  // moment arm about the axle grows while the buss cable's shrinks.
  for (const Budget b : {kScene, kPaper}) {
    SCOPED_TRACE(testing::Message() << b.substeps << " x " << b.iterations);
    Bow bow(b);
    const double arms_brace[2] = {bow.stringArm(0), bow.bussArm(0)};
    const std::vector<Sample> draw = slowDraw(bow, bow.full_draw, 0.3);
    double peak = 0.0, peak_statics = 0.0, peak_at = 0.0, worst = 0.0;
    for (const Sample& d : draw) {
      if (d.force > peak) peak = d.force, peak_at = d.x;
      peak_statics = std::max(peak_statics, d.statics);
      if (d.force > 0.1 * draw.back().force) worst = std::max(worst, std::abs(d.statics / d.force - 1.0));
    }
    for (int f = 0; f < 20; ++f) bow.frame();  // the springs' damping settles it
    double residual = 0.0;
    const double hold = bow.drawForce(), hold_statics = bow.staticDrawForce(&residual);
    const double let_off = 1.0 - hold / peak, let_off_statics = 1.0 - hold_statics / peak_statics;
    std::printf("[ measured ] %d x %d: statics vs drive force: worst %.2e; peak %.1f N at %.3f m (statics %.1f N), "
                "holding %.1f N at %.3f m (statics %.1f N, misfit %.1e N m); let-off %.4f (statics %.4f); cam "
                "moment arms, string / buss: brace %.1f / %.1f mm, full draw %.1f / %.1f mm\n",
                b.substeps, b.iterations, worst, peak, peak_at, peak_statics, hold, bow.drawn(), hold_statics, residual,
                let_off, let_off_statics, 1e3 * arms_brace[0], 1e3 * arms_brace[1], 1e3 * bow.stringArm(0),
                1e3 * bow.bussArm(0));
    EXPECT_LT(worst, 0.01);
    EXPECT_NEAR(hold, hold_statics, 0.01 * hold);
    EXPECT_NEAR(let_off, let_off_statics, 0.01);
    // A compound bow: the force peaks inside the draw and lets off by more
    // than half, because the buss cable's arm over the string's falls.
    EXPECT_GT(peak_at, 0.1);
    EXPECT_LT(peak_at, 0.4);
    EXPECT_GT(let_off, 0.5);
    EXPECT_LT(bow.bussArm(0) / bow.stringArm(0), 0.5 * arms_brace[1] / arms_brace[0]);
    EXPECT_TRUE(bow.finite());
  }
}

// Draws to full draw, lets the springs' damping settle the bow, turns the
// damping off and lets go; steps substep by substep until the nock leaves
// the arrow (the string slows down) and `after` s more, with the damping
// back on after the arrow left if `damped_after`.
struct Shot {
  double stored = 0.0;        // J, released: energy at full draw over that at brace
  double worst_before = 0.0;  // largest |E / E0 - 1| until the arrow leaves
  double error_at_exit = 0.0, error_after = 0.0;
  double exit_time = -1.0;    // s after release
  double speed = 0.0, predicted = 0.0, speed_later = 0.0;  // m/s
  double largest_tension = 0.0;  // N, over the draw and the shot
  bool finite = true;
};

Shot shoot(Bow& bow, double after, bool damped_after) {
  Shot shot;
  const std::vector<Sample> draw = slowDraw(bow, bow.full_draw, 0.6);
  (void)draw;
  for (int f = 0; f < 24; ++f) {
    bow.frame();
    shot.largest_tension = std::max(shot.largest_tension, bow.largestTension());
  }
  std::vector<double> damping;
  for (HingeId h = 0; h < static_cast<int>(bow.w().hinges().size()); ++h) {
    damping.push_back(bow.w().hinge(h).drive.damping);
    bow.w().hinge(h).drive.damping = 0.0;
  }
  const double e0 = bow.energy();
  shot.stored = e0 - bow.brace_energy;
  bow.w().prismatic(bow.rail).drive = PrismaticDrive{};  // let go
  const double h = bow.h();
  bow.w().settings().substeps = 1;  // the same substeps, one at a time
  const double m = bow.w().bodyMass(bow.arrow);
  for (double t = h; shot.exit_time < 0.0 || t < shot.exit_time + after; t += h) {
    bow.w().step(h);
    if (!bow.finite()) {
      shot.finite = false;
      break;
    }
    shot.largest_tension = std::max(shot.largest_tension, bow.largestTension());
    const double e = bow.energy();
    if (shot.exit_time < 0.0) {
      shot.worst_before = std::max(shot.worst_before, std::abs(e / e0 - 1.0));
      if (bow.w().prismaticSlide(bow.nock_joint) > 1e-9) {  // the nock left the arrow
        shot.exit_time = t;
        shot.error_at_exit = e / e0 - 1.0;
        shot.speed = -bow.w().body(bow.arrow).v.x();
        // What the bow keeps (springs, gravity, the motion of everything
        // but the arrow) leaves the arrow the rest: 1/2 m v^2 = E0 - that.
        shot.predicted = std::sqrt(2.0 * (e0 - (e - bow.kinetic(bow.arrow))) / m);
        if (damped_after)
          for (HingeId i = 0; i < static_cast<int>(damping.size()); ++i) bow.w().hinge(i).drive.damping = damping[i];
      }
      if (t > 0.1) break;  // never left: fails below
    }
    shot.error_after = e / e0 - 1.0;
  }
  shot.speed_later = -bow.w().body(bow.arrow).v.x();
  return shot;
}

TEST(Bow, ReleasedTheArrowLeavesWithTheEnergyTheBowStored) {
  // No damping after release: the energy (springs, gravity, the motion of
  // arrow, nock, limbs and cams) is conserved until the arrow leaves the
  // string, within 1 %, so the arrow's speed is sqrt(2 (E0 - E_bow) / m),
  // E_bow what the bow keeps then. The string runs taut through kilonewtons.
  Bow bow(kScene);
  const Shot shot = shoot(bow, 0.01, false);
  std::printf("[ measured ] %d x %d: stored %.2f J; energy until the arrow leaves (%.2f ms after release) within "
              "%.2e, %+.2e as it leaves, %+.2e 10 ms later (the bow rings on, undamped); arrow %.3f m/s vs %.3f m/s "
              "from the energy (%+.2e), %.3f m/s 10 ms later; efficiency %.3f; largest tension %.0f N\n",
              kScene.substeps, kScene.iterations, shot.stored, 1e3 * shot.exit_time, shot.worst_before,
              shot.error_at_exit, shot.error_after, shot.speed, shot.predicted, shot.speed / shot.predicted - 1.0,
              shot.speed_later, 0.5 * bow.w().bodyMass(bow.arrow) * shot.speed * shot.speed / shot.stored,
              shot.largest_tension);
  ASSERT_TRUE(shot.finite);
  ASSERT_GT(shot.exit_time, 0.0);
  EXPECT_LT(shot.worst_before, 0.01);
  EXPECT_NEAR(shot.speed, shot.predicted, 0.01 * shot.predicted);
  EXPECT_NEAR(shot.speed_later, shot.speed, 1e-9 * shot.speed);  // free on its rail
  EXPECT_GT(shot.largest_tension, 1000.0);
}

TEST(Bow, HeldAtFullDrawItStaysStill) {
  // Drawn to full draw and held there by the rail (a rigid drive) for 2 s,
  // the bow must not move. Under the end projection at the paper's 10
  // substeps it does not hold: a mode of the two cams turning opposite
  // ways, the string sliding through the nock and the limbs bending
  // unevenly (about 100 Hz, w h = 1) grows by a quarter a period, as the
  // end projection's energy error there is a gain that the trapezoidal
  // springs, unlike implicit ones, do not damp (DESIGN, "The held bow");
  // it holds from 14 substeps, and at 10 under the start projection.
  struct Case {
    Budget budget;
    Projection projection;
    bool implicit;  // the springs implicit, not trapezoidal
    const char* name;
  };
  for (const Case& c : {Case{{14, 2}, Projection::End, false, "14 x 2"},
                        Case{{30, 2}, Projection::End, false, "30 x 2"},
                        Case{kPaper, Projection::Start, false, "10 x 10, start projection"},
                        Case{kPaper, Projection::End, true, "10 x 10, implicit springs"}}) {
    Bow bow(c.budget);
    bow.w().settings().projection = c.projection;
    if (c.implicit)
      for (HingeId h = 0; h < static_cast<int>(bow.w().hinges().size()); ++h)
        bow.w().hinge(h).drive.integration = HingeDrive::Integration::Implicit;
    slowDraw(bow, bow.full_draw, 0.6);
    for (int f = 0; f < 6; ++f) bow.frame();  // the drive's stop
    double most = 0.0;
    for (int f = 0; f < 120; ++f) {
      bow.frame();
      most = std::max(most, bow.kineticEnergy());
    }
    std::printf("[ measured ] %s: held 2 s at full draw, kinetic energy at most %.2e J\n", c.name, most);
    // At rest but for what 2 iterations leave unmet (6e-8 J at 14 x 2) and
    // the stop's settling; the growing mode passes 1e-6 J of the bow's 92
    // within 0.3 s at 10 x 10 (67 J after 2 s).
    EXPECT_LT(most, 1e-6) << c.name;
  }
}

TEST(Bow, TheScenesOwnDriveDrawsToTheStopAndLetsGo) {
  // The file as it is: its rail drive (0.3 m/s, at most 400 N) draws the
  // arrow to the rail's stop at full draw and lets go at 2 s (until_s);
  // the springs keep their damping, so the arrow leaves slower than
  // undamped.
  Scene s = test::scene("bow");
  World& w = *s.world;
  const BodyId arrow = test::body(s, "arrow");
  PrismaticId rail = -1;
  for (PrismaticId p = 0; p < static_cast<int>(w.prismatics().size()); ++p)
    if (w.prismatic(p).a == arrow) rail = p;
  const double stop = w.prismatic(rail).limit.upper, release = w.prismatic(rail).drive.until;
  while (w.time() < release - 0.05) test::frame(s);
  const double drawn = w.prismaticSlide(rail);
  EXPECT_EQ(w.prismatic(rail).drive.mode, PrismaticDrive::Mode::Velocity);
  for (int f = 0; f < 6; ++f) test::frame(s);
  const double speed = -w.body(arrow).v.x();
  std::printf("[ measured ] the file's run: drawn %.6f m (stop %.2f m) at %.2f s; %.3f s later the drive is %s and "
              "the arrow flies at %.2f m/s\n",
              drawn, stop, release - 0.05, w.time() - release,
              w.prismatic(rail).drive.mode == PrismaticDrive::Mode::None ? "gone" : "still there", speed);
  EXPECT_NEAR(drawn, stop, 1e-6);
  EXPECT_EQ(w.prismatic(rail).drive.mode, PrismaticDrive::Mode::None);
  EXPECT_GT(speed, 50.0);
  EXPECT_FALSE(w.firstNonFiniteBody());
}

TEST(Bow, TheUndampedShotsLossIsFirstOrderInTheSubstep) {
  // Issue 29, item 4 (open: DESIGN.md, "The bow's shot at 10 x 10..."):
  // the cams, at 300 rad/s, stop within 1.3 ms as the string straightens,
  // and a step that spans that stop loses energy in proportion to its
  // length. At 10 iterations (converged) the loss before the arrow leaves
  // was measured 13.1, 12.9, 4.7, 2.8 and 1.2 % at 10, 20, 40, 80 and 160
  // substeps a frame: never more with more substeps, about halved by each
  // doubling once the stop spans a few substeps (ratios 0.59 and 0.43),
  // and never a gain.
  double previous = 1.0;
  for (const int n : {10, 40, 80, 160}) {
    Bow bow(Budget{n, 10});
    const Shot shot = shoot(bow, 0.0, false);
    ASSERT_TRUE(shot.finite) << n;
    ASSERT_GT(shot.exit_time, 0.0) << n;
    const double lost = -shot.error_at_exit;
    std::printf("[ measured ] %3d x 10: the undamped shot loses %.4f before the arrow leaves\n", n, lost);
    EXPECT_GT(lost, 0.0) << n;  // never energy made
    EXPECT_LE(lost, previous) << n;
    if (n > 40) {
      EXPECT_GT(lost / previous, 0.3) << n;
      EXPECT_LT(lost / previous, 0.7) << n;
    }
    previous = lost;
  }
  EXPECT_LT(previous, 0.02);  // 160 substeps: within the 2 %
}

TEST(Bow, AtThePapersTenSubstepsOfTenIterationsTheShotStaysFinite) {
  // The paper's budget: the draw is right (the tests above), but 10
  // substeps of 1/600 s follow the 13 ms shot, and the cams' stop at
  // brace takes 1.3 ms, less than one: the undamped bow loses 13 % of its
  // energy before the arrow leaves (reported here; the test above has its
  // order in h). Then, damped as the scene is, it rings down and stays
  // finite.
  Bow bow(kPaper);
  const Shot shot = shoot(bow, 0.5, true);
  std::printf("[ measured ] %d x %d: energy until the arrow leaves (%.2f ms) within %.2e, %+.2e as it leaves, "
              "%+.2e 0.5 s later (damped); arrow %.2f m/s vs %.2f m/s from the energy; largest tension %.0f N\n",
              kPaper.substeps, kPaper.iterations, 1e3 * shot.exit_time, shot.worst_before, shot.error_at_exit,
              shot.error_after, shot.speed, shot.predicted, shot.largest_tension);
  EXPECT_TRUE(shot.finite);
  EXPECT_GT(shot.exit_time, 0.0);
  EXPECT_GT(shot.largest_tension, 1000.0);
  EXPECT_LT(shot.error_after, shot.error_at_exit);  // the damping takes, nothing gives
}

}  // namespace
}  // namespace reeve::test_bow
