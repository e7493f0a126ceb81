#include "is_graphs/merging/input_watchdog.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

namespace is_graphs {
namespace merging {

std::string WatchdogConfig::Validate() const {
  for (const auto& [name, value] :
       {std::pair<const char*, double>{"degraded_after", degraded_after},
        {"lost_after", lost_after},
        {"max_distance_without_sgraph", max_distance_without_sgraph},
        {"lost_distance_without_sgraph", lost_distance_without_sgraph}})
    if (!(value > 0.0) || !std::isfinite(value)) return std::string(name) + " must be > 0";
  if (!(lost_after > degraded_after)) return "lost_after must be > degraded_after";
  if (!(lost_distance_without_sgraph > max_distance_without_sgraph))
    return "lost_distance_without_sgraph must be > max_distance_without_sgraph";
  for (const auto& [name, value] :
       {std::pair<const char*, double>{"degraded_sigma_per_m", degraded_sigma_per_m},
        {"degraded_yaw_sigma_deg_per_m", degraded_yaw_sigma_deg_per_m}})
    if (!(value >= 0.0) || !std::isfinite(value)) return std::string(name) + " must be >= 0";
  return "";
}

const char* ToString(InputWatchdog::Health health) {
  switch (health) {
    case InputWatchdog::Health::kFresh:
      return "fresh";
    case InputWatchdog::Health::kLate:
      return "late";
    case InputWatchdog::Health::kStopped:
      return "stopped";
  }
  return "?";
}

void InputWatchdog::Arm(double now, double distance_walked) {
  odometry_stamp_ = map_to_odom_stamp_ = now;
  distance_ = distance_at_sgraph_ = distance_walked;
}

void InputWatchdog::OnOdometry(double stamp, double distance_walked) {
  odometry_stamp_ = std::max(odometry_stamp_, stamp);
  distance_ = distance_walked;
}

void InputWatchdog::OnMapToOdom(double stamp) {
  map_to_odom_stamp_ = std::max(map_to_odom_stamp_, stamp);
}

void InputWatchdog::OnSGraph(double distance_walked) { distance_at_sgraph_ = distance_walked; }

InputWatchdog::Report InputWatchdog::Check(double now) const {
  Report r;
  r.odometry_age = std::max(0.0, now - odometry_stamp_);
  r.map_to_odom_age = std::max(0.0, now - map_to_odom_stamp_);
  r.distance_since_sgraph = std::max(0.0, distance_ - distance_at_sgraph_);
  std::ostringstream s;
  s.precision(3);
  // Every late input is named, the worst decides.
  const auto late = [&](double value, double degraded, double lost, const char* what,
                        const char* unit) {
    if (!(value > degraded)) return;
    const bool stopped = value > lost;
    if (s.tellp() > 0) s << "; ";
    s << what << " " << value << " " << unit << " (" << (stopped ? "LOST" : "DEGRADED") << " past "
      << (stopped ? lost : degraded) << " " << unit << ")";
    r.health = std::max(r.health, stopped ? Health::kStopped : Health::kLate);
  };
  late(r.odometry_age, config_.degraded_after, config_.lost_after, "no odometry for", "s");
  late(r.map_to_odom_age, config_.degraded_after, config_.lost_after,
       "no tf map -> odom (the S-Graph) for", "s");
  late(r.distance_since_sgraph, config_.max_distance_without_sgraph,
       config_.lost_distance_without_sgraph, "no S-Graph revision over", "m walked");
  r.message = s.str();
  return r;
}

}  // namespace merging
}  // namespace is_graphs
