// Scenes: JSON files (scenes/README.md, schema scenes/scene.schema.json)
// turned into a World with its hinges and joints and a CableSystem with its
// cables.
// Bad input gives a SceneError naming the file, the JSON path, what was
// expected and what was found; never a crash, never a silent default.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "reeve/cable/cable.h"
#include "reeve/engine/world.h"

namespace reeve {

/// Where a scene is viewed from: a pinhole camera at `eye` (m, world)
/// looking at `target` (m, world), with `up` (world, need not be unit) the
/// image's up direction and `fov_y_deg` the vertical field of view (deg).
struct CameraDef {
  Vec3 eye = Vec3::Zero();
  Vec3 target = Vec3::Zero();
  Vec3 up = Vec3::UnitY();
  double fov_y_deg = 40.0;
};

/// The kind of an entry of a scene's "joints" array.
enum class JointKind { Prismatic, Spherical, Fixed };

/// A loaded scene, ready to step: `world->step(1.0 / frame_rate_hz)` once
/// per frame for `frameCount()` frames. `cables` is built on `*world` and
/// has registered a substep hook in it, so keep the two together (do not
/// move one out alone); the members are declared so that `cables` is
/// destroyed before `world`.
struct Scene {
  std::string name;
  std::string description;
  double frame_rate_hz = 60.0;  ///< frames per simulated second, Hz
  double duration_s = 5.0;      ///< simulated time, s
  std::unique_ptr<World> world;
  std::unique_ptr<CableSystem> cables;
  std::optional<CameraDef> camera;
  /// The kind of each entry of "joints", in order: the k-th entry of a
  /// kind is World's k-th joint of it (prismatic(), spherical(),
  /// fixedJoint()). Hinges ("hinges") are World's hinges in order.
  std::vector<JointKind> joint_kinds;
  /// An imported model's parts that the scene does not carry, one line
  /// each (importMjcf); sceneWarnings() lists them in one warning.
  std::vector<std::string> not_imported;

  /// Number of frames to simulate: round(duration_s * frame_rate_hz).
  int frameCount() const;
};

/// An error in a scene. `file()` is the file (or source name), `jsonPath()`
/// a JSON Pointer (RFC 6901) to the offending value ("/bodies/2/shape/radius_m";
/// "" for the root or when no value applies), `expected()` and `found()`
/// describe what should have been there and what was.
///
/// what() is one of
///   "FILE: PATH: expected EXPECTED, got FOUND"   (PATH "(root)" for "")
///   "FILE:LINE: ELEMENT: expected EXPECTED, got FOUND"  (an imported
///                                                 model: atLine)
///   "FILE:LINE:COLUMN: invalid JSON: REASON"     (JSON syntax; expected()
///                                                 is "valid JSON", found() REASON)
///   "FILE: cannot read: REASON"                  (expected() is "a readable
///                                                 file", found() REASON)
class SceneError : public std::runtime_error {
 public:
  /// An error at `json_path` in `file`.
  SceneError(std::string file, std::string json_path, std::string expected, std::string found);

  /// A JSON syntax error at 1-based `line` and `column` (in characters):
  /// where the parser stopped, the last character of the offending token.
  static SceneError syntax(std::string file, int line, int column, std::string reason);
  /// A file that cannot be read, `reason` as from strerror.
  static SceneError unreadable(std::string file, std::string reason);
  /// An error in an imported model (an MJCF file, mjcf.h) at 1-based
  /// `line`, in `element` (`<joint name="elbow">`), held in jsonPath():
  /// "FILE:LINE: ELEMENT: expected EXPECTED, got FOUND".
  static SceneError atLine(std::string file, int line, std::string element, std::string expected, std::string found);

  const std::string& file() const { return file_; }
  const std::string& jsonPath() const { return json_path_; }
  const std::string& expected() const { return expected_; }
  const std::string& found() const { return found_; }
  /// 1-based position of a JSON syntax error; 0 for other errors.
  int line() const { return line_; }
  int column() const { return column_; }

 private:
  SceneError(const std::string& what, std::string file, std::string json_path, std::string expected,
             std::string found, int line, int column);

  std::string file_, json_path_, expected_, found_;
  int line_ = 0, column_ = 0;
};

/// Largest scene file loadScene() reads (bytes): 100 times the largest
/// shipped scene (hilbert3.json, 170 kB, 512 wheels).
inline constexpr std::uintmax_t kMaxSceneFileBytes = 16u << 20;

/// What one scene document may make the loader spend (issue 27). Past any
/// of these parseScene() throws a SceneError at the JSON path where the
/// limit was passed, before anything walks the document, so no input can
/// exhaust the stack or memory (scenes/README.md, "Limits"). The shipped
/// scenes nest 6 deep, hold at most 513 bodies and links, and describe
/// themselves in at most 3.1 kB.
inline constexpr int kMaxSceneDepth = 64;                    ///< arrays and objects nested in each other
inline constexpr std::size_t kMaxSceneStringBytes = 65536;   ///< one string or key, bytes of UTF-8
inline constexpr std::size_t kMaxSceneArrayLength = 100000;  ///< elements of one array ("bodies" too)
inline constexpr std::size_t kMaxSceneObjectMembers = 1000;  ///< keys of one object
inline constexpr std::size_t kMaxSceneJoints = 100000;       ///< entries of "hinges" and "joints" together
inline constexpr std::size_t kMaxSceneLinks = 100000;        ///< links of all cables together

/// Reads and builds the scene in the JSON file at `path`, or imports the
/// MuJoCo model there when it ends in .xml (mjcf.h: importMjcf).
/// Throws SceneError if the file cannot be read, is not a regular file (a
/// FIFO, a device such as /dev/zero, a folder: refused before it is
/// opened, so nothing blocks), is larger than kMaxSceneFileBytes, or the
/// scene is invalid.
Scene loadScene(const std::filesystem::path& path);

/// Builds the scene in `json_text`; `source_name` names it in errors (a file
/// name, "<stdin>", ...). Checks, in order: JSON syntax (and duplicate keys),
/// the schema sceneSchemaJson(), then what a schema cannot say (unique and
/// known body names, density or mass, where each link type may be in a
/// cable, polygon sections of non-zero area, rest length counts, non-zero
/// axes, joint limits with lower <= upper and angles in [-pi, pi], cables
/// the solver can build).
/// Throws SceneError at the first problem.
Scene parseScene(const std::string& json_text, const std::string& source_name);

/// The scene format's name of a solver method (`solver.method`):
/// "direct" or "gauss-seidel".
const char* solverMethodName(SolverKind method);
/// The solver method called `name` in the scene format, if there is one.
std::optional<SolverKind> solverMethodFromName(std::string_view name);

/// The text of scenes/simple.json (paper Fig. 12, left), embedded at build
/// time so programs work from any folder.
std::string_view defaultSceneJson();

/// The text of scenes/scene.schema.json (JSON Schema draft-07), embedded at
/// build time; parseScene validates against it.
std::string_view sceneSchemaJson();

}  // namespace reeve
