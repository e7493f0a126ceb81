// Shared by the offline tools that replay a scenario bag through the core without ROS
// transport (bench_sgraph, replay_pipeline): the topics, the sensor mount, the LiDAR layout
// option, percentiles, peak memory.
#pragma once

#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <tf2_eigen/tf2_eigen.h>
#include <tf2_msgs/TFMessage.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "../lidar_conversions.h"

namespace is_graphs {
namespace bag_replay {

/// The topics a scenario bag carries (the cloud under each simulated driver's topic), with and
/// without the leading slash.
inline std::vector<std::string> SensorTopics() {
  std::vector<std::string> topics;
  for (const char* t :
       {"velodyne_points", "ouster/points", "hesai/pandar", "odom", "ground_truth/pose"})
    topics.insert(topics.end(), {t, std::string("/") + t});
  return topics;
}

/// The bag's tf_static tree: base_link <- any frame by chaining the static transforms.
class StaticFrames {
 public:
  explicit StaticFrames(const rosbag::Bag& bag) {
    for (const auto& m :
         rosbag::View(bag, rosbag::TopicQuery(std::vector<std::string>{"tf_static", "/tf_static"})))
      if (auto tf = m.instantiate<tf2_msgs::TFMessage>())
        for (const auto& t : tf->transforms)
          parent_[t.child_frame_id] = {t.header.frame_id, tf2::transformToEigen(t)};
  }
  /// base <- frame (identity where the chain stops short of `base`).
  Eigen::Isometry3d BaseT(const std::string& frame, const std::string& base = "base_link") const {
    Eigen::Isometry3d base_T_frame = Eigen::Isometry3d::Identity();
    std::string f = frame;
    for (size_t hops = 0; f != base && hops < parent_.size(); ++hops) {
      const auto it = parent_.find(f);
      if (it == parent_.end()) break;
      base_T_frame = it->second.second * base_T_frame;
      f = it->second.first;
    }
    return base_T_frame;
  }

 private:
  std::map<std::string, std::pair<std::string, Eigen::Isometry3d>> parent_;
};

/// --cloud-layout NAME into `config`; false for an unknown name.
inline bool ParseCloudLayout(const std::string& name, ros_conversions::LidarCloudConfig* config) {
  const auto kind = ros_conversions::ParseCloudLayoutKind(name);
  if (kind) config->layout = *kind;
  return kind.has_value();
}

/// One cloud as the core's scan; the layout and each problem printed once to stderr, as the
/// node logs them.
inline Result<sgraph::Scan> ReadCloud(ros_conversions::LidarCloudReader& reader,
                                      const sensor_msgs::PointCloud2& msg, const char* tool) {
  std::string info;
  std::vector<std::string> warnings;
  auto scan = reader.Read(msg, &info, &warnings);
  if (!info.empty()) std::fprintf(stderr, "%s: cloud %s\n", tool, info.c_str());
  for (const std::string& w : warnings) std::fprintf(stderr, "%s: warning: %s\n", tool, w.c_str());
  return scan;
}

/// The q-quantile (0..1) by the nearest rank; 0 for no values.
inline double Percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(q * (v.size() - 1) + 0.5))];
}

/// This process's peak resident set size [KiB] (VmHWM), -1 when unknown.
inline long PeakRssKb() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::stol(line.substr(6));
  return -1;
}

}  // namespace bag_replay
}  // namespace is_graphs
