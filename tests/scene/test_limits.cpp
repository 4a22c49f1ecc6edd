// What a document may make the loader spend (scene.h, kMaxSceneDepth ...):
// each limit passed is a SceneError at the JSON path where it was passed,
// and one step below it is not.
#include <string>

#include "scene_test_util.h"

namespace reeve::test {
namespace {

// `levels` arrays nested in "bodies": [[[...]]].
std::string nestedBodies(std::size_t levels) {
  return R"({"name": "deep", "solver": {}, "bodies": )" + std::string(levels, '[') + std::string(levels, ']') + "}";
}

// "/bodies" followed by `n` times "/0".
std::string firstOfNested(std::size_t n) {
  std::string pointer = "/bodies";
  for (std::size_t i = 0; i < n; ++i) pointer += "/0";
  return pointer;
}

// `n` comma-separated copies of `item`.
std::string repeated(const std::string& item, std::size_t n) {
  std::string text;
  text.reserve(n * (item.size() + 1));
  for (std::size_t i = 0; i < n; ++i) text += (i ? "," : "") + item;
  return text;
}

// The issue's file: a million arrays nested in "bodies" (2 MB) crashed the
// loader's recursive walks with a stack overflow. The root object is level
// 1 and "bodies" level 2, so the array refused is the 65th level.
TEST(Limits, AMillionNestedArraysAreRefusedWhereTheDepthIsPassed) {
  const std::string text = nestedBodies(1000000);
  ASSERT_GT(text.size(), 2000000u);
  expectError(text, firstOfNested(kMaxSceneDepth - 1), "nested at most 64 deep", "one more level");
}

TEST(Limits, NestingAtTheLimitIsLeftToTheSchema) {
  const std::optional<SceneError> at_limit = errorOf(nestedBodies(kMaxSceneDepth - 1));
  ASSERT_TRUE(at_limit);
  EXPECT_EQ(at_limit->expected().find("nested"), std::string::npos) << at_limit->what();
  expectError(nestedBodies(kMaxSceneDepth), firstOfNested(kMaxSceneDepth - 1), "nested at most 64 deep",
              "one more level");
}

TEST(Limits, ALongStringOrKeyIsRefusedAtItsPath) {
  const std::string at_limit(kMaxSceneStringBytes, 'x'), over(kMaxSceneStringBytes + 1, 'x');
  const std::optional<SceneError> ok = errorOf(with(kBase, "\"solver\": {}", "\"solver\": 1, \"description\": \"" + at_limit + "\""));
  ASSERT_TRUE(ok);
  EXPECT_EQ(ok->jsonPath(), "/solver") << ok->what();  // the schema's error, past the string
  expectError(baseWith("\"name\": \"base\"", "\"name\": \"" + over + "\""), "/name",
              "a string of at most 65536 bytes", "65537 bytes");
  expectError(baseWith("\"solver\": {}", "\"solver\": {\"" + over + "\": 1}"), "/solver",
              "a string of at most 65536 bytes (keys too)", "a key of 65537 bytes");
}

TEST(Limits, ALongArrayIsRefusedAtTheFirstElementTooMany) {
  const std::string over = repeated("0", kMaxSceneArrayLength + 1);
  expectError(baseWith("\"solver\": {}", "\"solver\": {}, \"x\": [[" + over + "]]"), "/x/0/100000",
              "at most 100000 elements in an array", "more");
  const std::optional<SceneError> at_limit =
      errorOf(baseWith("\"solver\": {}", "\"solver\": {}, \"x\": [[" + repeated("0", kMaxSceneArrayLength) + "]]"));
  ASSERT_TRUE(at_limit);
  EXPECT_EQ(at_limit->jsonPath(), "/x") << at_limit->what();  // the schema refuses "x"
}

TEST(Limits, AnObjectWithTooManyKeysIsRefusedAtTheObject) {
  std::string members;
  for (std::size_t k = 0; k <= kMaxSceneObjectMembers; ++k) members += (k ? ",\"k" : "\"k") + std::to_string(k) + "\": 0";
  expectError(baseWith("\"solver\": {}", "\"solver\": {" + members + "}"), "/solver",
              "at most 1000 keys in an object", "more");
}

// Counted before the schema looks at the entries, so a refused document
// costs no validation: the entries here are not even objects.
TEST(Limits, HingesAndJointsTogetherAreBounded) {
  const std::string hinge = R"("hinges": [{"body": "wheel", "anchor_m": [0, 0, 0], "axis": [0, 0, 1]}])";
  expectError(with(kBase, hinge, "\"hinges\": [" + repeated("0", 60000) + "], \"joints\": [" + repeated("0", 40001) + "]"),
              "/joints/40000", "at most 100000 hinges and joints together", "100001");
  const std::optional<SceneError> at_limit =
      errorOf(with(kBase, hinge, "\"hinges\": [" + repeated("0", 60000) + "], \"joints\": [" + repeated("0", 40000) + "]"));
  ASSERT_TRUE(at_limit);
  EXPECT_EQ(at_limit->jsonPath(), "/hinges/0") << at_limit->what();  // the schema's error
}

TEST(Limits, LinksOfAllCablesTogetherAreBounded) {
  const auto scene = [](std::size_t last_links) {
    const std::string cable = R"({"name": "c", "links": [)" + repeated("0", 50000) + "]}";
    return R"({"name": "n", "solver": {}, "bodies": [], "cables": [)" + cable + "," + cable +
           R"(, {"name": "d", "links": [)" + repeated("0", last_links) + "]}]}";
  };
  expectError(scene(1), "/cables/2/links/0", "at most 100000 links in all cables together", "more");
  const std::optional<SceneError> at_limit = errorOf(scene(0));
  ASSERT_TRUE(at_limit);
  EXPECT_EQ(at_limit->expected().find("links in all cables"), std::string::npos) << at_limit->what();
}

}  // namespace
}  // namespace reeve::test
