#include "view_server.h"

#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <deque>
#include <future>
#include <iostream>
#include <map>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include <httplib.h>
#include <arpa/inet.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <nlohmann/json.hpp>

#include "interrupt.h"
#include "viewer_files.h"

namespace reeve {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// Messages kept for streams that fall behind; one further back lost its
// frames (the page says so by the frame numbers), not the connection.
constexpr std::size_t kKeptMessages = 1024;
// How often the scene file is looked at for changes.
constexpr auto kWatchEvery = std::chrono::milliseconds(250);
// A page more bytes behind than this (20 frames of hilbert3, thousands of
// a small machine's) is sent the other messages it missed but only the
// latest frame: a live view keeps its latency, not every frame (the frame
// numbers show the gap).
constexpr std::size_t kMaxBacklogBytes = 4u << 20;
// How long a stream waits for a message before it looks whether its page
// is still there and the server still running.
constexpr auto kStreamPoll = std::chrono::milliseconds(200);
// How long stop() waits for the streams to write their ends.
constexpr auto kStopWait = std::chrono::seconds(2);

// "localhost", or an address literal of this machine (127.0.0.0/8, ::1);
// not a name that only starts so ("127.0.0.1.example.com" is anyone's).
bool isLoopback(const std::string& host) {
  in_addr v4{};
  in6_addr v6{};
  if (host == "localhost") return true;
  if (inet_pton(AF_INET, host.c_str(), &v4) == 1) return (ntohl(v4.s_addr) >> 24) == 127;
  return inet_pton(AF_INET6, host.c_str(), &v6) == 1 && IN6_IS_ADDR_LOOPBACK(&v6);
}

// The host part of a Host header ("localhost:8765", "[::1]:8765").
std::string hostName(const std::string& header) {
  if (!header.empty() && header.front() == '[') return header.substr(1, header.find(']') - 1);
  return header.substr(0, header.find(':'));
}

std::string errorJson(const std::string& text) { return nlohmann::json{{"error", text}}.dump(); }

}  // namespace

// Threads. The stepping thread alone touches the scene (LiveScene): it
// steps, watches the file and runs the commands, which the HTTP threads
// queue for it and wait for. The log of messages has a mutex of its own,
// held only to add or copy pointers, so a scene slower than real time
// (stepped back to back) holds up neither the pages nor the commands.
struct ViewServer::Impl {
  ViewOptions options;
  httplib::Server http;
  int port = 0;
  struct File {
    std::string bytes;
    const char* type;
  };
  std::map<std::string, File> files;  // by URL path: all that is served

  // The stepping thread's own.
  LiveScene live;
  Clock::time_point next_frame;
  // The scene file's write time and size, as loaded and as last seen.
  struct FileStamp {
    fs::file_time_type time;
    std::uintmax_t size = 0;
    bool operator==(const FileStamp&) const = default;
  };
  FileStamp loaded, seen;
  static std::optional<FileStamp> stampOf(const fs::path& file) {
    std::error_code time_error, size_error;
    FileStamp stamp{fs::last_write_time(file, time_error), fs::file_size(file, size_error)};
    if (time_error || size_error) return std::nullopt;
    return stamp;
  }

  // Commands for the stepping thread, and their answers.
  struct Command {
    std::string text;
    std::promise<std::optional<std::string>> answer;  // nullopt: done; else why not
  };
  std::mutex queue_mutex;        // guards `queue` and `stopping`
  std::condition_variable wake;  // the stepping thread: a command, a page, a stop
  std::deque<std::shared_ptr<Command>> queue;
  bool stopping = false;

  // The messages, for the pages' streams.
  std::mutex log_mutex;              // guards everything below
  std::condition_variable messages;  // the streams: a message, a stop
  std::deque<std::shared_ptr<const std::string>> log;
  std::uint64_t first_seq = 0, next_seq = 0;  // of log.front(), and of the next message
  std::shared_ptr<const std::string> scene_message, status_message, frame_message;  // what a new page starts from
  int streams = 0;
  bool closing = false;  // the streams end

  std::thread stepper, server;

  explicit Impl(const ViewOptions& o)
      : options(o),
        live(o.scene_text ? LiveScene(*o.scene_text, o.scene.string(), o.overrides) : LiveScene(o.scene, o.overrides)) {}

