// `reeve segment`'s model: a scene in which one cable is replaced by a
// chain of rigid cylinders joined by spherical joints (the segmented-rope
// baseline of the cable joints paper, sec. 5 and Fig. 14).
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>

#include "reeve/scene/scene.h"

namespace reeve {

struct SegmentOptions {
  std::string cable;                ///< name of the cable to replace
  int segments = 100;               ///< N >= 1
  double radius_m = 0.01;           ///< cylinder radius of each segment
  std::optional<double> rope_mass_kg;  ///< total; default 1 % of the lighter end body
  /// The output's solver budget ("solver": substeps, iterations); default
  /// the input's. A chain of light rods needs many substeps: each rod
  /// rocks on its wheel at about sqrt(T L / I), thousands of rad/s, and
  /// below about 30 substeps a frame at 60 Hz the chain does not hold.
  std::optional<int> substeps, iterations;
  std::string command_line;         ///< how it was made, for the description
};

/// Bad options or a cable a chain cannot stand for; what() is the message.
class SegmentError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The scene `input` (its JSON document) with cable `options.cable`
/// replaced: N cylinders "<cable>_seg_000", ... (local z along the
/// segment, "collides": true, rope mass split evenly) whose axes join the
/// vertices of clearChainVertices() along the cable's current path in
/// `scene` (the same document loaded), lifted off the sections it wraps
/// until every chord is at least the cylinders' radius from each (the
/// chord's part within that radius of the section's plane): the
/// rope's centre line rides a wheel of radius r at r + radius, as a real
/// rope's does, so the chain is longer than the cable by about radius x
/// the angle wrapped, and starts touching its wheels, not cut into them.
/// Each cylinder is shorter than its segment by 2 x radius (capped at half
/// of it) so that neighbours do not touch at the joints. Spherical joints
/// join neighbours at their shared vertex and the ends to the end links'
/// bodies at the attachment points. Bodies the cable wrapped get
/// "collides": true. Everything else is copied. Throws SegmentError (also
/// for a junction's branch).
nlohmann::ordered_json segmentScene(const nlohmann::ordered_json& input, const Scene& scene,
                            const SegmentOptions& options);

}  // namespace reeve
