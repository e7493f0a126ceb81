// bench_sgraph: feeds the S-Graph core from a bag without ROS transport (rosbag C++ API) and
// prints per-scan latency, optimization time against keyframes, the real-time factor and the
// peak RSS; with --building, also the quality against the bag's ground truth and the BIM.
//
//   bench_sgraph BAG [--building FILE.ifc|.agraph.json] [--storey S] [--keyframe-distance M]
//                    [--min-plane-points N] [--max-iterations N] [--max-solver-time S]
//                    [--wall-normal-cell M] [--wall-normal-max-angle-deg A] [--explain-plane ID]
//                    [--cloud-layout auto|velodyne|ouster|hesai|robosense|xyzi]
//
// Quality: APE after evo's alignment (Umeyama SE(3), no scale) and after the gravity-aware one
// (yaw + translation: both frames are z-up); planes and rooms are compared after the latter.
// Planes lying on a door, window, stair, railing or piece of furniture of the building's mesh
// (not on a wall) are counted and listed apart: the A-Graph has no surface for them.
// --explain-plane lists each observation of a plane in the BIM frame (debugging a bad plane).
//
// Optimizations run synchronously after each keyframe here (the node runs them on a worker
// thread): scan latency excludes them, the real-time factor includes them.
#include <geometry_msgs/PoseStamped.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_eigen/tf2_eigen.h>
#include <tf2_msgs/TFMessage.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>

#include "../lidar_conversions.h"
#include "../pose_conversions.h"
#include "bag_replay.h"
#include "is_graphs/agraph/agraph_queries.h"
#include "is_graphs/agraph/ifc_conversion.h"
#include "is_graphs/geometry/triangle_mesh.h"
#include "is_graphs/pipeline/evaluation.h"
#include "is_graphs/sgraph/evaluation.h"
#include "is_graphs/sgraph/plane_support.h"
#include "is_graphs/sgraph/sgraph_builder.h"