  void publish(std::string message, std::shared_ptr<const std::string>* latest = nullptr) {
    auto shared = std::make_shared<const std::string>(std::move(message));
    std::lock_guard lock(log_mutex);
    if (latest) *latest = shared;
    log.push_back(std::move(shared));
    ++next_seq;
    if (log.size() > kKeptMessages) {
      log.pop_front();
      ++first_seq;
    }
    messages.notify_all();
  }
  void publishScene() {
    publish(live.sceneMessage(), &scene_message);
    publish(live.statusMessage(), &status_message);
    publish(live.frameMessage(), &frame_message);
  }
  void publishError(const std::string& text, const std::string& file = "", const std::string& json_path = "") {
    publish(jsonMessage(nlohmann::json{{"type", "error"}, {"message", text}, {"file", file}, {"json_path", json_path}}.dump()));
  }
  bool watched() {
    std::lock_guard lock(log_mutex);
    return streams > 0;
  }

  // The scene file changed on disk: the new one from t = 0, or its error
  // in the page and the old one on. Read once it has stayed as it is for a
  // watch interval: a file still being written (hilbert3.json, 100 kB,
  // written by a script) was read half-written, and its error shown.
  void watch() {
    if (options.scene.empty() || options.scene_text) return;
    const std::optional<FileStamp> now = stampOf(options.scene);
    if (!now || *now == loaded) return;
    if (*now != seen) {
      seen = *now;
      return;
    }
    loaded = *now;
    try {
      live.reloadFile(options.scene);
      publishScene();
    } catch (const SceneError& e) {
      // Saved again while it was read (a save in place, caught between
      // its truncation and its bytes): no error, the next watches read it
      // whole once it stays.
      if (stampOf(options.scene) != loaded) {
        loaded = seen = FileStamp{};
        return;
      }
      publishError(e.what(), e.file(), e.jsonPath());
    }
  }

  // The commands queued, each answered.
  void runCommands(std::deque<std::shared_ptr<Command>>& commands) {
    for (const std::shared_ptr<Command>& command : commands) {
      const std::uint32_t before = live.sceneGeneration();
      const std::optional<std::string> error = live.command(command->text);
      if (!error && live.sceneGeneration() != before) publishScene();  // reset
      else if (!error) publish(live.statusMessage(), &status_message);
      if (!error) next_frame = Clock::now();
      command->answer.set_value(error);
    }
    commands.clear();
  }

  void stepLoop() {
    auto next_watch = Clock::now() + kWatchEvery;
    next_frame = Clock::now();
    std::deque<std::shared_ptr<Command>> commands;
    for (;;) {
      {
        std::lock_guard lock(queue_mutex);
        if (stopping) break;
        commands.swap(queue);
      }
      runCommands(commands);
      const auto now = Clock::now();
      if (now >= next_watch) {
        watch();
        next_watch = now + kWatchEvery;
      }
      // Time runs while a page watches: not before the first opens, nor
      // while none is open.
      const bool playing = live.playing() && watched();
      const bool due = playing ? now >= next_frame : live.stepsWanted() > 0;
      if (!due) {
        if (!playing) next_frame = now;
        std::unique_lock lock(queue_mutex);
        wake.wait_until(lock, playing ? std::min(next_frame, next_watch) : next_watch,
                        [&] { return stopping || !queue.empty(); });
        continue;
      }
      const bool failed = live.failure().has_value();
      live.stepFrame();
      publish(live.frameMessage(), &frame_message);
      for (std::string& event : live.takeEventMessages()) publish(std::move(event));
      if (!failed && live.failure()) publishError("paused: " + *live.failure());
      if (!live.playing() && live.stepsWanted() == 0) publish(live.statusMessage(), &status_message);
      // Real time at the page's factor; a frame that took longer than its
      // share is not caught up on (the machine runs as fast as it can).
      next_frame = std::max(next_frame + std::chrono::duration_cast<Clock::duration>(
                                             std::chrono::duration<double>(live.frameSeconds() / live.realTimeFactor())),
                            now - std::chrono::milliseconds(100));
    }
    // Commands that came too late are told so, not left waiting.
    std::lock_guard lock(queue_mutex);
    for (const std::shared_ptr<Command>& command : queue) command->answer.set_value("the server is stopping");
    queue.clear();
  }

