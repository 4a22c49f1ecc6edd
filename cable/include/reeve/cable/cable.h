// Cables made of links joined by cable joints (paper sec. 3, Alg. 1 and the
// stored-cable bookkeeping of Alg. 2 lines 8-9).
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "reeve/cable/tangent.h"
#include "reeve/engine/world.h"

namespace reeve {

/// How the cable meets a body (paper sec. 3.3).
enum class LinkType {
  Attachment,  ///< fixed to a body-local point
  Rolling,     ///< wraps the body's circular cross-section in its cable plane
};

/// One link as the user describes it.
/// Attachment: `point` is the body-local point (m) the cable is tied to.
/// Rolling: the body must have a circular cross-section (cylinder, sphere);
/// its cable plane is the body-local z = 0 plane (a cylinder's axis is
/// local z); `orientation` +1: the cable travels counter-clockwise about
/// the plane normal as one walks along the cable, -1 clockwise (Fig. 3).
struct LinkDef {
  BodyId body = 0;
  LinkType type = LinkType::Attachment;
  int orientation = 1;
  Vec3 point = Vec3::Zero();
};

/// An open cable through `links` (at least two; the first and last are
/// attachments). `rest_lengths` (m), if given, holds one value per joint
/// (links - 1) and sets the initial slack; empty means taut at the start.
/// `compliance` (m/N) applies to every span (0: inextensible).
struct CableDef {
  std::string name;
  std::vector<LinkDef> links;
  double compliance = 0.0;
  std::vector<double> rest_lengths;
};

/// A link in the solver: the definition plus cached section radius (m) and
/// stored cable s (m), the length wrapped on the body (Alg. 2).
struct Link {
  BodyId body = 0;
  LinkType type = LinkType::Attachment;
  int orientation = 1;
  Vec3 point = Vec3::Zero();
  double radius = 0.0;
  double stored = 0.0;
};

/// The span between link j (where it leaves) and link j+1 (where it
/// arrives): one unilateral distance constraint of the World, whose
/// body-local anchors are the tangent points and whose rest length is the
/// cable in the span.
struct CableJoint {
  DistanceId constraint = 0;
};

struct Cable {
  std::string name;
  std::vector<Link> links;
  std::vector<CableJoint> joints;  // joints[j] joins links[j] and links[j+1]
};

/// All cables of a World. Registers a substep hook on construction that
/// moves tangent points and rest lengths before each position solve, so it
/// must outlive the World's stepping and is neither copied nor moved.
class CableSystem {
 public:
  explicit CableSystem(World& world);
  CableSystem(const CableSystem&) = delete;
  CableSystem& operator=(const CableSystem&) = delete;

  /// Adds a cable at the World's current poses: tangent points, initial
  /// rest lengths (taut unless given) and stored cable on rolling links.
  /// Throws std::invalid_argument for a definition that cannot be built
  /// (fewer than two links, rolling on a body without circular section,
  /// rolling end link, orientation not +-1, wrong rest_lengths size,
  /// no tangent between adjacent links).
  int addCable(const CableDef& def);

  /// Alg. 1 lines 2-7 and Alg. 2 lines 8-9 for every joint: new tangent
  /// points, rest lengths and stored cable from the current poses.
  void update();

  const std::vector<Cable>& cables() const { return cables_; }
  const World& world() const { return world_; }

  /// Tension (N), rest length (m) and current length (m) of joint j of
  /// cable c.
  double tension(int c, int j) const;
  double restLength(int c, int j) const;
  double length(int c, int j) const;
  /// World positions (m) of the tangent points of joint j of cable c.
  Vec3 startPoint(int c, int j) const;
  Vec3 endPoint(int c, int j) const;
  /// Rest lengths plus stored cable of cable c (m): conserved by update().
  double totalLength(int c) const;

 private:
  /// New body-local anchors (a, b) of joint j: tangent points on rolling
  /// links, the fixed points of attachments; nullopt if no tangent exists.
  std::optional<std::pair<Vec3, Vec3>> tangentAnchors(const Cable& cable, int j) const;
  void updateJoint(Cable& cable, int j);

  World& world_;
  std::vector<Cable> cables_;
};

}  // namespace reeve
