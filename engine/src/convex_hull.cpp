#include "reeve/engine/convex_hull.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <stdexcept>
#include <string>

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

namespace reeve {
namespace {

constexpr const char* kFlat = "convex hull: the points span no volume (they lie on a plane or a line)";

// Faces of the hull of `points` through qhull, which merges coplanar
// triangles ('C-0', its default). Vertex indices refer to `points`.
std::vector<ConvexHull::Face> qhullFaces(const std::vector<Vec3>& points) {
  std::vector<coordT> coords;
  for (const Vec3& p : points) coords.insert(coords.end(), {p.x(), p.y(), p.z()});
  // qhull prints its errors to a stream: keep them off stderr, as the
  // caller's exception (kFlat) says it plainly.
  char* message = nullptr;
  std::size_t message_size = 0;
  FILE* err = open_memstream(&message, &message_size);
  qhT qh_storage;
  qhT* qh = &qh_storage;  // the FORALL macros name it qh
  qh_zero(qh, err);
  char options[] = "qhull";
  const int exit_code = qh_new_qhull(qh, 3, static_cast<int>(points.size()), coords.data(),
                                     False, options, nullptr, err);
  std::vector<ConvexHull::Face> faces;
  if (exit_code == 0) {
    facetT* facet;
    FORALLfacets {
      ConvexHull::Face face;
      face.normal = Vec3(facet->normal[0], facet->normal[1], facet->normal[2]);
      setT* ordered = qh_facet3vertex(qh, facet);  // cyclic order, either sense
      vertexT *vertex, **vertexp;
      FOREACHvertex_(ordered) face.vertices.push_back(qh_pointid(qh, vertex->point));
      qh_settempfree(qh, &ordered);
      faces.push_back(std::move(face));
    }
  }
  qh_freeqhull(qh, !qh_ALL);
  int curlong = 0, totlong = 0;
  qh_memfreeshort(qh, &curlong, &totlong);
  std::fclose(err);
  std::free(message);
  if (exit_code != 0)  // with finite points, a flat input is what qhull rejects
    throw std::invalid_argument(kFlat);
  return faces;
}

}  // namespace

std::shared_ptr<const ConvexHull> makeConvexHull(const std::vector<Vec3>& points, bool keep_frame) {
  if (points.size() < 4)
    throw std::invalid_argument("convex hull: needs at least 4 points, got " +
                                std::to_string(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!points[i].allFinite())
      throw std::invalid_argument("convex hull: point " + std::to_string(i) + " is not finite");
  Vec3 lo = points[0], hi = points[0];
  for (const Vec3& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const double size = (hi - lo).norm();
  if (!(size > 0.0)) throw std::invalid_argument(kFlat);
  std::vector<ConvexHull::Face> faces = qhullFaces(points);

  auto hull = std::make_shared<ConvexHull>();
  std::map<int, int> index;  // input point -> hull vertex
  for (ConvexHull::Face& face : faces) {
    for (int& v : face.vertices) {
      const auto [it, added] = index.emplace(v, static_cast<int>(hull->vertices.size()));
      if (added) hull->vertices.push_back(points[v]);
      v = it->second;
    }
    // Newell's normal of the polygon gives its sense; make it outward.
    Vec3 newell = Vec3::Zero();
    for (std::size_t i = 0; i < face.vertices.size(); ++i)
      newell += hull->vertices[face.vertices[i]].cross(
          hull->vertices[face.vertices[(i + 1) % face.vertices.size()]]);
    if (newell.dot(face.normal) < 0.0) std::reverse(face.vertices.begin(), face.vertices.end());
    face.normal.normalize();
  }
  hull->faces = std::move(faces);

  // Mass properties by tetrahedra from an inside point o to each face's
  // fan triangles: volume, centroid and the second moment S = int x x^T dV,
  // with S_tet = V/20 (sum p_i p_i^T + (sum p_i)(sum p_i)^T) over its corners.
  Vec3 o = Vec3::Zero();
  for (const Vec3& v : hull->vertices) o += v;
  o /= static_cast<double>(hull->vertices.size());
  double volume = 0.0;
  Vec3 first = Vec3::Zero();
  Mat3 second = Mat3::Zero();
  for (const ConvexHull::Face& face : hull->faces) {
    const Vec3 a = hull->vertices[face.vertices[0]] - o;
    for (std::size_t i = 1; i + 1 < face.vertices.size(); ++i) {
      const Vec3 b = hull->vertices[face.vertices[i]] - o;
      const Vec3 c = hull->vertices[face.vertices[i + 1]] - o;
      const double v = a.dot(b.cross(c)) / 6.0;
      const Vec3 sum = a + b + c;
      volume += v;
      first += v * sum / 4.0;
      second += v / 20.0 * (a * a.transpose() + b * b.transpose() + c * c.transpose() +
                            sum * sum.transpose());
    }
  }
  if (!(volume > 1e-12 * size * size * size)) throw std::invalid_argument(kFlat);
  const Vec3 centroid = first / volume;  // relative to o
  const Mat3 central = second / volume - centroid * centroid.transpose();  // per unit mass
  hull->volume = volume;
  hull->inertia_per_mass = central.trace() * Mat3::Identity() - central;
  const Vec3 centre = o + centroid;
  if (keep_frame)  // about the origin, by parallel axes
    hull->inertia_per_mass += centre.squaredNorm() * Mat3::Identity() - centre * centre.transpose();
  else
    hull->input_centre_of_mass = centre;
  for (Vec3& v : hull->vertices) {
    v -= hull->input_centre_of_mass;
    hull->bounding_radius = std::max(hull->bounding_radius, v.norm());
  }
  return hull;
}

std::vector<Vec2> planeSection(const ConvexHull& hull, double z) {
  std::vector<Vec2> points;
  planeSection(hull, z, points);
  return points;
}

void planeSection(const ConvexHull& hull, double z, std::vector<Vec2>& points) {
  points.clear();
  double lo = hull.vertices[0].z(), hi = lo;
  for (const Vec3& v : hull.vertices) lo = std::min(lo, v.z()), hi = std::max(hi, v.z());
  if (!(z > lo && z < hi)) return;
  for (const ConvexHull::Face& face : hull.faces)
    for (std::size_t i = 0; i < face.vertices.size(); ++i) {
      const Vec3& p = hull.vertices[face.vertices[i]];
      const Vec3& q = hull.vertices[face.vertices[(i + 1) % face.vertices.size()]];
      if ((p.z() - z) * (q.z() - z) > 0.0 || p.z() == q.z()) continue;
      const double t = (z - p.z()) / (q.z() - p.z());
      points.emplace_back(p.x() + t * (q.x() - p.x()), p.y() + t * (q.y() - p.y()));
    }
}

std::optional<Vec3> nearestHullPoint(const ConvexHull& hull, const Vec3& p) {
  // The nearest point lies on a face whose plane p is outside of (p - x
  // lies in the normal cone at x, spanned by the normals of the faces
  // through x): there, p's projection onto the plane if the face holds
  // it, else the nearest point of the face's edges.
  std::optional<Vec3> nearest;
  double best = 0.0;
  for (const ConvexHull::Face& face : hull.faces) {
    const double height = face.normal.dot(p - hull.vertices[face.vertices[0]]);
    if (height <= 0.0) continue;
    const Vec3 foot = p - height * face.normal;
    bool inside = true;
    Vec3 candidate = foot;
    double distance2 = height * height;
    for (std::size_t i = 0; i < face.vertices.size(); ++i) {
      const Vec3& u = hull.vertices[face.vertices[i]];
      const Vec3& v = hull.vertices[face.vertices[(i + 1) % face.vertices.size()]];
      if ((v - u).cross(foot - u).dot(face.normal) >= 0.0) continue;  // inside this edge (counter-clockwise)
      if (inside) distance2 = INFINITY;
      inside = false;
      const Vec3 edge = v - u;
      const double t = std::clamp(edge.dot(p - u) / edge.squaredNorm(), 0.0, 1.0);
      const Vec3 q = u + t * edge;
      if ((p - q).squaredNorm() < distance2) distance2 = (p - q).squaredNorm(), candidate = q;
    }
    if (!nearest || distance2 < best) nearest = candidate, best = distance2;
  }
  return nearest;
}

}  // namespace reeve
