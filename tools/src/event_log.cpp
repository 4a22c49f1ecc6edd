#include "event_log.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "csv_writer.h"

namespace reeve {

EventLog::EventLog(const std::filesystem::path& path, bool replace) : out_(path, replace) {}

void EventLog::write(const CableSystem& cables, const std::vector<CableEvent>& events) {
  for (const CableEvent& e : events) {
    // Finite by the scene limits (a sum of finite frame times); checked
    // all the same, as every number Reeve writes is.
    if (!std::isfinite(e.time_s))
      throw std::runtime_error(nonFiniteMessage(e.time_s, "an event's time is " + std::to_string(e.time_s)));
    nlohmann::json line = {{"time_s", e.time_s},
                           {"cable", cables.cables()[e.cable].name},
                           {"link", e.link},
                           {"event", eventName(e.kind)},
                           {"orientation", e.orientation > 0 ? "ccw" : "cw"}};
    if (e.kind == CableEvent::Kind::Break) line["tension_N"] = e.tension;
    out_.write(line.dump() + "\n");
  }
}

}  // namespace reeve
