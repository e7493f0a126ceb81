#include "merger_diagnostics.h"

#include <diagnostic_msgs/DiagnosticStatus.h>

namespace is_graphs {
namespace ros_merger {

using diagnostic_msgs::DiagnosticStatus;

void FillLocalization(const MergerHealthSnapshot& s,
                      diagnostic_updater::DiagnosticStatusWrapper& d) {
  using merging::LocalizationState;
  const char* state = merging::ToString(s.state);
  switch (s.state) {
    case LocalizationState::kLocalized:
      d.summary(DiagnosticStatus::OK, state);
      break;
    case LocalizationState::kNotLocalized:
    case LocalizationState::kDegraded:
      d.summaryf(DiagnosticStatus::WARN, "%s: %s", state, s.message.c_str());
      break;
    case LocalizationState::kLost:
      d.summaryf(DiagnosticStatus::ERROR, "%s: %s", state, s.message.c_str());
      break;
  }
  d.add("state", state);
  d.add("message", s.message);
  d.add("poses published", s.poses);
  d.add("non-finite poses withheld", s.nonfinite_poses);
  d.add("graph matches received", s.matches);
  d.addf("last merge [ms]", "%.1f", s.last_merge_ms);
  d.addf("slowest merge [ms]", "%.1f", s.max_merge_ms);
}

void FillInputs(const MergerHealthSnapshot& s, long skipped_in_period,
                diagnostic_updater::DiagnosticStatusWrapper& d) {
  using Health = merging::InputWatchdog::Health;
  if (s.armed && s.watchdog.health == Health::kStopped)
    d.summaryf(DiagnosticStatus::ERROR, "input stopped: %s", s.watchdog.message.c_str());
  else if (s.armed && s.watchdog.health == Health::kLate)
    d.summaryf(DiagnosticStatus::WARN, "input late: %s", s.watchdog.message.c_str());
  else if (skipped_in_period > 0)
    d.summaryf(DiagnosticStatus::WARN, "%ld odometry messages skipped: %s", skipped_in_period,
               s.last_odometry_problem.c_str());
  else
    d.summary(DiagnosticStatus::OK, "inputs fresh");
  d.addf("odometry rate [Hz]", "%.1f", s.odometry_rate);
  d.add("odometry received", s.odometry_received);
  d.add("odometry skipped (NaN, glitch, out of order)", s.odometry_skipped);
  d.add("odometry steps bridged", s.odometry_bridged);
  d.add("last odometry problem", s.last_odometry_problem);
  d.add("S-Graph revisions", s.sgraph_revisions);
  d.add("S-Graph revisions rejected (non-finite)", s.sgraph_rejected);
  if (s.armed) {
    d.addf("odometry age [s]", "%.2f", s.watchdog.odometry_age);
    d.addf("tf map -> odom age [s]", "%.2f", s.watchdog.map_to_odom_age);
    d.addf("walked since the newest S-Graph revision [m]", "%.2f",
           s.watchdog.distance_since_sgraph);
  }
}

}  // namespace ros_merger
}  // namespace is_graphs
