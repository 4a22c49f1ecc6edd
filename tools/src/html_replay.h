// `reeve run --html`: the run as a replay in one HTML file that opens
// offline in any browser (issue 31): the viewer's page and JavaScript
// (viewer/, with three.js installed from npm by tools/setup.sh) inline,
// and every frame's poses, cable paths and tensions as JSON.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "output_file.h"
#include "reeve/scene/scene.h"
#include "viewer_files.h"

namespace reeve {

/// Records a scene frame by frame and writes the replay page. The page
/// plays the frames at the scene's frame rate (pause, step, a time
/// slider), draws the bodies by their shapes and each cable coloured by
/// its highest span tension, plots the tensions of the cable picked, and
/// when it has played to the end writes what it plotted into
/// <pre id="reeve-status"> as JSON (what the tests read).
class HtmlReplay {
 public:
  /// Reads the viewer's files from viewerDir() (replay.html, replay.js,
  /// view3d.js and from node_modules three's module build and
  /// OrbitControls) and opens
  /// `path` (an OutputFile: nothing appears there before commit()).
  /// Throws ViewerMissing naming a missing file and how to install it.
  HtmlReplay(const std::filesystem::path& path, bool replace, const Scene& scene);
  /// Records the scene's state now (reeve run: t = 0, then every frame):
  /// poses, cable paths with spool coils, span tensions and end points,
  /// link markers. Throws std::runtime_error if a pose or tension is not
  /// finite.
  void record();
  /// Records cable events (CableSystem::takeEvents) for the timeline.
  void recordEvents(const std::vector<CableEvent>& events);
  /// Writes the page with the frames recorded and closes the file.
  void close();
  void commit() { out_.commit(); }

 private:
  OutputFile out_;
  const Scene& scene_;
  std::string page_, viewer_js_, view3d_js_, three_js_, orbit_js_;
  std::string times_, poses_, paths_, tensions_, spans_, markers_, events_;  // JSON arrays' contents so far
  int frames_ = 0;
};

}  // namespace reeve
