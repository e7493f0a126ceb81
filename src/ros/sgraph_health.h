#pragma once
// sgraph_node's bookkeeping of its inputs and work, for warnings and /diagnostics: clouds and
// odometry received, skipped (why) and missing (gaps in the cloud stamps), their rates and ages,
// how far processing lags behind, keyframes and optimization time. Thread-safe.
#include <diagnostic_updater/DiagnosticStatusWrapper.h>
#include <ros/time.h>

#include <map>
#include <mutex>
#include <string>

#include "is_graphs/sgraph/cloud_gaps.h"
#include "rate_meter.h"

namespace is_graphs {
namespace ros_sgraph {

class SGraphHealth {
 public:
  /// A cloud arrived at `now` with this stamp: returns the clouds missing before it.
  int OnCloud(const ros::Time& now, double stamp);
  void OnCloudSkipped(const std::string& reason);
  /// Odometry arrived; `skipped`: the guard or the builder did not use it (`why`).
  void OnOdometry(const ros::Time& now, bool skipped, bool bridged, const std::string& why);
  /// A cloud was processed `lag` s after its stamp (the clock's now minus the stamp).
  void OnProcessed(double lag);
  void OnOptimized(int keyframes, unsigned revision, double ms);
  void OnRestart();

  /// Which input stopped (none for `timeout` s of the clock while the other comes), or "".
  std::string Stopped(const ros::Time& now, double timeout) const;
  long clouds_missing() const;

  /// "inputs": rates, counts, ages; WARN on skipped or missing clouds or skipped odometry in
  /// the period, or an input stopped. "processing": keyframes, lag, optimization.
  void FillInputs(const ros::Time& now, double timeout,
                  diagnostic_updater::DiagnosticStatusWrapper& d);
  void FillProcessing(double max_lag, diagnostic_updater::DiagnosticStatusWrapper& d);

 private:
  mutable std::mutex mutex_;
  ros_diagnostics::RateMeter cloud_rate_, odometry_rate_;
  sgraph::CloudGapCounter gaps_;
  ros::Time last_cloud_, last_odometry_;  // receipt, the node's clock
  long clouds_{0}, clouds_skipped_{0}, odometry_{0}, odometry_skipped_{0}, bridged_{0};
  std::map<std::string, long> skip_reasons_;
  std::string last_odometry_problem_;
  long reported_skipped_{0}, reported_missing_{0}, reported_odometry_skipped_{0};
  double lag_{0.0}, max_lag_{0.0};
  int keyframes_{0};
  unsigned revision_{0};
  double optimize_ms_{0.0};
  long restarts_{0};
};

}  // namespace ros_sgraph
}  // namespace is_graphs
