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
inline const Colour kRollingMarker(0.86f, 0.12f, 0.10f);     // paper: rolling links red
inline const Colour kAttachmentMarker(0.12f, 0.66f, 0.22f);  // paper: attachments green

/// Opacity of cable hidden behind bodies, drawn through them.
inline constexpr float kHiddenCableAlpha = 0.6f;
/// Darkening of the accent sectors of round bodies.
inline constexpr float kAccentShade = 0.72f;
/// Cable tube radius in output pixels at the camera target's distance.
inline constexpr double kCableRadiusPx = 2.5;
/// Marker radius as a multiple of the cable radius.
inline constexpr double kMarkerScale = 2.3;
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