  void control(const httplib::Request& req, httplib::Response& res) {
    if (req.get_header_value("Content-Type").rfind("application/json", 0) != 0) {
      // Only a page of this server sends it so: a cross-site form or
      // fetch would need a preflight the server never answers.
      res.status = 415;
      res.set_content(errorJson("a command is sent as application/json"), "application/json");
      return;
    }
    auto command = std::make_shared<Command>();
    command->text = req.body;
    std::future<std::optional<std::string>> answer = command->answer.get_future();
    {
      std::lock_guard lock(queue_mutex);
      if (stopping) {
        res.status = 503;
        res.set_content(errorJson("the server is stopping"), "application/json");
        return;
      }
      queue.push_back(command);
    }
    wake.notify_all();
    // Answered between two frames of the scene, however long one takes.
    const std::optional<std::string> error = answer.get();
    if (error) {
      res.status = 400;
      res.set_content(errorJson(*error), "application/json");
      return;
    }
    res.set_content(R"({"ok":true})", "application/json");
  }

  void stream(const httplib::Request&, httplib::Response& res) {
    std::unique_lock lock(log_mutex);
    if (streams >= kMaxStreams) {
      res.status = 503;
      res.set_content(errorJson("at most " + std::to_string(kMaxStreams) + " pages watch at once; close one"),
                      "application/json");
      return;
    }
    ++streams;
    lock.unlock();
    wake.notify_all();
    lock.lock();
    // A new page starts from the scene, its status and its latest frame.
    auto start = std::make_shared<std::vector<std::shared_ptr<const std::string>>>(
        std::vector{scene_message, status_message, frame_message});
    auto next = std::make_shared<std::uint64_t>(next_seq);
    res.set_header("Cache-Control", "no-store");
    res.set_chunked_content_provider(
        "application/octet-stream",
        [this, start, next](std::size_t, httplib::DataSink& sink) {
          std::vector<std::shared_ptr<const std::string>> batch;
          {
            std::unique_lock lock(log_mutex);
            if (start->empty())
              messages.wait_for(lock, kStreamPoll, [&] { return closing || *next < next_seq; });
            if (closing) {
              sink.done();
              return true;
            }
            batch.swap(*start);
            *next = std::max(*next, first_seq);  // fell behind: what is kept
            const auto frame = [&](std::uint64_t seq) { return static_cast<unsigned char>((*log[seq - first_seq])[4]) == kFrameMessage; };
            std::size_t behind = 0;
            for (std::uint64_t seq = *next; seq < next_seq; ++seq) behind += log[seq - first_seq]->size();
            std::uint64_t latest_frame = next_seq;  // none
            if (behind > kMaxBacklogBytes)
              for (std::uint64_t seq = next_seq; seq-- > *next;)
                if (frame(seq)) {
                  latest_frame = seq;
                  break;
                }
            for (; *next < next_seq; ++*next)
              if (latest_frame == next_seq || *next == latest_frame || !frame(*next)) batch.push_back(log[*next - first_seq]);
          }
          if (batch.empty()) return sink.is_writable();
          // One chunk for what came since the last: fewer writes for a page
          // that fell behind.
          std::string chunk;
          for (const auto& m : batch) chunk += *m;
          return sink.write(chunk.data(), chunk.size());  // false: the page went; this stream ends, only it
        },
        [this](bool) {
          std::lock_guard lock(log_mutex);
          --streams;
          messages.notify_all();  // stop() waits for the last
        });
  }

  // Only the page's own host names, against a site rebinding its name to
  // this address (loopback only; a public --host was warned about).
  bool hostAllowed(const httplib::Request& req) const {
    if (!isLoopback(options.host)) return true;
    const std::string host = hostName(req.get_header_value("Host"));
    return isLoopback(host) || host == options.host;
  }
};

