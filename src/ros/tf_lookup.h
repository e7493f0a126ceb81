#pragma once

#include <ros/time.h>
#include <tf2_ros/buffer.h>

#include <Eigen/Geometry>
#include <map>
#include <mutex>
#include <string>

#include "is_graphs/common/result.h"

namespace is_graphs {
namespace ros_tf {

/// The one place where the nodes look up tf: tf2::TransformException never escapes, a failed
/// lookup is an error naming the frames and tf's reason, and so is a non-finite transform.
class TfLookup {
 public:
  explicit TfLookup(const tf2_ros::Buffer& buffer) : buffer_(buffer) {}

  /// target <- source at `time` (ros::Time(0): the latest), waiting up to `timeout`.
  Result<Eigen::Isometry3d> Lookup(const std::string& target, const std::string& source,
                                   const ros::Time& time,
                                   const ros::Duration& timeout = ros::Duration(0.0)) const;

  /// The stamp of the newest target <- source tf holds (a heartbeat: how old that link is).
  Result<ros::Time> LatestStamp(const std::string& target, const std::string& source) const;

  /// As Lookup at the latest time, cached after the first success: for static transforms
  /// (base_link <- sensor mounts).
  Result<Eigen::Isometry3d> LookupStatic(const std::string& target, const std::string& source,
                                         const ros::Duration& timeout = ros::Duration(0.0));

 private:
  const tf2_ros::Buffer& buffer_;
  std::mutex mutex_;
  std::map<std::pair<std::string, std::string>, Eigen::Isometry3d> static_cache_;
};

}  // namespace ros_tf
}  // namespace is_graphs
