// Islands (island.h): which moving bodies the constraints join. Built by
// union-find over the joints, distance constraints, paths, coupled bodies
// and colliders; rebuilt when one is added, or when a distance
// constraint's or path's bodies were changed in place (a cable's span
// moving to the next link).
#include <algorithm>
#include <chrono>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>

#include "island.h"
#include "reeve/engine/world.h"

namespace reeve {
namespace {

// Disjoint sets with path halving; a set's root is its lowest body, so
// islands come out in the order of their lowest bodies.
struct Sets {
  std::vector<int> parent;
  int find(int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  void unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a < b) parent[b] = a;
    else if (b < a) parent[a] = b;
  }
};

}  // namespace

void World::coupleBodies(const std::vector<BodyId>& bodies) {
  for (const BodyId id : bodies)
    if (id < kWorldBody || id >= bodyCount())
      throw std::invalid_argument("coupleBodies: no body " + std::to_string(id) + " (the world has " +
                                  std::to_string(bodyCount()) + ")");
  couplings_.push_back(bodies);
  islands_dirty_ = true;
}

int World::islandCount() {
  refreshIslands();
  return static_cast<int>(islands_.size());
}

const std::vector<BodyId>& World::islandBodies(int i) {
  refreshIslands();
  return islands_.at(i)->bodies;
}

int World::islandOf(BodyId a, BodyId b) const {
  const int of_a = a == kWorldBody ? -1 : island_of_[a];
  return of_a >= 0 || b == kWorldBody ? of_a : island_of_[b];
}

// The constraints' bodies may have changed in place (distance(), path():
// the cable system moves a span from link to link): each must still be
// where it was filed, its moving bodies all on that island.
bool World::distanceMoved(int i) const {
  const DistanceConstraint& c = distances_[i];
  const int island = distance_island_[i];
  const auto filed = [&](BodyId id) { return id == kWorldBody || island_of_[id] < 0 || island_of_[id] == island; };
  return islandOf(c.a, c.b) != island || !filed(c.a) || !filed(c.b);
}

bool World::pathMoved(int i) const {
  // A path set again where it lay (PathConstraint::placement) is on the
  // bodies it was on when last found on its island.
  const long long placement = paths_[i].placement;
  const bool known = static_cast<std::size_t>(i) < path_placement_.size();
  if (known && placement != 0 && placement == path_placement_[i]) return false;
  int island = -1;
  for (const PathPoint& p : paths_[i].points)
    if (p.body != kWorldBody && island_of_[p.body] >= 0) {
      island = island_of_[p.body];
      break;
    }
  if (island != path_island_[i]) return true;
  for (const PathPoint& p : paths_[i].points)
    if (p.body != kWorldBody && island_of_[p.body] >= 0 && island_of_[p.body] != island) return true;
  if (known) path_placement_[i] = placement;
  return false;
}

bool World::rowsMoved(const std::vector<int>& distances, const std::vector<int>& paths) const {
  return std::any_of(distances.begin(), distances.end(), [&](int i) { return distanceMoved(i); }) ||
         std::any_of(paths.begin(), paths.end(), [&](int i) { return pathMoved(i); });
}

void World::refreshIslands() {
  for (int i = 0; i < distanceCount() && !islands_dirty_; ++i) islands_dirty_ = distanceMoved(i);
  for (int i = 0; i < pathCount() && !islands_dirty_; ++i) islands_dirty_ = pathMoved(i);
  if (islands_dirty_) buildIslands();
}

