#include "is_graphs/sim/movers_config.h"

#include <cmath>
#include <sstream>

namespace is_graphs {
namespace sim {
namespace {

std::string OutOf(const std::string& field, double value, double lo, double hi, const char* unit) {
  if (value >= lo && value <= hi) return "";
  std::ostringstream out;
  out << field << ": must be in [" << lo << ", " << hi << "] " << unit << ", got " << value;
  return out.str();
}

}  // namespace

std::string MoverConfig::Validate(const std::string& field) const {
  if (type != "person" && type != "cart")
    return field + ".type: must be person or cart, got '" + type + "'";
  if (rooms.empty() == waypoints.empty())
    return field + ": needs `rooms` (two or more) or `waypoints` (two or more), not both";
  if (!rooms.empty() && rooms.size() < 2) return field + ".rooms: needs two rooms or more";
  if (!waypoints.empty() && waypoints.size() < 2)
    return field + ".waypoints: needs two points or more";
  for (std::size_t i = 0; i < waypoints.size(); ++i)
    if (!waypoints[i].allFinite())
      return field + ".waypoints[" + std::to_string(i) + "]: must be finite";
  for (const std::string& e :
       {OutOf(field + ".speed", speed, 0.0, 3.0, "m/s (0: the kind's)"),
        OutOf(field + ".start", start, 0.0, 3600.0, "s"),
        OutOf(field + ".reflectivity", reflectivity, 0.0, 1.0, "(0: the kind's)")})
    if (!e.empty()) return e;
  return "";
}

std::string SwingingDoorConfig::Validate(const std::string& field) const {
  if (between.empty() == doorway.empty())
    return field + ": needs `between` (two room names) or `doorway` (a name or GlobalId)";
  if (!between.empty() && between.size() != 2)
    return field + ".between: must name two rooms, got " + std::to_string(between.size());
  if (!(period > 0.0 && period <= 3600.0))
    return field + ".period: must be > 0 and <= 3600 s, got " + std::to_string(period);
  for (const std::string& e : {OutOf(field + ".phase", phase, 0.0, 1.0, "(of a period)"),
                               OutOf(field + ".open_deg", open_deg, 1.0, 180.0, "deg"),
                               OutOf(field + ".hold_distance", hold_distance, 0.0, 50.0, "m")})
    if (!e.empty()) return e;
  return "";
}

}  // namespace sim
}  // namespace is_graphs
