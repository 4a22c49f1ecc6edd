// An Atwood machine with a massive wheel, built in code: boxes of m1 and
// m2 kg on a cable over a hinged solid cylinder of M kg and radius r, at
// g = 10 m/s^2 (test_atwood.cpp, test_applied_load.cpp).
#pragma once

#include "reeve/cable/cable.h"

namespace reeve {

struct Atwood {
  double m1, m2, M = 2.0, r = 0.2, g = 10.0;
  World world;
  CableSystem cables{world};
  BodyId box1, box2, wheel;
  int cable;
  Atwood(double m1_, double m2_, int substeps, int iterations, double M_ = 2.0,
         Projection projection = Projection::End)
      : m1(m1_), m2(m2_), M(M_) {
    world.settings().gravity = Vec3(0, -g, 0);
    world.settings().projection = projection;
    world.settings().substeps = substeps;
    world.settings().iterations = iterations;
    BodyDef w;
    w.shape = Shape::cylinder(r, 0.05);
    w.mass = M;
    wheel = world.addBody(w);
    world.addHinge({wheel, kWorldBody, Vec3::Zero(), Vec3::UnitZ(), 0.0});
    BodyDef box;
    box.shape = Shape::box(Vec3(0.1, 0.1, 0.1));
    box.mass = m1;
    box.position = Vec3(-r, -3.0, 0.0);
    box1 = world.addBody(box);
    box.mass = m2;
    box.position = Vec3(r, -3.0, 0.0);
    box2 = world.addBody(box);
    CableDef def;
    def.links = {LinkDef::attachment(box1, Vec3(0, 0.1, 0)),
                 LinkDef::rolling(wheel, -1),  // over the top: clockwise
                 LinkDef::attachment(box2, Vec3(0, 0.1, 0))};
    cable = cables.addCable(def);
  }
  double acceleration() const { return (m2 - m1) * g / (m1 + m2 + 0.5 * M * r * r / (r * r)); }
};

}  // namespace reeve