void World::buildIslands() {
  islands_dirty_ = false;
  ++islands_built_;
  const int n = bodyCount();
  // What each island holds for the step under way goes to the World, or
  // with its bodies to their new island: a whole step's islands may be at
  // different substeps (World::stepWhole).
  body_progress_.assign(n, -1);  // -1: on no island
  for (auto& island : islands_) {  // their bodies may be others' now
    addFlows(flows_, island->flows);
    island->flows = WorldEnergy{};
    if (island->non_finite && (!non_finite_found_ || *island->non_finite < *non_finite_found_))
      non_finite_found_ = island->non_finite;
    island->non_finite.reset();
    for (std::size_t s = 0; s < island->substep_iterations.size() && s < substep_iterations_.size(); ++s)
      substep_iterations_[s] = std::max(substep_iterations_[s], island->substep_iterations[s]);
    for (const BodyId id : island->bodies) body_progress_[id] = 4 * island->at + 2 * island->cut + island->started;
  }
  // Moving and kinematic bodies are the nodes; static bodies and the world
  // join nothing.
  const auto node = [&](BodyId id) { return id != kWorldBody && (mass_[id] > 0.0 || bodies_[id].kinematic); };
  Sets sets;
  sets.parent.resize(n);
  std::iota(sets.parent.begin(), sets.parent.end(), 0);
  const auto unite = [&](BodyId a, BodyId b) {
    if (node(a) && node(b)) sets.unite(a, b);
  };
  const auto uniteAll = [&](const auto& ids, auto body_of) {
    BodyId first = kWorldBody;
    for (const auto& item : ids) {
      const BodyId id = body_of(item);
      if (!node(id)) continue;
      if (first == kWorldBody) first = id;
      else sets.unite(first, id);
    }
  };
  for (const HingeJoint& j : hinges_) unite(j.a, j.b);
  for (const PrismaticJoint& j : prismatics_) unite(j.a, j.b);
  for (const SphericalJoint& j : sphericals_) unite(j.a, j.b);
  for (const FixedJoint& j : fixeds_) unite(j.a, j.b);
  for (const DistanceConstraint& c : distances_) unite(c.a, c.b);
  for (const PathConstraint& p : paths_) uniteAll(p.points, [](const PathPoint& q) { return q.body; });
  for (const auto& group : couplings_) uniteAll(group, [](BodyId id) { return id; });
  // Any two colliders may touch within a step.
  uniteAll(colliders_, [](BodyId id) { return id; });

  // The islands in the order of their lowest bodies, each keeping the
  // solver of the island that had its place (its warm start, its layout
  // when nothing changed).
  std::vector<int> island_of_root(n, -1);
  island_of_.assign(n, -1);
  int count = 0;
  for (BodyId id = 0; id < n; ++id) {
    if (!node(id)) continue;
    int& island = island_of_root[sets.find(id)];
    if (island < 0) {
      island = count++;
      if (static_cast<int>(islands_.size()) < count) islands_.push_back(std::make_unique<Island>());
      Island& fresh = *islands_[island];
      fresh.driven = true;  // until its drives are looked at (World::startIsland)
      for (auto* list : {&fresh.bodies, &fresh.hinges, &fresh.prismatics, &fresh.sphericals, &fresh.fixeds,
                         &fresh.distances, &fresh.paths, &fresh.manifolds})
        list->clear();
    }
    island_of_[id] = island;
    islands_[island]->bodies.push_back(id);
  }
  islands_.resize(count);
  for (auto& island : islands_) {
    int progress = -1;  // its bodies' islands' (a body new to islands has none)
    for (const BodyId id : island->bodies) {
      if (body_progress_[id] < 0) continue;
      if (progress >= 0 && body_progress_[id] != progress)  // IslandHook::whole_steps promised it would not
        throw std::logic_error("World: a substep hook joined islands that were at different substeps");
      progress = body_progress_[id];
    }
    progress = std::max(progress, 0);
    island->at = progress / 4;
    island->cut = progress / 2 % 2 == 1;
    island->started = progress % 2 == 1;
    island->substep_iterations.assign(substep_iterations_.size(), 0);
    // Whether one of its bodies may be massless beside another
    // (light_bodies.h): looked for each substep only where one may be.
    double lightest = std::numeric_limits<double>::infinity(), heaviest = 0.0;
    for (const BodyId id : island->bodies)
      if (mass_[id] > 0.0 && !bodies_[id].kinematic) {
        lightest = std::min(lightest, mass_[id]);
        heaviest = std::max(heaviest, mass_[id]);
      }
    island->light_possible = lightest <= kMasslessShare * heaviest;
  }
  island_cost_.assign(count, 0.0);  // an island's bodies may be others now
  island_manifolds_ = true;         // sortManifolds clears the lists
  // Room for 2 touching pairs a body, as findContacts has.
  for (auto& island : islands_) island->manifolds.reserve(2 * island->bodies.size());
  cutIslandRuns();
  if (!pool_ && threads_ > 1 && islands_.size() > 1) {
    pool_ = std::make_unique<ThreadPool>(threads_);
    pool_->setSpin(std::chrono::microseconds(200));
  }
  // A joint between two static bodies has nothing to solve, and is on no
  // island.
  const auto file = [&](auto& joints, std::vector<int> Island::*list, std::vector<int>* loose) {
    if (loose) loose->clear();
    for (int i = 0; i < static_cast<int>(joints.size()); ++i)
      if (const int island = islandOf(joints[i].a, joints[i].b); island >= 0)
        (islands_[island].get()->*list).push_back(i);
      else if (loose)
        loose->push_back(i);
  };
  file(hinges_, &Island::hinges, &loose_hinges_);
  file(prismatics_, &Island::prismatics, &loose_prismatics_);
  file(sphericals_, &Island::sphericals, nullptr);
  file(fixeds_, &Island::fixeds, nullptr);
  loose_distances_.clear();
  distance_island_.assign(distances_.size(), -1);
  for (int i = 0; i < distanceCount(); ++i) {
    const int island = distance_island_[i] = islandOf(distances_[i].a, distances_[i].b);
    (island < 0 ? loose_distances_ : islands_[island]->distances).push_back(i);
  }
  loose_paths_.clear();
  path_island_.assign(paths_.size(), -1);
  path_placement_.assign(paths_.size(), 0);
  for (int i = 0; i < pathCount(); ++i) {
    int& island = path_island_[i];
    for (const PathPoint& p : paths_[i].points)
      if (node(p.body)) {
        island = island_of_[p.body];
        break;
      }
    (island < 0 ? loose_paths_ : islands_[island]->paths).push_back(i);
  }
}

