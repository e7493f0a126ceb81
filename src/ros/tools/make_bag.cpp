// make_bag: turns a scenario YAML (bags/*.yaml) into a ROS 1 bag, deterministically.
//
//   make_bag SCENARIO.yaml -o OUT.bag [--duration-scale S] [--root DIR] [--compression C]
//
// Topics: the LiDAR's cloud as its driver publishes it (lidar_cloud_writer.h; VLP-16:
// velodyne_points, XYZIRT, frame velodyne, 10 Hz; OS1-64: ouster/points; XT32: hesai/pandar),
// odom (nav_msgs/Odometry, odom -> base_link, 50 Hz), tf (odom -> base_link), tf_static
// (base_link -> the sensor's frames, latched), ground_truth/pose (geometry_msgs/PoseStamped in
// bim, 50 Hz).
// Scans in `sensor.dropouts` windows are missing; a `kidnap` makes ground_truth/pose jump while
// odom holds its pose.
// The simulation is the ROS-free core (is_graphs/sim); this file only converts its outputs to
// messages. The bag is written to OUT.bag.tmp and renamed when complete. Errors go to stderr,
// naming the YAML field; exit status 2.
#include <geometry_msgs/PoseStamped.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_msgs/TFMessage.h>

#include <Eigen/Geometry>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

#include "is_graphs/sim/scenario_yaml.h"
#include "is_graphs/sim/simulation.h"
#include "is_graphs/sim/simulation_runner.h"
#include "lidar_cloud_writer.h"

namespace {

using is_graphs::sim::LidarScan;
using is_graphs::sim::OdometrySample;

struct Args {
  std::string scenario, output, root, compression{"none"};
  double duration_scale{1.0};
  bool quiet{false};
};

int Usage(const std::string& error) {
  std::cerr << "make_bag: " << error << "\n"
            << "usage: make_bag SCENARIO.yaml -o OUT.bag [--duration-scale S] [--root DIR]\n"
            << "                [--compression none|lz4|bz2] [--quiet]\n"
            << "  --duration-scale S  multiply the scenario's duration by S\n"
            << "  --root DIR          repository root for a relative `building` path\n"
            << "                      (default: the parent of the YAML's folder)\n"
            << "  --compression C     rosbag chunk compression (default none)\n";
  return 2;
}

std::string ParentDir(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? "." : (slash == 0 ? "/" : path.substr(0, slash));
}

geometry_msgs::Transform ToTransform(const Eigen::Isometry3d& pose) {
  geometry_msgs::Transform t;
  const Eigen::Quaterniond q(pose.linear());
  t.translation.x = pose.translation().x();
  t.translation.y = pose.translation().y();
  t.translation.z = pose.translation().z();
  t.rotation.x = q.x();
  t.rotation.y = q.y();
  t.rotation.z = q.z();
  t.rotation.w = q.w();
  return t;
}

geometry_msgs::Pose ToPose(const Eigen::Isometry3d& pose) {
  const geometry_msgs::Transform t = ToTransform(pose);
  geometry_msgs::Pose p;
  p.position.x = t.translation.x;
  p.position.y = t.translation.y;
  p.position.z = t.translation.z;
  p.orientation = t.rotation;
  return p;
}

nav_msgs::Odometry ToOdometry(const OdometrySample& s, const ros::Time& stamp) {
  nav_msgs::Odometry odom;
  odom.header.stamp = stamp;
  odom.header.frame_id = "odom";
  odom.child_frame_id = "base_link";
  odom.pose.pose = ToPose(s.odom_T_base);
  const double floor = 1e-6;  // keeps the matrices positive definite at the start
  const double pose_var[6] = {s.variance_xy + floor, s.variance_xy + floor, 1e-4, 1e-4, 1e-4,
                              s.variance_yaw + floor};
  const double twist_var[6] = {1e-3, 1e-3, 1e-3, 1e-3, 1e-3, 1e-3};
  for (int i = 0; i < 6; ++i) {
    odom.pose.covariance[i * 7] = pose_var[i];
    odom.twist.covariance[i * 7] = twist_var[i];
  }
  odom.twist.twist.linear.x = s.linear_velocity.x();
  odom.twist.twist.linear.y = s.linear_velocity.y();
  odom.twist.twist.linear.z = s.linear_velocity.z();
  odom.twist.twist.angular.x = s.angular_velocity.x();
  odom.twist.twist.angular.y = s.angular_velocity.y();
  odom.twist.twist.angular.z = s.angular_velocity.z();
  return odom;
}

geometry_msgs::TransformStamped Stamped(const Eigen::Isometry3d& pose, const ros::Time& stamp,
                                        const std::string& parent, const std::string& child) {
  geometry_msgs::TransformStamped t;
  t.header.stamp = stamp;
  t.header.frame_id = parent;
  t.child_frame_id = child;
  t.transform = ToTransform(pose);
  return t;
}

// Writes the simulation's outputs as messages.
class BagSink : public is_graphs::sim::SimulationSink {
 public:
  BagSink(rosbag::Bag* bag, const is_graphs::sim::LidarModel& lidar, double t0)
      : bag_(bag),
        lidar_(lidar),
        topic_(is_graphs::sim_ros::DriverFor(lidar.config().model).topic),
        t0_(t0) {}

  void OnOdometry(double t, const Eigen::Isometry3d& truth, const OdometrySample& s) override {
    const ros::Time stamp(t0_ + t);
    geometry_msgs::PoseStamped gt;
    gt.header.stamp = stamp;
    gt.header.frame_id = "bim";
    gt.pose = ToPose(truth);
    bag_->write("ground_truth/pose", stamp, gt);
    bag_->write("odom", stamp, ToOdometry(s, stamp));
    tf2_msgs::TFMessage tf;
    tf.transforms.push_back(Stamped(s.odom_T_base, stamp, "odom", "base_link"));
    bag_->write("tf", stamp, tf);
  }

