// Shared by the offline tools that replay a scenario bag through the core without ROS
// transport (bench_sgraph, replay_pipeline): the sensor mount, percentiles, peak memory.
#pragma once

#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <tf2_eigen/tf2_eigen.h>
#include <tf2_msgs/TFMessage.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <fstream>
#include <string>
#include <vector>

namespace is_graphs {
namespace bag_replay {

/// The topics a scenario bag carries, with and without the leading slash.
inline std::vector<std::string> SensorTopics() {
  return {"velodyne_points",  "odom",  "ground_truth/pose",
          "/velodyne_points", "/odom", "/ground_truth/pose"};
}

/// base_link <- velodyne from the bag's tf_static (identity when absent).
inline Eigen::Isometry3d BaseTSensor(const rosbag::Bag& bag,
                                     const std::string& sensor = "velodyne") {
  Eigen::Isometry3d base_T_sensor = Eigen::Isometry3d::Identity();
  for (const auto& m :
       rosbag::View(bag, rosbag::TopicQuery(std::vector<std::string>{"tf_static", "/tf_static"})))
    if (auto tf = m.instantiate<tf2_msgs::TFMessage>())
      for (const auto& t : tf->transforms)
        if (t.child_frame_id == sensor) base_T_sensor = tf2::transformToEigen(t);
  return base_T_sensor;
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
