// Errors before the schema: unreadable files and JSON syntax.
#include <sys/stat.h>

#include <cstdio>
#include <fstream>

#include "scene_test_util.h"

namespace reeve::test {
namespace {

// The position is where the parser stopped: the last character of the
// offending token (here the closing quote of "bodies").
TEST(JsonErrors, MissingCommaGivesLineAndColumn) {
  const std::optional<SceneError> e =
      errorOf("{\n  \"name\": \"x\",\n  \"solver\": {}\n  \"bodies\": []\n}\n");
  ASSERT_TRUE(e);
  EXPECT_EQ(e->line(), 4);
  EXPECT_EQ(e->column(), 10);
  EXPECT_EQ(e->jsonPath(), "");
  EXPECT_EQ(e->expected(), "valid JSON");
  EXPECT_NE(e->found().find("syntax error while parsing object"), std::string::npos) << e->what();
  EXPECT_EQ(std::string(e->what()), "test.json:4:10: invalid JSON: " + e->found());
}

TEST(JsonErrors, TrailingCommaGivesLineAndColumn) {
  const std::optional<SceneError> e = errorOf("{\"name\": \"x\",\n \"bodies\": [1, 2,]}");
  ASSERT_TRUE(e);
  EXPECT_EQ(e->line(), 2);
  EXPECT_EQ(e->column(), 18);
  EXPECT_NE(e->found().find("unexpected ']'"), std::string::npos) << e->what();
}

TEST(JsonErrors, ColumnCountsCharactersNotBytes) {
  // "é" is two bytes in UTF-8 but one column.
  const std::optional<SceneError> e = errorOf("{\"name\": \"\xC3\xA9\" x}");
  ASSERT_TRUE(e);
  EXPECT_EQ(e->line(), 1);
  EXPECT_EQ(e->column(), 14);
}

TEST(JsonErrors, EmptyTextIsASyntaxError) {
  const std::optional<SceneError> e = errorOf("");
  ASSERT_TRUE(e);
  EXPECT_EQ(std::string(e->what()).rfind("test.json:1:1: invalid JSON: ", 0), 0u) << e->what();
  EXPECT_NE(e->found().find("unexpected end of input"), std::string::npos);
}

TEST(JsonErrors, NumberTooLargeForADoubleIsASyntaxError) {
  const std::optional<SceneError> e = errorOf("{\n  \"duration_s\": 1e400\n}");
  ASSERT_TRUE(e);
  EXPECT_EQ(e->line(), 2);
  EXPECT_EQ(e->column(), 21);
  EXPECT_NE(e->found().find("number overflow parsing '1e400'"), std::string::npos) << e->what();
}

TEST(JsonErrors, RepeatedKeyIsRejectedNotSilentlyOverwritten) {
  expectError(baseWith(R"("radius_m": 0.2})", R"("radius_m": 0.2, "radius_m": 0.3})"),
              "/bodies/2/shape/radius_m", "each key at most once", "\"radius_m\" a second time");
}

TEST(JsonErrors, UnreadableFileNamesFileAndReason) {
  const std::string missing = (kScenesDir / "no_such_scene.json").string();
  try {
    loadScene(missing);
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.file(), missing);
    EXPECT_EQ(e.jsonPath(), "");
    EXPECT_EQ(e.expected(), "a readable file");
    EXPECT_EQ(e.found(), "No such file or directory");
    EXPECT_EQ(std::string(e.what()), missing + ": cannot read: No such file or directory");
  }
}

// What loadScene() says about `path` (it must refuse it).
std::string refusal(const std::filesystem::path& path) {
  try {
    loadScene(path);
  } catch (const SceneError& e) {
    EXPECT_EQ(e.expected(), "a readable file");
    return e.what();
  }
  ADD_FAILURE() << path << " loaded";
  return "";
}

TEST(JsonErrors, FolderIsUnreadable) {
  EXPECT_EQ(refusal(kScenesDir), kScenesDir.string() + ": cannot read: a folder, not a regular file");
}

TEST(JsonErrors, DevicesAndFifosAreRefusedBeforeTheyAreOpened) {
  // /dev/zero never ends; opening a FIFO with no writer never returns.
  EXPECT_EQ(refusal("/dev/zero"), "/dev/zero: cannot read: a device, not a regular file");
  const std::filesystem::path fifo = std::filesystem::temp_directory_path() / "reeve_scene_test_fifo.json";
  std::filesystem::remove(fifo);
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(refusal(fifo), fifo.string() + ": cannot read: a FIFO (named pipe), not a regular file");
  std::filesystem::remove(fifo);
}

TEST(JsonErrors, AFileLargerThanTheLimitIsRefusedUnread) {
  // One byte over: a sparse file, so nothing is written to disk.
  const std::filesystem::path big = std::filesystem::temp_directory_path() / "reeve_scene_test_big.json";
  { std::ofstream touch(big); }
  std::filesystem::resize_file(big, kMaxSceneFileBytes + 1);
  EXPECT_EQ(refusal(big), big.string() + ": cannot read: " + std::to_string(kMaxSceneFileBytes + 1) +
                              " bytes, more than a scene may have (" + std::to_string(kMaxSceneFileBytes) + ")");
  std::filesystem::resize_file(big, 0);  // at the limit a valid scene still loads
  {
    std::ofstream out(big);
    out << kBase;
  }
  std::filesystem::resize_file(big, kMaxSceneFileBytes);  // padded with NULs: not JSON, but read
  try {
    loadScene(big);
  } catch (const SceneError& e) {
    EXPECT_EQ(e.expected(), "valid JSON") << e.what();
  }
  std::filesystem::remove(big);
}

TEST(JsonErrors, LoadSceneErrorsNameTheFile) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / "reeve_scene_test_bad_radius.json";
  {
    std::ofstream out(path);
    out << baseWith(R"("radius_m": 0.2})", R"("radius_m": -0.2})");
  }
  try {
    loadScene(path);
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.file(), path.string());
    EXPECT_EQ(std::string(e.what()),
              path.string() + ": /bodies/2/shape/radius_m: expected a number > 0, got -0.2");
  }
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace reeve::test
