// `reeve view`'s server (tools/src/view_server.h) over real HTTP: only the
// viewer's files are served, whatever the path's encoding; a stream
// starts with the scene, its status and a frame, and frames follow while
// it watches; at most kMaxStreams pages watch at once; commands are
// answered; stop() ends every stream and returns.
#include <atomic>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "view_server.h"
// After Eigen (through view_server.h): glibc's <resolv.h>, which httplib.h
// includes, defines _res, a name in Eigen's headers.
#include <httplib.h>

namespace reeve::test_view_server {
namespace {

using namespace std::chrono_literals;

ViewOptions atwood() {
  ViewOptions o;
  o.scene = std::filesystem::path(REEVE_SCENES_DIR) / "atwood.json";
  o.port = 0;
  return o;
}

// The messages' types (live_scene.h) in `bytes`, whole ones only.
std::vector<int> messageTypes(const std::string& bytes, std::vector<std::string>* payloads = nullptr) {
  std::vector<int> types;
  std::size_t at = 0;
  while (bytes.size() - at >= 4) {
    std::uint32_t n = 0;
    std::memcpy(&n, bytes.data() + at, 4);
    if (bytes.size() - at - 4 < n) break;
    types.push_back(static_cast<unsigned char>(bytes[at + 4]));
    if (payloads) payloads->push_back(bytes.substr(at + 5, n - 1));
    at += 4 + n;
  }
  return types;
}

TEST(ViewServer, ServesOnlyTheViewersOwnFilesHoweverThePathIsWritten) {
  ViewServer server(atwood());
  server.start();
  httplib::Client client("127.0.0.1", server.port());
  const auto page = client.Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_NE(page->body.find("/viewer/live.js"), std::string::npos);
  for (const char* file : {"/viewer/live.js", "/viewer/view3d.js", "/viewer/three.module.min.js", "/viewer/OrbitControls.js"}) {
    const auto r = client.Get(file);
    ASSERT_TRUE(r) << file;
    EXPECT_EQ(r->status, 200) << file;
    EXPECT_EQ(r->get_header_value("Content-Type"), "text/javascript") << file;
  }
  for (const char* path : {"/viewer/../../../../etc/passwd", "/viewer/..%2f..%2f..%2fetc%2fpasswd",
                           "/%2e%2e/%2e%2e/etc/passwd", "/viewer/%2E%2E/live.html", "/viewer/live.js/",
                           "/viewer/LIVE.JS", "/viewer/node_modules/three/package.json", "/etc/passwd", "/.",
                           "/viewer/live.js%00", "//etc/passwd"}) {
    const auto r = client.Get(path);
    ASSERT_TRUE(r) << path;
    EXPECT_EQ(r->status, 404) << path;
    EXPECT_EQ(r->body.find("root:"), std::string::npos) << path;
  }
  // A name other than the server's own (a site rebinding its name here),
  // one that only looks like a loopback address among them.
  for (const char* host : {"attacker.example", "127.0.0.1.attacker.example:8765", "localhost.attacker.example", ""}) {
    const auto foreign = client.Get("/", {{"Host", host}});
    ASSERT_TRUE(foreign) << host;
    EXPECT_EQ(foreign->status, 403) << host;
  }
  for (const char* host : {"localhost:8765", "127.0.0.1", "127.1.2.3:80", "[::1]:8765"}) {
    const auto own = client.Get("/", {{"Host", host}});
    ASSERT_TRUE(own) << host;
    EXPECT_EQ(own->status, 200) << host;
  }
  server.stop();
}

TEST(ViewServer, AnswersCommandsOnlyAsJsonAndWithTheirReason) {
  ViewServer server(atwood());
  server.start();
  httplib::Client client("127.0.0.1", server.port());
  const auto ok = client.Post("/control", R"({"cmd": "pause"})", "application/json");
  ASSERT_TRUE(ok);
  EXPECT_EQ(ok->status, 200);
  const auto bad = client.Post("/control", R"({"cmd": "set", "iterations": 0})", "application/json");
  ASSERT_TRUE(bad);
  EXPECT_EQ(bad->status, 400);
  EXPECT_NE(bad->body.find("/iterations"), std::string::npos) << bad->body;
  const auto form = client.Post("/control", R"({"cmd": "play"})", "text/plain");  // a cross-site form's
  ASSERT_TRUE(form);
  EXPECT_EQ(form->status, 415);
  const auto huge = client.Post("/control", std::string(kMaxCommandBytes + 1, ' '), "application/json");
  ASSERT_TRUE(huge);
  EXPECT_EQ(huge->status, 413);
  server.stop();
}

// A page's stream, read on a thread of its own until `stop` or `enough`
// messages. `bytes` and `status` once the thread is joined; messages()
// meanwhile.
struct Watcher {
  std::string bytes;
  int status = 0;
  std::atomic<bool> stop{false};
  std::mutex mutex;  // guards bytes while the thread runs
  std::thread thread;
  std::size_t messages() {
    std::lock_guard lock(mutex);
    return messageTypes(bytes).size();
  }
  Watcher(int port, std::size_t enough) {
    thread = std::thread([this, port, enough] {
      httplib::Client client("127.0.0.1", port);
      client.set_read_timeout(10, 0);
      const auto r = client.Get("/stream", [&](const char* data, std::size_t n) {
        std::lock_guard lock(mutex);
        bytes.append(data, n);
        return !stop && messageTypes(bytes).size() < enough;
      });
      // Cancelled: this side had read enough of a stream that was fine.
      status = r ? r->status : (r.error() == httplib::Error::Canceled ? 200 : -1);
    });
  }
  ~Watcher() {
    stop = true;
    if (thread.joinable()) thread.join();
  }
};

TEST(ViewServer, AStreamStartsWithTheSceneItsStatusAndAFrameAndFramesFollow) {
  ViewServer server(atwood());
  server.start();
  {
    Watcher page(server.port(), 8);
    page.thread.join();
    std::vector<std::string> payloads;
    const std::vector<int> types = messageTypes(page.bytes, &payloads);
    ASSERT_GE(types.size(), 8u);
    EXPECT_EQ(types[0], kJsonMessage);
    EXPECT_NE(payloads[0].find(R"("type":"scene")"), std::string::npos);
    EXPECT_NE(payloads[0].find(R"("name":"atwood")"), std::string::npos);
    EXPECT_EQ(types[1], kJsonMessage);
    EXPECT_NE(payloads[1].find(R"("type":"status")"), std::string::npos);
    for (std::size_t i = 2; i < types.size(); ++i) EXPECT_EQ(types[i], kFrameMessage) << i;
    // Frames numbered one after another: the page watching, time runs.
    std::uint32_t first = 0, last = 0;
    std::memcpy(&first, payloads[2].data() + 4, 4);
    std::memcpy(&last, payloads.back().data() + 4, 4);
    EXPECT_EQ(last - first, types.size() - 3);
  }
  server.stop();
}

TEST(ViewServer, ASceneSlowerThanRealTimeHoldsUpNeitherPagesNorCommands) {
  // hilbert3 at 100 substeps a frame: about 50 ms of physics for 17 ms of
  // time, stepped back to back (once, the stepper held the scene's lock
  // the whole time, and a page waited for its first message for ever).
  ViewOptions o;
  o.scene = std::filesystem::path(REEVE_SCENES_DIR) / "hilbert3.json";
  o.port = 0;
  o.overrides.substeps = 100;
  ViewServer server(o);
  server.start();
  {
    Watcher page(server.port(), 5);  // scene, status, a frame, and two more frames
    page.thread.join();
    EXPECT_EQ(page.status, 200);
    EXPECT_GE(messageTypes(page.bytes).size(), 5u);
  }
  {
    Watcher page(server.port(), 1u << 30);  // watching, so that time runs
    httplib::Client client("127.0.0.1", server.port());
    client.set_read_timeout(30, 0);
    const auto t0 = std::chrono::steady_clock::now();
    const auto paused = client.Post("/control", R"({"cmd": "pause"})", "application/json");
    ASSERT_TRUE(paused);
    EXPECT_EQ(paused->status, 200);
    EXPECT_LT(std::chrono::steady_clock::now() - t0, 20s);  // a frame or so, not for ever
  }
  server.stop();
}

TEST(ViewServer, AtMostFourPagesWatchAndStopEndsTheirStreams) {
  ViewServer server(atwood());
  server.start();
  std::vector<std::unique_ptr<Watcher>> pages;
  for (int i = 0; i < kMaxStreams; ++i) pages.push_back(std::make_unique<Watcher>(server.port(), 1u << 30));
  for (const auto& page : pages) {  // each has its scene message
    const auto until = std::chrono::steady_clock::now() + 10s;
    while (page->messages() < 3 && std::chrono::steady_clock::now() < until) std::this_thread::sleep_for(10ms);
  }
  httplib::Client client("127.0.0.1", server.port());
  const auto fifth = client.Get("/stream");
  ASSERT_TRUE(fifth);
  EXPECT_EQ(fifth->status, 503);
  EXPECT_NE(fifth->body.find("close one"), std::string::npos);
  const auto t0 = std::chrono::steady_clock::now();
  server.stop();  // ends the four streams: their threads return
  for (auto& page : pages) page->thread.join();
  EXPECT_LT(std::chrono::steady_clock::now() - t0, 5s);
  for (const auto& page : pages) EXPECT_EQ(page->status, 200);
}

}  // namespace
}  // namespace reeve::test_view_server
