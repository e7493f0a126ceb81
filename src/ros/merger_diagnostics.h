#pragma once
// merger_node's /diagnostics: what the node's state and input counters say, as statuses.
#include <diagnostic_updater/DiagnosticStatusWrapper.h>

#include <string>

#include "is_graphs/merging/input_watchdog.h"
#include "is_graphs/merging/merge_state.h"

namespace is_graphs {
namespace ros_merger {

/// A copy of the node's state, taken under its lock for one /diagnostics message.
struct MergerHealthSnapshot {
  merging::LocalizationState state{merging::LocalizationState::kNotLocalized};
  std::string message;
  bool armed{false};  // the watchdog runs (a pose is published)
  merging::InputWatchdog::Report watchdog;
  double odometry_rate{0.0};  // Hz over the diagnostic period
  long odometry_received{0}, odometry_skipped{0}, odometry_bridged{0};
  std::string last_odometry_problem;
  long sgraph_revisions{0}, sgraph_rejected{0}, matches{0}, poses{0}, nonfinite_poses{0};
  double last_merge_ms{0.0}, max_merge_ms{0.0};
};

/// "localization": OK when LOCALIZED, WARN when NOT_LOCALIZED or DEGRADED, ERROR when LOST.
void FillLocalization(const MergerHealthSnapshot& s,
                      diagnostic_updater::DiagnosticStatusWrapper& d);
/// "inputs": the ages the watchdog sees and the input counters; WARN when odometry was skipped
/// in this period or an input is late, ERROR when one stopped.
void FillInputs(const MergerHealthSnapshot& s, long skipped_in_period,
                diagnostic_updater::DiagnosticStatusWrapper& d);

}  // namespace ros_merger
}  // namespace is_graphs
