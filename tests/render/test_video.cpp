#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <map>
#include <optional>
#include <string>

#include "atwood_rig.h"
#include "reeve/render/renderer.h"
#include "reeve/render/video.h"
#include "temp_dir.h"

namespace reeve::test_video {
namespace {

// Stream facts from ffprobe: key -> value (width, height, nb_read_frames).
std::map<std::string, std::string> probe(const std::filesystem::path& video) {
  const std::string command =
      "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
      "stream=nb_read_frames,width,height,codec_name,pix_fmt -of default=noprint_wrappers=1 '" +
      video.string() + "'";
  std::map<std::string, std::string> facts;
  FILE* out = popen(command.c_str(), "r");
  if (!out) return facts;
  char line[256];
  while (std::fgets(line, sizeof line, out)) {
    std::string s(line);
    const auto eq = s.find('=');
    if (eq != std::string::npos) facts[s.substr(0, eq)] = s.substr(eq + 1, s.find('\n') - eq - 1);
  }
  pclose(out);
  return facts;
}

// Sets PATH for the scope, restores it after.
class PathOverride {
 public:
  explicit PathOverride(const std::string& path) {
    if (const char* old = std::getenv("PATH")) old_ = old;
    setenv("PATH", path.c_str(), 1);
  }
  ~PathOverride() {
    if (old_) setenv("PATH", old_->c_str(), 1);
    else unsetenv("PATH");
  }

 private:
  std::optional<std::string> old_;
};

constexpr int kWidth = 320, kHeight = 180, kFrames = 12;

TEST(VideoWriter, WritesAnH264Mp4WithEveryFrame) {
  test::TempDir dir;
  const auto path = dir.path() / "atwood.mp4";
  test::AtwoodRig rig;
  Renderer renderer(kWidth, kHeight);
  const Camera camera = frameScene(rig.world, rig.cables, double(kWidth) / kHeight);
  VideoWriter video(path, kWidth, kHeight, 30.0);
  for (int f = 0; f < kFrames; ++f) {
    rig.run(1);
    video.add(renderer.render(rig.world, rig.cables, camera));
  }
  video.finish();
  auto facts = probe(path);
  EXPECT_EQ(facts["width"], std::to_string(kWidth));
  EXPECT_EQ(facts["height"], std::to_string(kHeight));
  EXPECT_EQ(facts["nb_read_frames"], std::to_string(kFrames));
  EXPECT_EQ(facts["codec_name"], "h264");
  EXPECT_EQ(facts["pix_fmt"], "yuv420p");
  EXPECT_NO_THROW(video.finish());  // a second finish does nothing
}

TEST(VideoWriter, DestructorFinishesTheVideo) {
  test::TempDir dir;
  const auto path = dir.path() / "grey.mp4";
  {
    VideoWriter video(path, 64, 32, 24.0);
    const Image grey{64, 32, std::vector<std::uint8_t>(64 * 32 * 3, 128)};
    for (int f = 0; f < 5; ++f) video.add(grey);
  }
  EXPECT_EQ(probe(path)["nb_read_frames"], "5");
}

TEST(VideoWriter, MissingFfmpegThrowsSayingSo) {
  test::TempDir empty;
  PathOverride path(empty.path().string());
  try {
    VideoWriter video(empty.path() / "x.mp4", 64, 32, 30.0);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("ffmpeg program not found on PATH"), std::string::npos)
        << e.what();
  }
}

TEST(VideoWriter, FfmpegFailureReportsItsExitStatus) {
  test::TempDir dir;
  const Image black{64, 32, std::vector<std::uint8_t>(64 * 32 * 3, 0)};
  try {
    VideoWriter video(dir.path() / "missing_dir" / "x.mp4", 64, 32, 30.0);
    video.add(black);  // may already see ffmpeg gone
    video.finish();
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("exit status"), std::string::npos) << e.what();
  }
}

TEST(VideoWriter, RejectsBadSizesAndFrames) {
  test::TempDir dir;
  EXPECT_THROW(VideoWriter(dir.path() / "odd.mp4", 65, 32, 30.0), std::invalid_argument);
  EXPECT_THROW(VideoWriter(dir.path() / "fps.mp4", 64, 32, 0.0), std::invalid_argument);
  VideoWriter video(dir.path() / "x.mp4", 64, 32, 30.0);
  EXPECT_THROW(video.add(Image{32, 32, std::vector<std::uint8_t>(32 * 32 * 3)}),
               std::invalid_argument);
  video.add(Image{64, 32, std::vector<std::uint8_t>(64 * 32 * 3, 200)});
  video.finish();
  EXPECT_THROW(video.add(Image{64, 32, std::vector<std::uint8_t>(64 * 32 * 3)}),
               std::logic_error);
}

}  // namespace
}  // namespace reeve::test_video
