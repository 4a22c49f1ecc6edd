// Colours and proportions of rendered frames: one place to restyle them.
#pragma once

#include "reeve/engine/body.h"

namespace reeve::style {

using Colour = Eigen::Vector3f;  // linear 0..1 RGB

inline const Colour kBackground(0.93f, 0.94f, 0.95f);
inline const Colour kFloor(0.985f, 0.985f, 0.98f);
inline const Colour kGridMinor(0.80f, 0.81f, 0.83f);
inline const Colour kGridMajor(0.62f, 0.64f, 0.67f);
inline const Colour kCable(0.10f, 0.10f, 0.12f);
/// Link markers in the paper's colours (Fig. 7, 10): rolling red,
/// attachment green, pinhole blue. A hybrid link is shown red-green: a ball
/// in the colour of what it does now with a ring in the other colour round
/// it, facing the camera; rolling (cable left on the spool): red ball,
/// green ring; attached (cable used up, tied): green ball, red ring.
/// Inactive links (the cable does not touch them) get no marker.
inline const Colour kRollingMarker(0.86f, 0.12f, 0.10f);     // paper: rolling links red
inline const Colour kAttachmentMarker(0.12f, 0.66f, 0.22f);  // paper: attachments green
inline const Colour kPinholeMarker(0.13f, 0.36f, 0.92f);     // paper: pinholes blue
/// Shade of a body's colour for the outline of a section its rolling link
/// wraps where the body's own shape does not show it (a groove, a polygon).
inline constexpr float kSectionOutlineShade = 0.45f;

/// Opacity of cable hidden behind bodies, drawn through them.
inline constexpr float kHiddenCableAlpha = 0.6f;
/// Darkening of the accent sectors of round bodies.
inline constexpr float kAccentShade = 0.72f;
/// Cable tube radius in output pixels at the camera target's distance.
inline constexpr double kCableRadiusPx = 2.5;
/// Marker radius as a multiple of the cable radius.
inline constexpr double kMarkerScale = 2.3;
/// Hybrid marker ring: radius of its centre line and of its tube, as
/// multiples of the marker radius.
inline constexpr double kHybridRingRadius = 1.3;
inline constexpr double kHybridRingTube = 0.32;
/// A body smaller than a marker gets a ring in its colour round it, its
/// radius the body's size plus this multiple of the marker radius.
inline constexpr double kSmallBodyRingScale = 1.6;
/// Section outline tube radius as a multiple of the cable radius.
inline constexpr double kSectionOutlineScale = 0.45;
/// Spacing of the turns of a spool's coil as a multiple of the cable radius
/// (2: touching), and the coil's tube radius likewise.
inline constexpr double kCoilPitchScale = 2.2;
inline constexpr double kCoilTubeScale = 1.0;
/// Least thickness of a full coil (kMaxCoilTurns turns), as a multiple of
/// the cable radius: a spool whose section's inradius is smaller still
/// shows its cable paying out.
inline constexpr double kCoilMinBandScale = 8.0;
/// Grid lines across the floor, roughly (rounded to a 1-2-5 spacing).
inline constexpr double kGridLines = 16.0;

/// Colour of body `id`: blues for dynamic bodies, warm greys for static
/// ones, shade varying with the id so neighbours differ.
inline Colour bodyColour(BodyId id, bool is_static) {
  static const Colour dynamic[] = {{0.26f, 0.48f, 0.78f}, {0.36f, 0.60f, 0.86f},
                                   {0.20f, 0.38f, 0.66f}, {0.44f, 0.66f, 0.82f}};
  static const Colour fixed[] = {{0.62f, 0.59f, 0.55f}, {0.70f, 0.67f, 0.62f},
                                 {0.55f, 0.53f, 0.50f}};
  return is_static ? fixed[id % 3] : dynamic[id % 4];
}

}  // namespace reeve::style
