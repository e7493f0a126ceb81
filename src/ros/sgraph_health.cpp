#include "sgraph_health.h"

#include <diagnostic_msgs/DiagnosticStatus.h>

#include <algorithm>
#include <cctype>
#include <sstream>

namespace is_graphs {
namespace ros_sgraph {

using diagnostic_msgs::DiagnosticStatus;

int SGraphHealth::OnCloud(const ros::Time& now, double stamp) {
  cloud_rate_.Tick();
  std::lock_guard<std::mutex> lock(mutex_);
  ++clouds_;
  last_cloud_ = now;
  return gaps_.Add(stamp);
}

void SGraphHealth::OnCloudSkipped(const std::string& reason) {
  // Counted by kind: the numbers in a reason (stamps, counts) are left out, so the map stays
  // as small as the kinds of reasons.
  std::string kind;
  for (char c : reason.substr(0, 60))
    if (!std::isdigit(static_cast<unsigned char>(c)) && c != '.') kind += c;
  std::lock_guard<std::mutex> lock(mutex_);
  ++clouds_skipped_;
  ++skip_reasons_[kind];
}

void SGraphHealth::OnOdometry(const ros::Time& now, bool skipped, bool bridged,
                              const std::string& why) {
  odometry_rate_.Tick();
  std::lock_guard<std::mutex> lock(mutex_);
  ++odometry_;
  last_odometry_ = now;
  if (skipped) ++odometry_skipped_, last_odometry_problem_ = why;
  if (bridged) ++bridged_;
}

void SGraphHealth::OnProcessed(double lag) {
  std::lock_guard<std::mutex> lock(mutex_);
  lag_ = lag;
  max_lag_ = std::max(max_lag_, lag);
}

void SGraphHealth::OnOptimized(int keyframes, unsigned revision, double ms) {
  std::lock_guard<std::mutex> lock(mutex_);
  keyframes_ = keyframes;
  revision_ = revision;
  optimize_ms_ = ms;
}

void SGraphHealth::OnRestart() {
  std::lock_guard<std::mutex> lock(mutex_);
  ++restarts_;
}

long SGraphHealth::clouds_missing() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return gaps_.missing();
}

std::string SGraphHealth::Stopped(const ros::Time& now, double timeout) const {
  std::lock_guard<std::mutex> lock(mutex_);
  if (last_cloud_.isZero() || last_odometry_.isZero()) return "";  // not started
  const double cloud_age = (now - last_cloud_).toSec();
  const double odometry_age = (now - last_odometry_).toSec();
  std::ostringstream s;
  s.precision(3);
  if (cloud_age > timeout && odometry_age <= timeout)
    s << "no clouds for " << cloud_age << " s while odometry comes: no keyframes";
  else if (odometry_age > timeout && cloud_age <= timeout)
    s << "no odometry for " << odometry_age << " s while clouds come: clouds skipped";
  return s.str();
}

void SGraphHealth::FillInputs(const ros::Time& now, double timeout,
                              diagnostic_updater::DiagnosticStatusWrapper& d) {
  const double cloud_rate = cloud_rate_.Rate(now), odometry_rate = odometry_rate_.Rate(now);
  const std::string stopped = Stopped(now, timeout);
  std::lock_guard<std::mutex> lock(mutex_);
  const long skipped = clouds_skipped_ - reported_skipped_;
  const long missing = gaps_.missing() - reported_missing_;
  const long odometry_skipped = odometry_skipped_ - reported_odometry_skipped_;
  reported_skipped_ = clouds_skipped_;
  reported_missing_ = gaps_.missing();
  reported_odometry_skipped_ = odometry_skipped_;
  if (!stopped.empty())
    d.summary(DiagnosticStatus::WARN, stopped);
  else if (skipped > 0 || missing > 0 || odometry_skipped > 0)
    d.summaryf(DiagnosticStatus::WARN,
               "this period: %ld clouds skipped, %ld missing (stamp gaps), %ld odometry skipped",
               skipped, missing, odometry_skipped);
  else
    d.summary(DiagnosticStatus::OK, "inputs fresh");
  d.addf("cloud rate [Hz]", "%.1f", cloud_rate);
  d.addf("odometry rate [Hz]", "%.1f", odometry_rate);
  d.add("clouds received", clouds_);
  d.add("clouds skipped", clouds_skipped_);
  for (const auto& [reason, count] : skip_reasons_) d.add("  skipped: " + reason, count);
  d.add("clouds missing (gaps in the stamps)", gaps_.missing());
  d.addf("cloud period [s]", "%.3f", gaps_.period());
  d.add("odometry received", odometry_);
  d.add("odometry skipped (NaN, glitch, out of order)", odometry_skipped_);
  d.add("odometry steps bridged", bridged_);
  d.add("last odometry problem", last_odometry_problem_);
  if (!last_cloud_.isZero()) d.addf("cloud age [s]", "%.2f", (now - last_cloud_).toSec());
  if (!last_odometry_.isZero()) d.addf("odometry age [s]", "%.2f", (now - last_odometry_).toSec());
}

void SGraphHealth::FillProcessing(double max_lag, diagnostic_updater::DiagnosticStatusWrapper& d) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (lag_ > max_lag)
    d.summaryf(DiagnosticStatus::WARN, "processing %.2f s behind the clouds (max_cloud_lag %.2f s)",
               lag_, max_lag);
  else
    d.summaryf(DiagnosticStatus::OK, "%d keyframes, revision %u", keyframes_, revision_);
  d.add("keyframes", keyframes_);
  d.add("revision", revision_);
  d.addf("last optimization [ms]", "%.1f", optimize_ms_);
  d.addf("cloud lag [s]", "%.3f", lag_);
  d.addf("largest cloud lag [s]", "%.3f", max_lag_);
  d.add("S-Graph restarts (track lost, time back, node restarted)", restarts_);
}

}  // namespace ros_sgraph
}  // namespace is_graphs
