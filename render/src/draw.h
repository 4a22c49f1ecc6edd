// Fixed-function OpenGL drawing of the scene's pieces, in the current
// context with the camera's matrices loaded.
#pragma once

#include "meshes.h"
#include "reeve/engine/body.h"
#include "style.h"

namespace reeve {

/// Facets around a cable tube.
inline constexpr int kTubeSides = 16;

/// The tessellated unit shapes, built once per context.
struct ShapeMeshes {
  Mesh box;
  TwoToneMesh cylinder, sphere;  // bodies
  Mesh ball;                     // cable ends and markers, coarser
  Mesh ring;                     // hybrid markers: torus of radius 1
  ShapeMeshes();
};

/// Sets the colour (and alpha) used by lit and unlit drawing.
void setColour(const style::Colour& colour, float alpha = 1.0f);

/// A body's shape at its pose, lit, in `colour` (accents darker).
void drawBody(const ShapeMeshes& meshes, const Shape& shape, const BodyState& body,
              const style::Colour& colour);

/// `mesh` as it is, in the current colour and model-view.
void drawMesh(const Mesh& mesh);

/// A ball of `radius` (m) at `centre` (m, world), in the current colour.
void drawBall(const ShapeMeshes& meshes, const Vec3& centre, double radius);

/// A ring (torus) of centre-line radius `radius` (m) about `centre` (m,
/// world), its axis along `axis` (unit), in the current colour; the tube's
/// radius is style::kHybridRingTube / style::kHybridRingRadius of it.
void drawRing(const ShapeMeshes& meshes, const Vec3& centre, const Vec3& axis, double radius);

/// The floor: a square at height `y` (m) centred under (`centre_x`,
/// `centre_z`) with half side `half` (m), filled and ruled by a 1-2-5 grid
/// (every fifth line darker), lines `line_px` pixels wide, unlit.
void drawFloor(double y, double centre_x, double centre_z, double half, float line_px);

}  // namespace reeve
