// Mesh files of MJCF `<mesh>` assets: OBJ (its `v` and `f` records) and
// STL (binary or ASCII), and the mass properties of the solid a mesh
// bounds, as MuJoCo's compiler takes them (pyramids from a centre: exact
// for a closed mesh of outward triangles).
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "mjcf_model.h"

namespace reeve::mjcf {
namespace {

[[noreturn]] void bad(const std::string& path, int line, const std::string& what) {
  throw MeshError(path + (line > 0 ? ":" + std::to_string(line) : "") + ": " + what);
}

// OBJ: "v x y z" vertices, "f a b c ..." faces of 1-based (negative:
// from the end) indices, each maybe "a/t/n"; a polygon is fanned from its
// first corner. Everything else (normals, texture coordinates, groups,
// materials) is not needed for a solid.
TriangleMesh readObj(const std::string& path, std::istream& in) {
  TriangleMesh mesh;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    std::istringstream words(line);
    words.imbue(std::locale::classic());
    std::string tag;
    if (!(words >> tag)) continue;
    if (tag == "v") {
      Vec3 v;
      if (!(words >> v.x() >> v.y() >> v.z()) || !v.allFinite()) bad(path, number, "a vertex of three finite numbers, got \"" + line + "\"");
      mesh.vertices.push_back(v);
    } else if (tag == "f") {
      std::vector<int> corners;
      for (std::string word; words >> word;) {
        const int count = static_cast<int>(mesh.vertices.size());
        int index = 0;
        try {
          index = std::stoi(word.substr(0, word.find('/')));
        } catch (const std::exception&) {
          bad(path, number, "a face of vertex numbers, got \"" + word + "\"");
        }
        index = index < 0 ? count + index : index - 1;
        if (index < 0 || index >= count)
          bad(path, number, "a vertex number of 1 to " + std::to_string(count) + " so far, got " + word);
        corners.push_back(index);
      }
      if (corners.size() < 3) bad(path, number, "a face of at least 3 vertices, got " + std::to_string(corners.size()));
      for (std::size_t k = 1; k + 1 < corners.size(); ++k) mesh.triangles.push_back({corners[0], corners[k], corners[k + 1]});
    }
  }
  return mesh;
}

// STL: binary (an 80-byte header, a 32-bit count, 50 bytes a triangle) or
// ASCII ("solid", then "vertex x y z" three to a facet). Corners are not
// shared in STL: each triangle has its own three.
TriangleMesh readStl(const std::string& path, const std::string& bytes) {
  TriangleMesh mesh;
  const auto addCorner = [&](const Vec3& v, int line) {
    if (!v.allFinite()) bad(path, line, "finite vertex coordinates");
    mesh.vertices.push_back(v);
    if (mesh.vertices.size() % 3 == 0) {
      const int n = static_cast<int>(mesh.vertices.size());
      mesh.triangles.push_back({n - 3, n - 2, n - 1});
    }
  };
  std::uint32_t count = 0;
  if (bytes.size() >= 84) std::memcpy(&count, bytes.data() + 80, 4);
  if (bytes.size() >= 84 && bytes.size() == 84 + 50ull * count) {
    for (std::uint32_t t = 0; t < count; ++t)
      for (int corner = 0; corner < 3; ++corner) {
        float xyz[3];
        std::memcpy(xyz, bytes.data() + 84 + 50ull * t + 12 + 12 * corner, sizeof xyz);
        addCorner(Vec3(xyz[0], xyz[1], xyz[2]), 0);
      }
    return mesh;
  }
  if (bytes.compare(0, 5, "solid") != 0)
    bad(path, 0, "an STL file: binary (84 + 50 bytes a triangle) or ASCII (starting \"solid\"), got " +
                     std::to_string(bytes.size()) + " bytes of neither");
  std::istringstream in(bytes);
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    std::istringstream words(line);
    words.imbue(std::locale::classic());
    std::string tag;
    if (!(words >> tag) || tag != "vertex") continue;
    Vec3 v;
    if (!(words >> v.x() >> v.y() >> v.z())) bad(path, number, "a vertex of three numbers, got \"" + line + "\"");
    addCorner(v, number);
  }
  if (mesh.vertices.size() % 3 != 0) bad(path, 0, "vertices three to a facet, got " + std::to_string(mesh.vertices.size()));
  return mesh;
}

}  // namespace

