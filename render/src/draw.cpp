#include "draw.h"

#include <cmath>

#include <GL/gl.h>

namespace reeve {
namespace {

constexpr int kBodySegments = 72;

// Multiplies the model-view matrix by translate * rotate * scale.
void transform(const Vec3& translation, const Quat& rotation, const Vec3& scale) {
  Eigen::Affine3d m = Eigen::Translation3d(translation) * rotation * Eigen::Scaling(scale);
  glMultMatrixd(m.matrix().data());
}

void drawTwoTone(const TwoToneMesh& mesh, const style::Colour& colour) {
  setColour(colour);
  drawMesh(mesh.main);
  setColour(colour * style::kAccentShade);
  drawMesh(mesh.accent);
}

// 1, 2 or 5 times a power of ten, near `raw` (> 0).
double niceStep(double raw) {
  const double decade = std::pow(10.0, std::floor(std::log10(raw)));
  const double mantissa = raw / decade;
  return decade * (mantissa < 1.5 ? 1.0 : mantissa < 3.5 ? 2.0 : mantissa < 7.5 ? 5.0 : 10.0);
}

}  // namespace

ShapeMeshes::ShapeMeshes()
    : box(unitBox()),
      cylinder(unitCylinder(kBodySegments)),
      sphere(unitSphere(kBodySegments, kBodySegments / 2)),
      ring(unitTorus(style::kHybridRingTube / style::kHybridRingRadius, 2 * kTubeSides,
                     kTubeSides / 2)) {
  const TwoToneMesh coarse = unitSphere(kTubeSides, kTubeSides / 2);
  appendTransformed(ball, coarse.main, Eigen::Affine3d::Identity());
  appendTransformed(ball, coarse.accent, Eigen::Affine3d::Identity());
}

void drawMesh(const Mesh& mesh) {
  if (mesh.vertexCount() == 0) return;
  glVertexPointer(3, GL_FLOAT, 0, mesh.positions.data());
  glNormalPointer(GL_FLOAT, 0, mesh.normals.data());
  glDrawArrays(GL_TRIANGLES, 0, mesh.vertexCount());
}

void setColour(const style::Colour& colour, float alpha) {
  glColor4f(colour.x(), colour.y(), colour.z(), alpha);
}

void drawBody(const ShapeMeshes& meshes, const Shape& shape, const BodyState& body,
              const style::Colour& colour) {
  glPushMatrix();
  switch (shape.type) {
    case Shape::Type::Box:
      transform(body.x, body.q, shape.half_extents);
      setColour(colour);
      drawMesh(meshes.box);
      break;
    case Shape::Type::Cylinder:
      transform(body.x, body.q, Vec3(shape.radius, shape.radius, shape.half_length));
      drawTwoTone(meshes.cylinder, colour);
      break;
    case Shape::Type::Sphere:
      transform(body.x, body.q, Vec3::Constant(shape.radius));
      drawTwoTone(meshes.sphere, colour);
      break;
    case Shape::Type::Hull:
      transform(body.x, body.q, Vec3::Ones());
      setColour(colour);
      drawMesh(hullMesh(*shape.hull));  // rebuilt each draw: a hull has tens of triangles
      break;
  }
  glPopMatrix();
}

void drawBall(const ShapeMeshes& meshes, const Vec3& centre, double radius) {
  glPushMatrix();
  transform(centre, Quat::Identity(), Vec3::Constant(radius));
  drawMesh(meshes.ball);
  glPopMatrix();
}

void drawRing(const ShapeMeshes& meshes, const Vec3& centre, const Vec3& axis, double radius) {
  glPushMatrix();
  transform(centre, rotationBetween(Vec3::UnitZ(), axis), Vec3::Constant(radius));
  drawMesh(meshes.ring);
  glPopMatrix();
}

void drawFloor(double y, double centre_x, double centre_z, double half, float line_px) {
  const double x0 = centre_x - half, x1 = centre_x + half;
  const double z0 = centre_z - half, z1 = centre_z + half;
  // The fill sits behind the lines drawn on it.
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(1.0f, 1.0f);
  setColour(style::kFloor);
  glBegin(GL_QUADS);
  glVertex3d(x0, y, z0), glVertex3d(x0, y, z1), glVertex3d(x1, y, z1), glVertex3d(x1, y, z0);
  glEnd();
  glDisable(GL_POLYGON_OFFSET_FILL);

  const double step = niceStep(2.0 * half / style::kGridLines);
  glLineWidth(line_px);
  glBegin(GL_LINES);
  for (bool major : {false, true}) {  // major lines last, on top where they cross
    setColour(major ? style::kGridMajor : style::kGridMinor);
    for (long k = std::lround(std::ceil(x0 / step)); k * step <= x1; ++k)
      if ((k % 5 == 0) == major) glVertex3d(k * step, y, z0), glVertex3d(k * step, y, z1);
    for (long k = std::lround(std::ceil(z0 / step)); k * step <= z1; ++k)
      if ((k % 5 == 0) == major) glVertex3d(x0, y, k * step), glVertex3d(x1, y, k * step);
  }
  glEnd();
}

}  // namespace reeve
