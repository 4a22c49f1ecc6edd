#include "event_log.h"

#include <cerrno>
#include <cstring>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace reeve {

EventLog::EventLog(const std::filesystem::path& path) : out_(path) {
  if (!out_) throw std::runtime_error(path.string() + ": cannot write: " + std::strerror(errno));
}

void EventLog::drain(CableSystem& cables) {
  for (const CableEvent& e : cables.takeEvents()) {
    const nlohmann::json line = {{"time_s", e.time_s},
                                 {"cable", cables.cables()[e.cable].name},
                                 {"link", e.link},
                                 {"event", eventName(e.kind)},
                                 {"orientation", e.orientation > 0 ? "ccw" : "cw"}};
    out_ << line.dump() << '\n';
  }
  if (!out_) throw std::runtime_error("event log write failed (disk full?)");
}

}  // namespace reeve