TriangleMesh readMeshFile(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".obj" && ext != ".stl") bad(path, 0, "an .obj or .stl mesh (MuJoCo's .msh is not read)");
  // Looked at before opening, as a scene file is: a FIFO blocks, a device
  // never ends.
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) bad(path, 0, "a readable regular file");
  if (const auto bytes = std::filesystem::file_size(path, error); !error && bytes > kMaxMeshFileBytes)
    bad(path, 0, "at most " + std::to_string(kMaxMeshFileBytes) + " bytes, got " + std::to_string(bytes));
  std::ifstream in(path, std::ios::binary);
  if (!in) bad(path, 0, "a readable file");
  std::ostringstream text;
  text << in.rdbuf();
  TriangleMesh mesh;
  if (ext == ".obj") {
    std::istringstream stream(text.str());
    mesh = readObj(path, stream);
  } else {
    mesh = readStl(path, text.str());
  }
  if (mesh.triangles.empty()) bad(path, 0, "a mesh with triangles, got none");
  return mesh;
}

MeshMassProperties meshMassProperties(const TriangleMesh& mesh, bool legacy) {
  // MuJoCo's compiler: each triangle and an apex inside bound a pyramid of
  // volume (c - apex) . n A / 3 (c the triangle's centroid, n its unit
  // normal, A its area), whose centre of mass is 3/4 of the way from the
  // apex to c. First the apex is the area-weighted centroid of the
  // triangles, for the centre of mass; then the centre of mass, for the
  // volume and the second moments, integral of x x^T = V / 20 (a a^T +
  // b b^T + c c^T + s s^T) with s = a + b + c, the corners from the apex.
  // Exact for a closed mesh of outward triangles. `legacy` (MuJoCo's
  // default, exactmeshinertia="false") sums each pyramid's |volume|: the
  // same for a convex mesh; for others, and for meshes that are not
  // closed, it is what MuJoCo takes.
  struct Face {
    Vec3 centre, normal;
    double area;
  };
  std::vector<Face> faces;
  faces.reserve(mesh.triangles.size());
  double area = 0.0;
  Vec3 surface_centre = Vec3::Zero();
  for (const auto& t : mesh.triangles) {
    const Vec3 &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
    const Vec3 n = (b - a).cross(c - a);
    const double twice = n.norm();
    if (!(twice > 1e-15)) continue;  // as MuJoCo: a degenerate triangle adds nothing
    faces.push_back({(a + b + c) / 3.0, n / twice, twice / 2.0});
    area += twice / 2.0;
    surface_centre += twice / 2.0 * faces.back().centre;
  }
  MeshMassProperties out;
  if (!(area > 0.0)) return out;
  surface_centre /= area;
  const auto pyramid = [&](const Face& f, const Vec3& apex) {
    const double v = (f.centre - apex).dot(f.normal) * f.area / 3.0;
    return legacy ? std::abs(v) : v;
  };
  double volume = 0.0;
  Vec3 first = Vec3::Zero();
  for (const Face& f : faces) {
    const double v = pyramid(f, surface_centre);
    volume += v;
    first += v * (0.75 * f.centre + 0.25 * surface_centre);
  }
  if (!(volume > 0.0)) return out;
  const Vec3 centre = first / volume;
  volume = 0.0;
  Mat3 second = Mat3::Zero();
  std::size_t k = 0;
  for (const auto& t : mesh.triangles) {
    const Vec3 a = mesh.vertices[t[0]] - centre, b = mesh.vertices[t[1]] - centre, c = mesh.vertices[t[2]] - centre;
    if (!((b - a).cross(c - a).norm() > 1e-15)) continue;
    const double v = pyramid(faces[k++], centre);
    const Vec3 s = a + b + c;
    volume += v;
    second += v / 20.0 * (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
  }
  out.volume = volume;
  if (!(volume > 0.0)) return out;
  out.centroid = centre;
  out.inertia_unit_density = second.trace() * Mat3::Identity() - second;
  return out;
}

}  // namespace reeve::mjcf