ViewServer::ViewServer(const ViewOptions& options) : impl_(std::make_unique<Impl>(options)) {
  Impl& m = *impl_;
  if (!options.scene.empty() && !options.scene_text)
    if (const auto stamp = Impl::stampOf(options.scene)) m.loaded = m.seen = *stamp;
  m.files["/"] = {readViewerFile("live.html", "reeve view"), "text/html; charset=utf-8"};
  m.files["/viewer/live.js"] = {readViewerFile("live.js", "reeve view"), "text/javascript"};
  m.files["/viewer/view3d.js"] = {readViewerFile("view3d.js", "reeve view"), "text/javascript"};
  m.files["/viewer/three.module.min.js"] = {readViewerFile(kThreeModule, "reeve view"), "text/javascript"};
  m.files["/viewer/OrbitControls.js"] = {readViewerFile(kOrbitControls, "reeve view"), "text/javascript"};
  m.publishScene();

  httplib::Server& http = m.http;
  // Frames go out as they come, each a small write: without TCP_NODELAY
  // Nagle's algorithm holds one back until the page acknowledges the last,
  // which a page delays (accepted sockets inherit it from the listener).
  http.set_socket_options([](socket_t socket) {
    httplib::default_socket_options(socket);
    const int yes = 1;
    setsockopt(socket, IPPROTO_TCP, TCP_NODELAY, &yes, sizeof yes);
  });
  http.set_payload_max_length(kMaxCommandBytes);
  http.set_keep_alive_timeout(1);
  http.set_default_headers({{"X-Content-Type-Options", "nosniff"}});
  http.set_pre_routing_handler([&m](const httplib::Request& req, httplib::Response& res) {
    if (m.hostAllowed(req)) return httplib::Server::HandlerResponse::Unhandled;
    res.status = 403;
    res.set_content(errorJson("this server answers only to its own address"), "application/json");
    return httplib::Server::HandlerResponse::Handled;
  });
  // Every file by its exact path: nothing outside them, however encoded.
  http.Get(R"(/.*)", [&m](const httplib::Request& req, httplib::Response& res) {
    if (req.path == "/stream") return m.stream(req, res);
    const auto found = m.files.find(req.path);
    if (found == m.files.end()) {
      res.status = 404;
      res.set_content("not found\n", "text/plain");
      return;
    }
    res.set_header("Cache-Control", "no-store");
    res.set_content(found->second.bytes, found->second.type);
  });
  http.Post("/control", [&m](const httplib::Request& req, httplib::Response& res) { m.control(req, res); });
  m.port = options.port == 0 ? http.bind_to_any_port(options.host) : (http.bind_to_port(options.host, options.port) ? options.port : -1);
  if (m.port < 0)
    throw std::runtime_error("cannot listen on " + options.host + ":" + std::to_string(options.port) +
                             " (in use, or not this machine's address); pass another --port, or --port 0 for any free one");
}

ViewServer::~ViewServer() { stop(); }

int ViewServer::port() const { return impl_->port; }

std::string ViewServer::url() const {
  const std::string& host = impl_->options.host;
  return "http://" + (host.find(':') != std::string::npos ? "[" + host + "]" : host) + ":" + std::to_string(port()) + "/";
}

void ViewServer::start() {
  Impl& m = *impl_;
  m.server = std::thread([&m] { m.http.listen_after_bind(); });
  m.stepper = std::thread([&m] { m.stepLoop(); });
}

void ViewServer::stop() {
  Impl& m = *impl_;
  {
    std::lock_guard lock(m.queue_mutex);
    m.stopping = true;
  }
  m.wake.notify_all();
  if (m.stepper.joinable()) m.stepper.join();
  else {  // never started: no one answers the queue
    std::lock_guard lock(m.queue_mutex);
    for (const auto& command : m.queue) command->answer.set_value("the server is stopping");
    m.queue.clear();
  }
  {
    std::unique_lock lock(m.log_mutex);
    m.closing = true;
    m.messages.notify_all();
    // Each stream ends with its last chunk written: the server's stop
    // stops writing, and a page cut off mid-stream reads an error, not an
    // end (the four-page test, once in three runs here). A page that reads
    // nothing is cut off after kStopWait.
    m.messages.wait_for(lock, kStopWait, [&] { return m.streams == 0; });
  }
  m.http.stop();
  if (m.server.joinable()) m.server.join();
}

int viewCommand(const ViewOptions& options) {
  try {
    const InterruptGuard interrupt;
    ViewServer server(options);
    if (!isLoopback(options.host))
      std::fprintf(stderr,
                   "reeve view: warning: listening on %s, not only this machine: anyone who reaches it can watch and "
                   "control the scene (for a remote machine, forward a port over SSH instead: README)\n",
                   options.host.c_str());
    server.start();
    std::printf("reeve view: '%s' at %s (Ctrl-C stops)\n", options.scene.empty() ? "simple" : options.scene.c_str(),
                server.url().c_str());
    std::fflush(stdout);
    while (!interrupt.received()) std::this_thread::sleep_for(std::chrono::milliseconds(100));
    server.stop();
    std::printf("reeve view: stopped\n");
    return 0;
  } catch (const SceneError& e) {
    std::cerr << "reeve: " << e.what() << '\n';
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "reeve: " << e.what() << '\n';
    return 1;
  }
}

}  // namespace reeve
