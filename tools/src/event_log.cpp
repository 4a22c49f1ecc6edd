#include "event_log.h"

#include <nlohmann/json.hpp>

namespace reeve {

EventLog::EventLog(const std::filesystem::path& path, bool replace) : out_(path, replace) {}

void EventLog::drain(CableSystem& cables) {
  for (const CableEvent& e : cables.takeEvents()) {
    const nlohmann::json line = {{"time_s", e.time_s},
                                 {"cable", cables.cables()[e.cable].name},
                                 {"link", e.link},
                                 {"event", eventName(e.kind)},
                                 {"orientation", e.orientation > 0 ? "ccw" : "cw"}};
    out_.write(line.dump() + "\n");
  }
}

}  // namespace reeve
