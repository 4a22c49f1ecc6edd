// `reeve view` (issue 31): a local HTTP server that steps a scene in real
// time while a page watches and streams it to the live page
// (viewer/live.html) in a browser, which sends its controls back. cpp-httplib (Debian's libcpp-httplib-dev;
// DESIGN.md, "The live view": why HTTP streaming, not WebSockets).
//
//   GET  /                the page; GET /viewer/NAME its scripts and
//                         three.js (only those: every other path is 404)
//   GET  /stream          the messages (live_scene.h), chunked, as they come
//   POST /control         a command (LiveScene::command) as application/json:
//                         200 {"ok": true} or 400 {"error": "..."}
#pragma once

#include <atomic>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "live_scene.h"

namespace reeve {

struct ViewOptions {
  std::filesystem::path scene;     ///< empty: the built-in simple.json; watched for edits
  /// The scene's JSON instead of a file (Python's Scene.view()); `scene`
  /// then only names it, and nothing is watched.
  std::optional<std::string> scene_text;
  std::string host = "127.0.0.1";  ///< address to listen on
  int port = 8765;                 ///< 0: any free port
  LiveScene::Overrides overrides;
};

/// Streams at most this many pages at once (each holds a server thread).
inline constexpr int kMaxStreams = 4;

class ViewServer {
 public:
  /// Loads the scene and the viewer's files and binds host:port. Throws
  /// SceneError, ViewerMissing, or std::runtime_error when it cannot
  /// listen there.
  explicit ViewServer(const ViewOptions& options);
  /// Stops (stop()) if running.
  ~ViewServer();
  ViewServer(const ViewServer&) = delete;
  ViewServer& operator=(const ViewServer&) = delete;

  /// The port it listens on.
  int port() const;
  /// "http://HOST:PORT/".
  std::string url() const;
  /// Starts serving and stepping, on threads of its own.
  void start();
  /// Ends every stream, stops serving and stepping, joins the threads.
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// `reeve view`: serves until SIGINT or SIGTERM, then stops cleanly and
/// returns 0; 2 for an invalid scene, 1 for a missing viewer or an
/// address it cannot listen on.
int viewCommand(const ViewOptions& options);

}  // namespace reeve