  void OnScan(const LidarScan& scan, double publish_time) override {
    bag_->write(topic_, ros::Time(t0_ + publish_time),
                is_graphs::sim_ros::ToCloud(scan, lidar_, ros::Time(t0_ + scan.stamp)));
  }

 private:
  rosbag::Bag* bag_;
  const is_graphs::sim::LidarModel& lidar_;
  std::string topic_;
  double t0_;
};

int Run(const Args& args) {
  const std::string root = args.root.empty() ? ParentDir(ParentDir(args.scenario)) : args.root;
  const auto config = is_graphs::sim::LoadScenarioYaml(args.scenario, root);
  if (!config.ok()) return std::cerr << "make_bag: " << config.error() << "\n", 2;
  const auto prepared = is_graphs::sim::PrepareSimulation(
      config.value(), is_graphs::sim::DefaultBimCacheDir(root), args.duration_scale);
  if (!prepared.ok()) {  // errors of a field (scene.clutter[2].room: ...) name its line
    std::ifstream in(args.scenario);
    std::stringstream text;
    text << in.rdbuf();
    return std::cerr << "make_bag: "
                     << is_graphs::sim::WithYamlLine(text.str(), args.scenario, prepared.error())
                     << "\n",
           2;
  }
  const is_graphs::sim::Simulation& sim = *prepared.value();
  if (!args.quiet) {
    for (const std::string& line : sim.log) std::cerr << "make_bag: " << line << "\n";
  }

  const std::string tmp = args.output + ".tmp";
  std::remove(tmp.c_str());
  try {
    rosbag::Bag bag(tmp, rosbag::bagmode::Write);
    if (args.compression == "lz4") bag.setCompression(rosbag::compression::LZ4);
    if (args.compression == "bz2") bag.setCompression(rosbag::compression::BZ2);
    const double t0 = sim.config.start_time;

    // tf_static once, latched (rosbag play re-publishes it latched).
    auto latched = boost::make_shared<ros::M_string>();
    (*latched)["callerid"] = "/make_bag";
    (*latched)["latching"] = "1";
    (*latched)["topic"] = "/tf_static";
    (*latched)["type"] = ros::message_traits::datatype<tf2_msgs::TFMessage>();
    (*latched)["md5sum"] = ros::message_traits::md5sum<tf2_msgs::TFMessage>();
    (*latched)["message_definition"] = ros::message_traits::definition<tf2_msgs::TFMessage>();
    tf2_msgs::TFMessage tf_static;
    const auto driver = is_graphs::sim_ros::DriverFor(sim.config.sensor.model);
    tf_static.transforms.push_back(
        Stamped(sim.base_T_mount, ros::Time(t0), "base_link", driver.mount_frame));
    if (driver.points_frame != driver.mount_frame)  // ouster-ros: os_sensor -> os_lidar
      tf_static.transforms.push_back(Stamped(sim.sensor->spec().mount_T_points, ros::Time(t0),
                                             driver.mount_frame, driver.points_frame));
    bag.write("tf_static", ros::Time(t0), tf_static, latched);

    BagSink sink(&bag, *sim.sensor, t0);
    const is_graphs::sim::RunStats stats = is_graphs::sim::RunSimulation(sim, sink);
    bag.close();
    if (!args.quiet) {
      std::cerr << "make_bag: " << stats.scans << " scans ("
                << stats.points / std::max(1, stats.scans) << " points each on average"
                << (stats.dropped_scans ? ", " + std::to_string(stats.dropped_scans) + " dropped"
                                        : std::string())
                << "), " << stats.odometry_samples << " odometry samples, " << sim.duration
                << " s\n";
    }
  } catch (const std::exception& e) {
    std::remove(tmp.c_str());
    std::cerr << "make_bag: " << args.output << ": cannot write the bag: " << e.what() << "\n";
    return 2;
  }
  if (std::rename(tmp.c_str(), args.output.c_str()) != 0) {
    std::remove(tmp.c_str());
    std::cerr << "make_bag: " << args.output << ": cannot rename " << tmp << ": "
              << std::strerror(errno) << "\n";
    return 2;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Args args;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> const char* { return i + 1 < argc ? argv[++i] : nullptr; };
    if (a == "-o" || a == "--output") {
      const char* v = value();
      if (!v) return Usage("-o: missing the output bag path");
      args.output = v;
    } else if (a == "--duration-scale") {
      const char* v = value();
      char* end = nullptr;
      if (!v || (args.duration_scale = std::strtod(v, &end), *end != '\0')) {
        return Usage("--duration-scale: must be a number");
      }
    } else if (a == "--root") {
      const char* v = value();
      if (!v) return Usage("--root: missing the directory");
      args.root = v;
    } else if (a == "--compression") {
      const char* v = value();
      if (!v || (std::string(v) != "none" && std::string(v) != "lz4" && std::string(v) != "bz2")) {
        return Usage("--compression: must be none, lz4 or bz2");
      }
      args.compression = v;
    } else if (a == "--quiet") {
      args.quiet = true;
    } else if (a == "-h" || a == "--help") {
      Usage("turns a scenario YAML into a ROS 1 bag");
      return 0;
    } else if (!a.empty() && a[0] == '-') {
      return Usage("unknown option " + a);
    } else if (args.scenario.empty()) {
      args.scenario = a;
    } else {
      return Usage("more than one scenario given");
    }
  }
  if (args.scenario.empty()) return Usage("missing the scenario YAML");
  if (args.output.empty()) return Usage("-o: missing the output bag path");
  return Run(args);
}