void World::cutIslandRuns() {
  // One run a thread, some empty when there are fewer islands. Work as
  // measured, or else estimated by the bodies and constraints.
  island_runs_.assign(1, 0);
  if (!thread_runs_) thread_runs_ = std::make_unique<ThreadRun[]>(threads_);
  for (int t = 0; t < threads_; ++t) thread_runs_[t].ran.reserve(islands_.size());  // a thread may run them all
  serial_ns_ = 0.0;
  timed_runs_ = 0;
  // The islands' news is not known until they run (driven: a drive may be
  // among them).
  news_.assign(threads_, RunNews{.driven = true});
  const int n = static_cast<int>(islands_.size());
  const bool measured = std::all_of(island_cost_.begin(), island_cost_.end(), [](double c) { return c > 0.0; });
  const auto work = [&](int k) {
    if (measured) return island_cost_[k];
    const Island& i = *islands_[k];
    return static_cast<double>(i.bodies.size() + i.hinges.size() + i.prismatics.size() + i.sphericals.size() +
                               i.fixeds.size() + i.distances.size() + i.paths.size());
  };
  double total = 0.0;
  for (int i = 0; i < n; ++i) total += work(i);
  const std::size_t runs = threads_;
  double done = 0.0;
  for (int i = 0; i < n; ++i) {
    done += work(i);
    // Run k ends once the work done reaches k / runs of the total.
    while (island_runs_.size() < runs && done * runs >= island_runs_.size() * total) island_runs_.push_back(i + 1);
  }
  island_runs_.resize(runs + 1, n);
}

void World::balanceIslandRuns() {
  if (timed_runs_ == 0) return;
  // The islands' work a run (ns), and whether it pays to share it: a run
  // on threads costs 1 to 2 us more than its work (its join), and every
  // line the threads share crosses between cores.
  double shared_ns = 0.0;  // the threads' time, shared out over the islands they ran
  for (const auto& island : islands_) shared_ns += island->ns;
  const double work = (share_runs_ ? shared_ns : serial_ns_) / timed_runs_;
  const bool shared = share_runs_;
  share_runs_ = work >= (share_runs_ ? 0.5 : 1.0) * min_shared_run_ns_;
  serial_ns_ = 0.0;
  timed_runs_ = 0;
  if (!shared) return;
  for (int i = 0; i < static_cast<int>(islands_.size()); ++i) {
    double& cost = island_cost_[i];
    const double ns = std::exchange(islands_[i]->ns, 0.0);
    cost = cost > 0.0 ? 0.5 * (cost + ns) : ns;
  }
  cutIslandRuns();
}

void World::sortManifolds() {
  // Nothing to hand out and nothing to take back: the islands' lines stay
  // in their threads' caches (a clear() writes even an empty list).
  if (manifolds_.empty() && !island_manifolds_) return;
  for (auto& island : islands_) island->manifolds.clear();
  for (int m = 0; m < static_cast<int>(manifolds_.size()); ++m)
    islands_[islandOf(manifolds_[m].a, manifolds_[m].b)]->manifolds.push_back(m);
  island_manifolds_ = !manifolds_.empty();
}

}  // namespace reeve