namespace {

using Clock = std::chrono::steady_clock;
using namespace is_graphs;

double Ms(Clock::duration d) { return std::chrono::duration<double, std::milli>(d).count(); }

using bag_replay::PeakRssKb;
using bag_replay::Percentile;

int Usage() {
  std::cerr << "usage: bench_sgraph BAG [--building FILE] [--storey S] [--keyframe-distance M]"
               " [--min-plane-points N] [--max-iterations N] [--max-solver-time S]"
               " [--wall-normal-cell M] [--wall-normal-max-angle-deg A] [--explain-plane ID]"
               " [--cloud-layout L]\n";
  return 2;
}

// Each observation of plane `id`: where the keyframe was (truth), the observed plane put in the
// BIM frame by the true keyframe pose (its own error, free of the estimate's) and by the estimate.
void ExplainPlane(const sgraph::SGraph& graph, int id, const Eigen::Isometry3d& bim_T_map,
                  const std::vector<sgraph::StampedPose>& truth) {
  const auto p = std::find_if(graph.planes.begin(), graph.planes.end(),
                              [&](const sgraph::Plane& q) { return q.id == id; });
  if (p == graph.planes.end()) {
    std::printf("plane %d: not in the graph\n", id);
    return;
  }
  const geometry::Plane mapped = p->plane.Transformed(bim_T_map);
  const auto yaw = [](const Eigen::Vector3d& n) { return std::atan2(n.y(), n.x()) * 180.0 / M_PI; };
  std::printf("plane %d in BIM: normal yaw %.2f deg, d %.3f\n", id, yaw(mapped.normal), mapped.d);
  for (const auto& o : graph.observations) {
    if (o.plane != id) continue;
    const auto k = std::find_if(graph.keyframes.begin(), graph.keyframes.end(),
                                [&](const sgraph::Keyframe& q) { return q.id == o.keyframe; });
    const auto t = sgraph::TruthAt(truth, k->stamp);
    if (!t) continue;
    const geometry::Plane by_truth = o.local.Transformed(*t);
    const geometry::Plane by_est = o.local.Transformed(bim_T_map * k->pose);
    std::printf(
        "  kf %d at (%.2f, %.2f): by truth yaw %.2f d %.3f; by estimate yaw %.2f d %.3f; "
        "info diag %.3g %.3g %.3g\n",
        o.keyframe, t->translation().x(), t->translation().y(), yaw(by_truth.normal), by_truth.d,
        yaw(by_est.normal), by_est.d, o.information(0, 0), o.information(1, 1),
        o.information(2, 2));
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) return Usage();
  std::string bag_path = argv[1], building_path, storey;
  sgraph::FrontendConfig frontend;
  sgraph::BackendConfig backend;
  int min_plane_points_eval = 200;
  std::vector<int> explain;  // --explain-plane: plane ids whose observations are listed
  ros_conversions::LidarCloudConfig cloud_config;
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 >= argc) return Usage();
    if (a == "--building")
      building_path = argv[++i];
    else if (a == "--storey")
      storey = argv[++i];
    else if (a == "--keyframe-distance")
      frontend.keyframe_distance = std::stod(argv[++i]);
    else if (a == "--min-plane-points")
      min_plane_points_eval = std::stoi(argv[++i]);
    else if (a == "--max-iterations")
      backend.max_iterations = std::stoi(argv[++i]);
    else if (a == "--max-solver-time")
      backend.max_solver_time = std::stod(argv[++i]);
    else if (a == "--wall-normal-max-angle-deg")
      frontend.wall_normal_max_angle_deg = std::stod(argv[++i]);
    else if (a == "--wall-normal-cell")
      frontend.wall_normal_cell = std::stod(argv[++i]);
    else if (a == "--explain-plane")
      explain.push_back(std::stoi(argv[++i]));
    else if (a == "--cloud-layout") {
      if (!bag_replay::ParseCloudLayout(argv[++i], &cloud_config)) return Usage();
    } else
      return Usage();
  }
  if (const auto e = frontend.Validate(); !e.empty()) {
    std::cerr << "bench_sgraph: " << e << "\n";
    return 2;
  }
  rosbag::Bag bag;
  try {
    bag.open(bag_path, rosbag::bagmode::Read);
  } catch (const rosbag::BagException& e) {
    std::cerr << "bench_sgraph: " << bag_path << ": " << e.what() << "\n";
    return 2;
  }
  const bag_replay::StaticFrames static_frames(bag);
  ros_conversions::LidarCloudReader cloud_reader(cloud_config);
  sgraph::SGraphBuilder builder(frontend, backend);
  std::vector<double> scan_ms, keyframe_ms, optimize_ms;
  std::vector<std::pair<int, double>> optimize_at;
  std::vector<sgraph::StampedPose> truth;
  double first = -1.0, last = 0.0;
  const auto start = Clock::now();
  Clock::duration processing{0};
  rosbag::View view(bag, rosbag::TopicQuery(bag_replay::SensorTopics()));
  for (const auto& m : view) {
    const double t = m.getTime().toSec();
    if (first < 0.0) first = t;
    last = t;
    if (auto odom = m.instantiate<nav_msgs::Odometry>()) {
      const auto t0 = Clock::now();
      builder.AddOdometry(odom->header.stamp.toSec(), ros_conversions::FromPose(odom->pose.pose));
      processing += Clock::now() - t0;
    } else if (auto cloud = m.instantiate<sensor_msgs::PointCloud2>()) {
      const auto t0 = Clock::now();
      const auto scan = bag_replay::ReadCloud(cloud_reader, *cloud, "bench_sgraph");
      if (!scan.ok()) continue;
      const auto r = builder.AddScan(scan.value(), static_frames.BaseT(cloud->header.frame_id));
      const auto t1 = Clock::now();
      scan_ms.push_back(Ms(t1 - t0));
      if (r.status == sgraph::SGraphBuilder::ScanStatus::kKeyframe) {
        keyframe_ms.push_back(scan_ms.back());
        const auto summary = builder.Optimize();
        const double ms = Ms(Clock::now() - t1);
        optimize_ms.push_back(ms);
        optimize_at.emplace_back(summary.num_keyframes, ms);
      }
      processing += Clock::now() - t0;
    } else if (auto pose = m.instantiate<geometry_msgs::PoseStamped>()) {
      truth.push_back({pose->header.stamp.toSec(), ros_conversions::FromPose(pose->pose)});
    }
  }
  const double wall = std::chrono::duration<double>(Clock::now() - start).count();
  const double bag_seconds = last - first;
  const sgraph::SGraph graph = builder.Snapshot();
  std::printf("bag: %s (%.1f s)\n", bag_path.c_str(), bag_seconds);
  std::printf("scans: %zu, keyframes: %zu, planes: %zu, observations: %zu, rooms: %zu\n",
              scan_ms.size(), graph.keyframes.size(), graph.planes.size(),
              graph.observations.size(), graph.rooms.size());
  std::printf(
      "per-scan latency [ms]: median %.2f, p99 %.2f, max %.2f (keyframe scans: median %.2f, p99 "
      "%.2f)\n",
      Percentile(scan_ms, 0.5), Percentile(scan_ms, 0.99), Percentile(scan_ms, 1.0),
      Percentile(keyframe_ms, 0.5), Percentile(keyframe_ms, 0.99));
  std::printf("optimization [ms]: median %.1f, max %.1f; by keyframes:",
              Percentile(optimize_ms, 0.5), Percentile(optimize_ms, 1.0));
  for (size_t i = 0; i < optimize_at.size(); ++i)
    if (i + 1 == optimize_at.size() || (i + 1) % std::max<size_t>(1, optimize_at.size() / 6) == 0)
      std::printf(" %d:%.1f", optimize_at[i].first, optimize_at[i].second);
  std::printf("\nreal-time factor: %.1fx (processing only %.1fx), wall %.1f s\n",
              bag_seconds / wall, bag_seconds / std::chrono::duration<double>(processing).count(),
              wall);
  std::printf("peak RSS: %.1f MiB\n", PeakRssKb() / 1024.0);

  if (building_path.empty()) return 0;
  auto loaded = agraph::LoadBim(building_path);
  if (!loaded.ok()) {
    std::cerr << "bench_sgraph: " << loaded.error() << "\n";
    return 1;
  }
  agraph::AGraph building = loaded.value();
  if (!storey.empty()) {
    auto s = agraph::SelectStorey(building, storey);
    if (s.ok()) building = s.value();
  }
  const auto traj = sgraph::EvaluateTrajectory(graph, truth);
  const Eigen::Vector3d tilted = traj.bim_T_map.linear() * Eigen::Vector3d::UnitZ();
  std::printf(
      "trajectory APE RMSE (%d keyframes): SE(3)-aligned S-Graph %.3f m, odometry %.3f m "
      "(alignment tilt %.2f deg); yaw-aligned S-Graph %.3f m, odometry %.3f m\n",
      traj.keyframes, traj.sgraph_rmse, traj.odom_rmse,
      std::acos(std::min(1.0, tilted.z())) * 180.0 / M_PI, traj.sgraph_rmse_gravity,
      traj.odom_rmse_gravity);
  const Eigen::Isometry3d& bim_T_map = traj.bim_T_map_gravity;
  {
    // The S-Graph alone (no BIM in its optimization): its map cloud put in B by the yaw-aligned
    // fit of its keyframes to the truth, against the wall-surfaces (the paper's map RMSE).
    std::vector<Eigen::Vector3f> cloud = builder.MapCloud(0.1);
    const Eigen::Isometry3f b_T_m = bim_T_map.cast<float>();
    for (auto& p : cloud) p = b_T_m * p;
    const auto e = pipeline::CloudAgainstWallSurfaces(cloud, building);
    std::printf(
        "map cloud vs BIM wall-surfaces (S-Graph alone, yaw-aligned to the truth): RMSE %.3f m, "
        "median %.3f m (%d of %d points)\n",
        e.rmse, e.median, e.used, e.points);
  }
  std::optional<geometry::TriangleMesh> mesh;
  if (!building.mesh.empty()) {
    auto m = geometry::LoadObj(building.mesh);
    if (m.ok()) mesh = std::move(m.value());
  }
  const auto planes = sgraph::EvaluatePlanes(graph, building, bim_T_map, min_plane_points_eval);
  int matched = 0, good = 0, others = 0;
  std::vector<double> dist, ang;
  std::string off;    // the wall planes outside 5 cm / 1 deg, one line each
  std::string other;  // the planes on other elements, one line each
  for (const auto& p : planes) {
    if (p.surface < 0) continue;
    const auto it = std::find_if(graph.planes.begin(), graph.planes.end(),
                                 [&](const sgraph::Plane& q) { return q.id == p.plane; });
    const std::string cls = mesh ? sgraph::PlaneSupportClass(*it, bim_T_map, *mesh, 0.04) : "";
    const Eigen::Vector3d a = bim_T_map * Eigen::Vector3d(it->start.x(), it->start.y(), 0.0);
    const Eigen::Vector3d b = bim_T_map * Eigen::Vector3d(it->end.x(), it->end.y(), 0.0);
    char line[256];
    std::snprintf(line, sizeof(line),
                  "  plane %d (%d points, z %.2f..%.2f) from (%.2f, %.2f) to (%.2f, %.2f) near "
                  "surface %d: %.3f m, %.2f deg (on %s)\n",
                  p.plane, it->num_points, it->z_min, it->z_max, a.x(), a.y(), b.x(), b.y(),
                  p.surface, p.distance, p.angle_deg, cls.empty() ? "-" : cls.c_str());
    // On a door, window, stair, railing or furniture of the mesh (not on a wall): the A-Graph
    // has no surface for it. Planes on nothing of the mesh (clutter, a wall moved on site) count.
    if (!cls.empty() && cls.rfind("IfcWall", 0) != 0) {
      ++others;
      other += line;
      continue;
    }
    ++matched;
    dist.push_back(p.distance);
    ang.push_back(p.angle_deg);
    if (p.distance <= 0.05 && p.angle_deg <= 1.0) {
      ++good;
      continue;
    }
    off += line;
  }
  std::printf(
      "wall planes (>= %d points): %zu, on other elements: %d, on a BIM wall-surface: %d, "
      "within 5 cm and 1 deg: %d; distance median %.3f max %.3f m, angle median %.2f "
      "max %.2f deg\n",
      min_plane_points_eval, planes.size(), others, matched, good, Percentile(dist, 0.5),
      Percentile(dist, 1.0), Percentile(ang, 0.5), Percentile(ang, 1.0));
  std::printf("%s", off.c_str());
  if (others > 0)
    std::printf("on other elements (doors, windows, stairs, furniture):\n%s", other.c_str());
  for (int id : explain) ExplainPlane(graph, id, bim_T_map, truth);
  const auto rooms = sgraph::EvaluateRooms(graph, building, truth, bim_T_map);
  std::printf(
      "rooms: walked through %d, found %d, detected %d, false %d (of which duplicates %d)\n",
      rooms.walked, rooms.found, rooms.detected, rooms.false_rooms, rooms.duplicates);
  for (const auto& v : rooms.verdicts) {  // each S-room: where it lies, what it counts as
    const auto it = std::find_if(graph.rooms.begin(), graph.rooms.end(),
                                 [&](const sgraph::Room& r) { return r.id == v.room; });
    std::string planes;
    for (int id : it->planes) planes += (planes.empty() ? "" : ",") + std::to_string(id);
    const char* kind = v.kind == sgraph::RoomVerdict::Kind::kFound       ? "found"
                       : v.kind == sgraph::RoomVerdict::Kind::kDuplicate ? "DUPLICATE"
                                                                         : "OUTSIDE";
    std::printf("  room %d (%s, %zu keyframes, planes %s): centre (%.2f, %.2f) in '%s': %s\n",
                v.room, it->type == sgraph::RoomType::kCorridor ? "corridor" : "room",
                it->keyframes.size(), planes.c_str(), v.center_bim.x(), v.center_bim.y(),
                v.a_room >= 0 ? building.rooms[v.a_room].name.c_str() : "-", kind);
  }
  return 0;
}
