// Warnings for scenes that load but will likely not run as their author
// meant. `reeve validate` and `reeve run` print them; they never change an
// exit status.
#pragma once

#include <string>
#include <vector>

#include "reeve/scene/scene.h"

namespace reeve {

/// Something a scene that loads may not mean: `json_path` (RFC 6901) and
/// what is odd there.
struct SceneWarning {
  std::string json_path;
  std::string message;
};

/// A span may start past its rest length (a pretensioned cable), but not by
/// more than this fraction of it, and at least kStartStretchWarningMin_m.
inline constexpr double kStartStretchWarning = 0.1;
inline constexpr double kStartStretchWarningMin_m = 0.01;

/// Above this predicted cost (s of computing per simulated second) the
/// solver settings get a warning: a run that will take hours says so first.
inline constexpr double kSlowSceneWarning_s = 60.0;

/// Above this omega h a trapezoidal spring under Gauss-Seidel gets a
/// warning (hinge_joint.h: its first-order turns need it below about 1).
inline constexpr double kTrapezoidalOmegaH = 1.0;

/// The computing time (s, one core of a 2020s x86 machine) that stepping
/// `scene` with its current settings takes per simulated second, at most:
/// frame_rate_hz x substeps x (fixed work per substep + iterations x work
/// per iteration), each linear in the bodies, cable joints and joint rows,
/// with constants measured on the shipped scenes (DESIGN.md, "Cost
/// estimate"). The direct solver stops iterating once it converges, so it
/// often takes less; it is meant for orders of magnitude.
double predictedSecondsPerSimulatedSecond(const Scene& scene);

/// Warnings for a loaded, not yet stepped scene:
/// - cable spans that start more than kStartStretchWarning of their rest
///   length (and 1 cm) longer than it. The first solve pulls such a span
///   in at once, and a direct solve that must turn wheels radians to do it
///   can diverge (CableSystem::firstBreach). The fuzzer's first finding
///   was one.
/// - rest lengths given for spans that a frictionless pinhole or wrap
///   joins into one run (at "/cables/N/rest_length_m"): the run shares
///   its rest length in proportion to the spans' lengths, so they read
///   otherwise than given (their sum kept; issue 28, item 10).
/// - solver settings (at "/solver") that predict more than
///   kSlowSceneWarning_s per simulated second, with the prediction.
/// - Gauss-Seidel (at "/solver") with a trapezoidal spring whose omega h
///   passes kTrapezoidalOmegaH, omega^2 = k (1 / I_a + 1 / I_b) with each
///   body's inertia about the hinge's axle (k (1 / m_a + 1 / m_b) for a
///   slider's), and the substeps that bring it below.
std::vector<SceneWarning> sceneWarnings(const Scene& scene);

}  // namespace reeve
